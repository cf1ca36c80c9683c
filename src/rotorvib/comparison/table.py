"""Side-by-side comparison of the papers' stated values with the reproduced ones: the table
(:func:`build_table`), each row with its verdict (:mod:`rotorvib.comparison.verdicts`) and
the finding it belongs to (:func:`with_findings`), written as ``results/comparison.csv`` and
``.md`` (:func:`write_table_files`)."""

from __future__ import annotations

import math
import re
from pathlib import Path

from rotorvib.comparison.choices import alternatives_text, choices_text
from rotorvib.comparison.paper_values import paper_says
from rotorvib.comparison.reproduced import MARGIN_COLUMNS, Margin, Reproduced
from rotorvib.comparison.verdicts import (CALIBRATED, TOLERANCES_CHOSEN, UNDETERMINED,
                                         describe_holds, judged_against, totals, verdict,
                                         verdict_definitions)
from rotorvib.io.tables import write_table

COLUMNS = ("paper", "item", "quantity", "unit", "source", "paper_value", "reproduced",
           "rel_error", "paper_says", "margin", "uncertainty", "margin_unit", "margin_basis",
           "verdict", "finding", "choices", "alternatives", "explanation")


def build_table(paper_values: list[dict], reproduced: list[Reproduced]) -> list[dict]:
    """Join paper values and reproduced values; every paper value must be reproduced exactly once.

    Raises ``ValueError`` for a paper value nobody reproduced, a reproduced quantity the data
    file does not know, a row other than MATCH or EXPECTED without an explanation, or a claim
    decided without a :class:`~rotorvib.comparison.reproduced.Margin`.
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
        rel, verdict_ = verdict(p["value"], r.reproduced, source=p["source"], holds=r.holds,
                                implied=r.implied, interval=r.interval,
                                calibrated=r.calibrated)
        if verdict_ not in ("MATCH", "EXPECTED") and not r.explanation.strip():
            raise ValueError(f"{key} is {verdict_} but has no explanation")
        if p["value"] is None and r.margin is None and verdict_ not in (UNDETERMINED,
                                                                          CALIBRATED):
            raise ValueError(f"claim {key} is {verdict_} but has no margin")
        explanation = r.explanation
        if r.calibrated:
            holds = describe_holds(r.holds)
            explanation = (f"not evidence: {r.calibrated}, so it agrees by construction; "
                           + (f"{holds}: " if holds else "") + explanation)
        elif judged_against(p["value"], r.implied) != p["value"]:
            explanation = (f"the paper prints {p['value']:g} but its own other numbers imply "
                           f"{r.implied:.4g}, against which the row is judged; {explanation}")
        elif verdict_ == UNDETERMINED and r.interval is not None:
            explanation = (f"the reproduction cannot tell {r.reproduced:.4g} from "
                           f"{r.interval[0]:.4g}-{r.interval[1]:.4g}, which holds the paper's "
                           f"{p['value']:g}; {explanation}")
        elif describe_holds(r.holds):
            explanation = f"{describe_holds(r.holds)}: {explanation}"
        table.append({"paper": p["paper"], "item": p["item"], "quantity": p["quantity"],
                      "unit": p["unit"], "source": p["source"], "paper_value": p["value"],
                      "reproduced": r.reproduced, "rel_error": rel, "verdict": verdict_,
                      "explanation": explanation, "paper_says": paper_says(p),
                      "cause": r.cause, "choices": choices_text(r, TOLERANCES_CHOSEN),
                      "alternatives": alternatives_text(r),
                      **dict(zip(MARGIN_COLUMNS, _margin_values(r.margin)))})
    return with_findings(table)


def _margin_values(margin: Margin | None) -> tuple:
    if margin is None:
        return None, None, "", ""
    return float(margin.value), float(margin.uncertainty), margin.unit, margin.basis


def margin_text(row: dict) -> str:
    """A comparison row's margin as text, e.g. ``"+0.12 +/- 0.01 (relative; grid step)"``; an
    infinite margin or uncertainty in words (``"without bound"``, e.g. a curve censored at one
    end), never as an infinity."""
    if row["margin"] is None or row["margin"] == "":
        return ""
    unit = f"{row['margin_unit']}; " if row["margin_unit"] else ""

    margin, spread = float(row["margin"]), float(row["uncertainty"])
    said = (f"{margin:+.3g}" if math.isfinite(margin) else "no value" if math.isnan(margin)
            else "without bound" if margin > 0 else "failing without bound")
    spread_said = (f"{spread:.2g}" if math.isfinite(spread) else "no value"
                   if math.isnan(spread) else "without bound")
    return f"{said} +/- {spread_said} ({unit}{row['margin_basis']})"


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def with_findings(table: list[dict]) -> list[dict]:
    """Each row with the finding it belongs to (``finding``: the paper's letter and a number
    in order of first appearance).  A finding is one cause: the rows of one paper with one
    verdict that name the same ``cause``, or, where a row names none, whose explanations are
    the same but for their numbers (the GA's optimum mass on its lower bound, for each of nine
    GAs, is one finding); a row without an explanation is a finding of its own."""
    ids: dict[tuple, str] = {}
    per_paper: dict[str, int] = {}
    rows = []
    for row in table:
        cause = row.get("cause") or _NUMBER.sub("#", row["explanation"]) or row["quantity"]
        key = (row["paper"], row["verdict"], cause)
        if key not in ids:
            per_paper[row["paper"]] = per_paper.get(row["paper"], 0) + 1
            ids[key] = f"{row['paper']}{per_paper[row['paper']]}"
        rows.append({**row, "finding": ids[key]})
    return rows


def write_table_files(table: list[dict], csv_path: str | Path, md_path: str | Path,
                      more_totals: tuple[str, ...] = ()) -> None:
    """``results/comparison.csv`` and ``.md``: the rows of :func:`build_table`, with the
    verdict totals and ``more_totals`` (e.g. of the discrepancy analysis) in the header."""
    notes = [verdict_definitions(),
             "Totals: " + "; ".join(totals(table) + list(more_totals))]

    def percent(row):
        return {} if row["rel_error"] is None else {"rel_error": f"{100 * row['rel_error']:.2f} %"}

    write_table([{k: row[k] for k in COLUMNS} for row in table], csv_path, md_path,
                title="Paper values against the reproduction", notes=notes, markdown_cells=percent)
