"""The reduced workflow under two OpenBLAS kernels, compared: do the results depend on the
processor's BLAS kernel?

    python -m benchmarks.kernels [KERNEL KERNEL] [--reuse]

runs ``snakemake -j2`` on the reduced configuration twice, into ``results/kernels/<kernel>``,
with ``OPENBLAS_CORETYPE`` set to each kernel (default ``SkylakeX`` and ``Haswell``; ``Zen``
and ``Prescott`` are others), then compares what they wrote:

- the comparison, row by row: the verdict, and every text the reader sees (the explanation,
  the alternatives, the margin as printed), which carries each number to its printed digits:
  these must be identical;
- its numbers (reproduced value, margin and its uncertainty), relative difference;
- every dataset, variable by variable: the largest difference relative to the variable's
  scale (its largest magnitude), per dataset.

It prints the comparison and writes it to ``benchmarks/records/kernels.json``; it exits 1 when a
verdict or a printed text differs.  ``--reuse`` compares the runs already there.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from benchmarks.reduced import run_reduced
from rotorvib.comparison.table import margin_text

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "benchmarks/records/kernels.json"
#: The comparison's texts a reader sees; with the verdict, each must be the same under both.
TEXTS = ("verdict", "explanation", "alternatives")
NUMBERS = ("reproduced", "margin", "uncertainty")


def comparison_rows(results: Path) -> dict[tuple[str, str], dict]:
    with open(results / "comparison.csv", newline="", encoding="utf-8") as f:
        return {(r["paper"], r["quantity"]): r for r in csv.DictReader(f)}


def relative(a: np.ndarray, b: np.ndarray) -> float:
    """Largest ``|a - b|`` relative to the larger magnitude of ``a``; NaN where both are
    NaN counts as equal, a NaN on one side only as infinitely different."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape:
        return float("inf")
    finite = np.isfinite(a) & np.isfinite(b)
    if not np.array_equal(a[~finite], b[~finite], equal_nan=True):
        return float("inf")
    scale = float(np.max(np.abs(a[finite]), initial=0.0))
    diff = float(np.max(np.abs(a[finite] - b[finite]), initial=0.0))
    return diff / scale if scale else diff


def compare_comparison(first: Path, second: Path) -> dict:
    """Rows whose verdict or printed text differs, and each number's largest relative
    difference (with its row)."""
    one, two = comparison_rows(first), comparison_rows(second)
    differing = sorted(f"{p} {q}" for (p, q), r in one.items()
                       if (p, q) not in two or any(r[k] != two[(p, q)][k] for k in TEXTS)
                       or margin_text(r) != margin_text(two[(p, q)]))
    largest = {}
    for column in NUMBERS:
        gaps = [(relative([float(r[column])], [float(two[key][column])]), f"{key[0]} {key[1]}")
                for key, r in one.items() if key in two and r[column] not in ("", None)
                and _number(r[column]) and _number(two[key][column])]
        gap, row = max(gaps, default=(0.0, ""))
        largest[column] = {"relative": gap, "row": row}
    return {"rows": len(one), "differing_rows": differing, "largest": largest}


def _number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def compare_datasets(first: Path, second: Path) -> dict[str, dict]:
    """Per dataset: its variables' largest relative difference and the variable."""
    out = {}
    for path in sorted(first.glob("paper_*/datasets/*.nc")):
        name = str(path.relative_to(first))
        with xr.open_dataset(path) as a, xr.open_dataset(second / name) as b:
            gaps = [(relative(a[v].values, b[v].values), v) for v in a.data_vars
                    if np.issubdtype(a[v].dtype, np.number)]
        gap, variable = max(gaps, default=(0.0, ""))
        out[name] = {"relative": gap, "variable": variable,
                     "variables_above_1e-9": {v: g for g, v in sorted(gaps) if g > 1e-9}}
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("kernels", nargs="*", default=["SkylakeX", "Haswell"])
    parser.add_argument("--reuse", action="store_true", help="compare the runs already there")
    args = parser.parse_args(argv)
    if len(args.kernels) != 2 or args.kernels[0] == args.kernels[1]:
        parser.error("give two different kernels, e.g. SkylakeX Haswell")
    os.chdir(ROOT)                 # the configuration's results folder is the repository's
    folder = Path("results/kernels")
    if not args.reuse:
        for kernel in args.kernels:
            run = run_reduced(folder, kernel, ["-j2"],
                              env={**os.environ, "OPENBLAS_CORETYPE": kernel})
            print(f"{kernel}: {run.wall:.0f} s wall, {run.cpu:.0f} CPU-s", flush=True)
    first, second = (folder / k for k in args.kernels)
    record = {"kernels": args.kernels, "comparison": compare_comparison(first, second),
              "datasets": compare_datasets(first, second)}
    RECORD.write_text(json.dumps(record, indent=1) + "\n")
    c = record["comparison"]
    print(f"comparison: {c['rows']} rows, {len(c['differing_rows'])} whose verdict or printed "
          f"text differs {c['differing_rows']}")
    for column, gap in c["largest"].items():
        print(f"  {column}: largest relative difference {gap['relative']:.1e} ({gap['row']})")
    for name, gap in record["datasets"].items():
        above = ", ".join(f"{v} {g:.0e}" for v, g in gap["variables_above_1e-9"].items())
        print(f"{name}: {gap['relative']:.1e} ({gap['variable']})"
              + (f"; above 1e-9: {above}" if above else ""))
    return 1 if c["differing_rows"] else 0


if __name__ == "__main__":
    sys.exit(main())
