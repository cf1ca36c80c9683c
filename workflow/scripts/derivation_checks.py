"""Rules *_derivation_checks: a paper's printed equations checked symbolically (sympy)."""

from rotorvib.pipeline import job  # first: the imports below run without the cyclic GC

import importlib
import sys

from rotorvib.methods.symbolic import write_checks

module = importlib.import_module(snakemake.params.module)  # sympy's imports too
job.start(snakemake.log[0])
rows = module.checks()
write_checks(rows, snakemake.output.csv, snakemake.output.md)
print(f"{len(rows)} equations checked, {sum(not r.passed for r in rows)} FAIL", file=sys.stderr)
