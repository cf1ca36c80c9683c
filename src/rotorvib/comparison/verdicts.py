"""The verdicts of the comparison of the papers' stated values with the reproduced ones.

Every value a paper states lives in ``data/paper_values.csv`` with its ``source``: ``printed``,
``chosen`` (the paper prints none; the reproduction's choice) or ``theory`` (e.g. an error
order, or a claim of the reproduction's own beyond the papers, counted apart).  Each paper's
pipeline writes the reproduced values (:mod:`rotorvib.comparison.reproduced`); the
comparison (:mod:`rotorvib.comparison.table`) joins the two and assigns a verdict (this
module):

* a printed number: MATCH (relative error <= 1 %), MINOR (<= 10 %), MAJOR (> 10 %); where the
  paper's own other numbers imply a value (``implied``) more than 10 % from the printed one,
  the row is judged against the implied value (:func:`judged_against`): PAPER-INCONSISTENT
  where it agrees with it within 10 %, MAJOR otherwise;
* a number located only within an ``interval`` (an optimum on a grid whose neighbours lie
  within the curve's own roughness) that holds the paper's value is UNDETERMINED unless it is
  a MATCH or EXPECTED already; a number with no value (every run censored: NaN, never a
  penalty passed off as a number) is UNDETERMINED too;
* a chosen or theoretical value: EXPECTED (within 1 %) or UNEXPECTED, counted apart;
* a claim: from the variants it was evaluated under (kinematics, constructions, choices'
  alternatives) that decide it (:func:`claim_verdict`): SUPPORTED, NOT SUPPORTED, DEPENDS
  where they disagree (naming them), UNDETERMINED where none decides.  A claim carries its
  :class:`~rotorvib.comparison.reproduced.Margin` and the margin's uncertainty: a margin inside
  it decides nothing;
* a row whose paper value a calibration of the reproduction was fitted to (``calibrated``
  says which) is CALIBRATED, whatever it would be otherwise: counted apart, never as evidence.
"""

from __future__ import annotations

import math

MATCH_TOL = 0.01
MINOR_TOL = 0.10
#: The tolerances a number's verdict rests on, as its ``choices`` name them.
TOLERANCES_CHOSEN = (f"comparison.MATCH_TOL = {MATCH_TOL:g}, MINOR_TOL = {MINOR_TOL:g} (the "
                     "verdicts' relative tolerances)")
UNDETERMINED = "UNDETERMINED"
NUMERIC_VERDICTS = ("MATCH", "MINOR", "MAJOR", "PAPER-INCONSISTENT", UNDETERMINED)
EXPECTATION_VERDICTS = ("EXPECTED", "UNEXPECTED", UNDETERMINED)
CLAIM_VERDICTS = ("SUPPORTED", "NOT SUPPORTED", "DEPENDS", UNDETERMINED)
CALIBRATED = "CALIBRATED"
CLAIMS = "the papers' claims"
#: Claims of the reproduction's own beyond the papers (source ``theory``): findings, never
#: counted as the papers' claims.
HYPOTHESES = "hypotheses beyond the papers"
#: The kinds of row and their verdicts, as the totals count them.
VERDICT_GROUPS = (("printed numbers", NUMERIC_VERDICTS),
                  ("chosen or theoretical values", EXPECTATION_VERDICTS),
                  (CLAIMS, CLAIM_VERDICTS),
                  (HYPOTHESES, CLAIM_VERDICTS),
                  ("calibrated, not evidence", (CALIBRATED,)))


def relative_error(reference: float, value: float) -> float:
    """``|value - reference| / |reference|`` (``|value|`` for a zero reference)."""
    return abs(value) if reference == 0.0 else abs(value - reference) / abs(reference)


def claim_verdict(holds) -> str:
    """The verdict of the variants that decide (a variant that cannot, its margin inside its
    uncertainty, adds nothing either way): SUPPORTED where all of them hold, NOT SUPPORTED
    where all fail, DEPENDS where they disagree; UNDETERMINED where none decides. Symmetric:
    exchanging holds and fails exchanges SUPPORTED and NOT SUPPORTED and leaves the others."""
    if not holds:
        raise ValueError("a claim needs at least one evaluated variant")
    decided = {h for _, h in holds if h is not None}
    if len(decided) != 1:
        return "DEPENDS" if decided else UNDETERMINED
    return "SUPPORTED" if True in decided else "NOT SUPPORTED"


def judged_against(paper_value: float, implied: float | None) -> float:
    """The value a number is judged against: the ``implied`` one where it lies more than
    :data:`MINOR_TOL` from the printed one (the paper contradicts itself), else the printed."""
    if implied is not None and relative_error(implied, paper_value) > MINOR_TOL:
        return implied
    return paper_value


