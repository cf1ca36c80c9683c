"""Rule b_forces: bearing forces of Table 2's rows against the race radius R (calibration)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.io.coords import grid
from rotorvib.pipeline.shards import run_balancer_study
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import force_dataset

job.start(snakemake.log[0])
p = snakemake.params
t2, cal = p.table2, p.calibration["R"]
R_values = np.union1d(grid(cal), [p.setup["machine"]["R"]])
setup = Setup.from_config(**p.setup)
run_balancer_study(
    snakemake, setup,
    lambda runs: force_dataset(setup, kinematics=p.kinematics, cases=t2["cases"],
                               R_values=R_values, speed=t2["speed"], eps_bar=t2["eps_bar"],
                               phi0_deg=p.ics[t2["ic"]], runs=runs),
    study="forces")
