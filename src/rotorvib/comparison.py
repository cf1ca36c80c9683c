"""Side-by-side comparison of the papers' stated values with the reproduced ones.

Every value a paper states lives in ``data/paper_values.csv``.  Each paper's pipeline writes the
reproduced values (``paper, quantity, reproduced, explanation``); this module joins the two and
assigns a verdict: MATCH (relative error <= 1 %), MINOR (<= 10 %), MAJOR (> 10 %), or QUALITATIVE
for claims without a number, whose explanation says whether the data support the claim.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

from rotorvib.io.tables import write_table

COLUMNS = ("paper", "item", "quantity", "unit", "paper_value", "reproduced", "rel_error",
           "verdict", "explanation")
MATCH_TOL = 0.01
MINOR_TOL = 0.10


@dataclass(frozen=True)
class Reproduced:
    """One reproduced quantity, as written by a paper's comparison-values script."""

    paper: str
    quantity: str
    reproduced: float | None
    explanation: str

    @classmethod
    def of(cls, paper: str, quantity: str, value, explanation: str) -> "Reproduced":
        """A row with ``value`` as float (None for a qualitative claim)."""
        return cls(paper, quantity, None if value is None else float(value), explanation)


def supported(ok: bool) -> str:
    """The opening word of a qualitative row's explanation."""
    return "supported" if ok else "not supported"


def verdict(paper_value: float | None, reproduced: float | None) -> tuple[float | None, str]:
    """Return ``(relative error, verdict)``; ``paper_value=None`` marks a qualitative claim."""
    if paper_value is None:
        return None, "QUALITATIVE"
    if reproduced is None or not math.isfinite(reproduced):
        raise ValueError("a quantitative paper value needs a finite reproduced value")
    if paper_value == 0.0:
        rel = abs(reproduced)
    else:
        rel = abs(reproduced - paper_value) / abs(paper_value)
    return rel, "MATCH" if rel <= MATCH_TOL else "MINOR" if rel <= MINOR_TOL else "MAJOR"


def _float_or_none(text: str) -> float | None:
    return float(text) if text.strip() else None


def read_paper_values(path: str | Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = [row for row in csv.DictReader(fh) if not row["paper"].startswith("#")]
    for row in rows:
        row["value"] = _float_or_none(row["value"])
    return rows


def read_reproduced(path: str | Path) -> list[Reproduced]:
    with open(path, newline="", encoding="utf-8") as fh:
        return [Reproduced(r["paper"], r["quantity"], _float_or_none(r["reproduced"]),
                           r["explanation"]) for r in csv.DictReader(fh)]


def write_reproduced(rows: list[Reproduced], path: str | Path) -> None:
    with open(path, "w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(["paper", "quantity", "reproduced", "explanation"])
        for r in rows:
            writer.writerow([r.paper, r.quantity, "" if r.reproduced is None else repr(r.reproduced),
                             r.explanation])


def build_table(paper_values: list[dict], reproduced: list[Reproduced]) -> list[dict]:
    """Join paper values and reproduced values; every paper value must be reproduced exactly once.

    Raises ``ValueError`` for a paper value nobody reproduced, a reproduced quantity the data
    file does not know, or a MINOR/MAJOR/QUALITATIVE row without an explanation.
    """
    by_key = {}
    for r in reproduced:
        key = (r.paper, r.quantity)
        if key in by_key:
            raise ValueError(f"quantity {key} reproduced twice")
        by_key[key] = r
    known = {(p["paper"], p["quantity"]) for p in paper_values}
    unknown = sorted(set(by_key) - known)
    if unknown:
        raise ValueError(f"reproduced quantities missing from the paper-values file: {unknown}")
    table = []
    for p in paper_values:
        key = (p["paper"], p["quantity"])
        if key not in by_key:
            raise ValueError(f"paper value {key} has no reproduced value")
        r = by_key[key]
        rel, verdict_ = verdict(p["value"], r.reproduced)
        if verdict_ != "MATCH" and not r.explanation.strip():
            raise ValueError(f"{key} is {verdict_} but has no explanation")
        table.append({"paper": p["paper"], "item": p["item"], "quantity": p["quantity"],
                      "unit": p["unit"], "paper_value": p["value"], "reproduced": r.reproduced,
                      "rel_error": rel, "verdict": verdict_, "explanation": r.explanation})
    return table


def paper_values_of(path: str | Path, paper: str) -> dict[str, float | None]:
    """``{quantity: value}`` of one paper from the paper-values file."""
    return {row["quantity"]: row["value"] for row in read_paper_values(path) if row["paper"] == paper}


def write_table_files(table: list[dict], csv_path: str | Path, md_path: str | Path) -> None:
    """``results/comparison.csv`` and ``.md``: the rows of :func:`build_table`."""
    counts = {}
    for row in table:
        counts[row["verdict"]] = counts.get(row["verdict"], 0) + 1
    notes = ["Verdicts: MATCH (relative error <= 1 %), MINOR (<= 10 %), MAJOR (> 10 %), "
             "QUALITATIVE (claim without a number; the explanation says whether the data "
             "support it).",
             "Totals: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))]

    def percent(row):
        return {} if row["rel_error"] is None else {"rel_error": f"{100 * row['rel_error']:.2f} %"}

    write_table([{k: row[k] for k in COLUMNS} for row in table], csv_path, md_path,
                title="Paper values against the reproduction", notes=notes, markdown_cells=percent)