def verdict(paper_value: float | None, reproduced: float | None, *, source: str = "printed",
            holds=(), implied: float | None = None,
            interval: tuple[float, float] | None = None,
            calibrated: str = "") -> tuple[float | None, str]:
    """Return ``(relative error, verdict)`` (module docstring); ``paper_value=None`` marks a
    claim, judged by ``holds``. The relative error is to the value the row is judged against:
    the implied one where the paper contradicts itself."""
    if calibrated:
        rel = (None if paper_value is None or reproduced is None
               else relative_error(paper_value, reproduced))
        return rel, CALIBRATED
    if paper_value is None:
        return None, claim_verdict(holds)
    if reproduced is None or not math.isfinite(reproduced):
        return None, UNDETERMINED       # no number to compare (e.g. every run censored)
    if judged_against(paper_value, implied) != paper_value:
        rel = relative_error(implied, reproduced)
        return rel, "PAPER-INCONSISTENT" if rel <= MINOR_TOL else "MAJOR"
    rel = relative_error(paper_value, reproduced)
    if source != "printed":
        found = "EXPECTED" if rel <= MATCH_TOL else "UNEXPECTED"
    else:
        found = "MATCH" if rel <= MATCH_TOL else "MINOR" if rel <= MINOR_TOL else "MAJOR"
    if found not in ("MATCH", "EXPECTED") and interval is not None and \
            interval[0] <= paper_value <= interval[1]:
        return rel, UNDETERMINED
    return rel, found


def describe_holds(holds) -> str:
    """``"holds under printed; not under consistent"`` for a claim evaluated under variants."""
    named = [(k, h) for k, h in holds if k]
    if not named:
        return ""
    groups = {h: [k for k, v in named if v is h] for h in (True, False, None)}
    parts = [f"{label} {', '.join(groups[h])}" for h, label in
             ((True, "holds under"), (False, "not under"), (None, "undetermined under"))
             if groups[h]]
    return "; ".join(parts)


def group_of(row: dict) -> str:
    """The verdict group (:data:`VERDICT_GROUPS`) of a comparison row: a calibrated row apart;
    a claim has no paper value, and is the paper's (printed) or a hypothesis of the
    reproduction's own; a number is printed, or chosen or theoretical."""
    if row.get("verdict") == CALIBRATED:
        return VERDICT_GROUPS[-1][0]
    if row["paper_value"] in (None, ""):
        return CLAIMS if row["source"] == "printed" else HYPOTHESES
    return "printed numbers" if row["source"] == "printed" else "chosen or theoretical values"


def totals(table: list[dict]) -> list[str]:
    """Verdict counts of rows and of distinct findings
    (:func:`~rotorvib.comparison.table.with_findings`) in the groups of
    :data:`VERDICT_GROUPS` (a number's UNDETERMINED, nothing to compare, is named only where
    there is one), e.g. ``"MATCH 20 (6 findings)"``."""
    lines = []
    for name, verdicts in VERDICT_GROUPS:
        group = [row for row in table if group_of(row) == name]
        found = {v: {r["finding"] for r in group if r["verdict"] == v} for v in verdicts}
        counts = {v: sum(r["verdict"] == v for r in group) for v in verdicts}
        shown = [v for v in verdicts if v != UNDETERMINED or verdicts is CLAIM_VERDICTS
                 or counts[v]]
        rows = f"{len(group)} row{'' if len(group) == 1 else 's'}"
        lines.append(f"{name} ({rows}, {_findings(set().union(*found.values()))}): "
                     + ", ".join(f"{v} {counts[v]}" + (f" ({_findings(found[v])})"
                                                      if counts[v] else "") for v in shown))
    return lines


def _findings(ids: set) -> str:
    return f"{len(ids)} finding{'' if len(ids) == 1 else 's'}"


def verdict_definitions() -> str:
    """The verdicts in words, with the tolerances this module applies."""
    return (f"Verdicts. Printed numbers: MATCH (relative error <= {100 * MATCH_TOL:g} %), MINOR "
            f"(<= {100 * MINOR_TOL:g} %), MAJOR (> {100 * MINOR_TOL:g} %), PAPER-INCONSISTENT (the paper's "
            "own numbers imply another value, which the reproduction agrees with). Values the "
            "paper does not print (source chosen or theory): EXPECTED (<= "
            f"{100 * MATCH_TOL:g} %) or UNEXPECTED, counted apart. Claims: SUPPORTED, NOT SUPPORTED, "
            "DEPENDS (the variants that decide disagree; the explanation names them), "
            "UNDETERMINED (no variant decides); a variant that cannot decide counts neither way; "
            "the reproduction's own hypotheses beyond the papers are counted apart from the "
            "papers' claims. Each claim names the choices it rests on and the alternatives it "
            "was evaluated under, and carries its margin (positive where it holds) and the "
            "margin's uncertainty; a margin inside its uncertainty decides nothing. A number "
            "with nothing to compare (every run censored) is UNDETERMINED. A row whose paper "
            "value a calibration was fitted to is CALIBRATED, counted apart, never evidence.")
