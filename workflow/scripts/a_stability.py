"""Rule a_stability: paper A's Fig 7, stable region by multiple scales and by Lyapunov."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.studies import stability_region_dataset

job.start(snakemake.log[0])
p = snakemake.params
axes = {k: grid(p.fig7[k]) for k in ("beta", "omega")}
ds = stability_region_dataset(p.case["mu"], p.case["rho"], p.fig7["zetas"], axes["beta"],
                              axes["omega"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
