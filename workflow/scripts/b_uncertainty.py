"""Rule b_uncertainty: Sobol indices and bands of Table 2's optimum row (beyond paper B)."""

import sys

from rotorvib.io.datasets import Provenance, job_config, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.uncertainty import uncertainty_dataset

sys.stderr = open(snakemake.log[0], "w", buffering=1)
use_threads(snakemake.threads)
p = snakemake.params
u, t2 = p.uncertainty, p.table2
ds = uncertainty_dataset(Setup.from_config(**p.setup), ranges=u["ranges"], design=t2["cases"][-1],
                         eps_bar=t2["eps_bar"], phi0_deg=p.ics[t2["ic"]], speed=t2["speed"],
                         kinematics=p.kinematics, n_base=u["n_base"],
                         convergence=u["convergence"], resamples=u["resamples"], seed=u["seed"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p), u["seed"]))
