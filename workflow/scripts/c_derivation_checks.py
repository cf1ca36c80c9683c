"""Rule c_derivation_checks: paper C's printed equations checked symbolically (sympy)."""

import sys

from rotorvib.derivation import write_checks
from rotorvib.dva.derivation import checks

sys.stderr = open(snakemake.log[0], "w", buffering=1)
rows = checks()
write_checks(rows, snakemake.output.csv, snakemake.output.md)
print(f"{len(rows)} equations checked, {sum(not r.passed for r in rows)} FAIL", file=sys.stderr)
