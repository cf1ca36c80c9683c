"""Rules *_derivation_checks: a paper's printed equations checked symbolically (sympy)."""

import importlib
import sys

from rotorvib.methods.symbolic import write_checks

sys.stderr = open(snakemake.log[0], "w", buffering=1)
rows = importlib.import_module(snakemake.params.module).checks()
write_checks(rows, snakemake.output.csv, snakemake.output.md)
print(f"{len(rows)} equations checked, {sum(not r.passed for r in rows)} FAIL", file=sys.stderr)
