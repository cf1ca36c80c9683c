"""Rule a_slow_flow: the small-mu slow flow's stability boundary against the exact one."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.io.coords import grid
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.studies import slow_flow_dataset

job.start(snakemake.log[0])
p = snakemake.params
axes = {k: grid(p.flow[k]) for k in ("beta", "omega")}
ds = slow_flow_dataset(p.case["mu"], p.case["rho"], p.case["zeta"], axes["beta"], axes["omega"])
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
