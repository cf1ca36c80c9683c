"""Rule b_table1_runs: balance time over ball mass for each operating speed (Table 1)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.models.balancer.simulate import use_threads
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import table1_dataset

job.start(snakemake.log[0])
use_threads(snakemake.threads)
p = snakemake.params
t1 = p.table1
masses = np.linspace(t1["mass"]["min"], t1["mass"]["max"], t1["mass"]["n"])
ds = table1_dataset(Setup.from_config(**p.setup), kinematics=p.kinematics, speeds=t1["speeds"],
                    ics=p.ics, beta=t1["beta"], eps_bar=t1["eps_bar"], masses=masses)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
