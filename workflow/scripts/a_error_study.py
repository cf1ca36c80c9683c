"""Rule a_error_study: error of the multiple-scales solutions against the initial distance."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

from rotorvib.pipeline.config import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.studies import error_study_dataset

job.start(snakemake.log[0])
p = snakemake.params
ds = error_study_dataset(p.case, p.offset, p.study["deltas"], p.study["tau_end"], p.tau_step, p.rk)
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
