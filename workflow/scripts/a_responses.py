"""Rule a_responses: paper A's responses by Runge-Kutta and multiple scales (Figs 2-6)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import sys

from rotorvib.methods.multiple_scales import ConstantsDiverged
from rotorvib.pipeline.job import job_config
from rotorvib.io.datasets import Provenance, write_dataset
from rotorvib.papers.a.responses import responses_dataset

job.start(snakemake.log[0])
p = snakemake.params
betas = sorted({p.case["beta"], *p.betas})
try:
    ds = responses_dataset(p.case, p.offset, betas, p.tau_end, p.tau_step, p.rk)
except ConstantsDiverged as error:   # found by tests/schema_fuzz.py: an offset too far out
    sys.exit(f"config key 'paper_a.initial_offset': {error}, under paper_a.case and "
             "paper_a.fig5_6.betas; a smaller offset brings the two-term constants (eq. 39) "
             "within the expansion's reach (how small depends on the case)")
write_dataset(ds, snakemake.output[0], Provenance(snakemake.rule, job_config(p)))
