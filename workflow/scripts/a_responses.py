"""Rule a_responses: paper A's responses by Runge-Kutta and multiple scales (Figs 2-6)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.studies import responses_dataset

job.start(snakemake.log[0])
p = snakemake.params
betas = sorted({p.case["beta"], *p.betas})
ds = responses_dataset(p.case, p.offset, betas, p.tau_end, p.tau_step, p.rk)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
