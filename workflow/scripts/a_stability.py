"""Rule a_stability: paper A's Fig 7, stable region by multiple scales and by Lyapunov."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import numpy as np

from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.studies import stability_region_dataset

job.start(snakemake.log[0])
p = snakemake.params
grid = {k: np.linspace(p.fig7[k]["min"], p.fig7[k]["max"], p.fig7[k]["n"]) for k in ("beta", "omega")}
ds = stability_region_dataset(p.case["mu"], p.case["rho"], p.fig7["zetas"], grid["beta"],
                              grid["omega"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
