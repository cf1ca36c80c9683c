"""Rule a_error_study: error of the multiple-scales solutions against the initial distance."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import sys

from rotorvib.methods.multiple_scales import ConstantsDiverged
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.responses import error_study_dataset

job.start(snakemake.log[0])
p = snakemake.params
try:
    ds = error_study_dataset(p.case, p.offset, p.study["deltas"], p.study["tau_end"], p.tau_step,
                             p.rk)
except ConstantsDiverged as error:   # found by tests/schema_fuzz.py: a distance too far out
    sys.exit(f"config key 'paper_a.error_study.deltas': {error}, under paper_a.case; smaller "
             "distances bring the two-term constants (eq. 39) within the expansion's reach (how "
             "small depends on the case)")
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
