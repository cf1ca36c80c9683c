"""Side-by-side comparison of the papers' stated values with the reproduced ones.

Every value a paper states lives in ``data/paper_values.csv`` with its ``source``: ``printed``,
``chosen`` (the paper prints none; the reproduction's choice) or ``theory`` (e.g. an error
order, or a claim of the reproduction's own beyond the papers, counted apart).  Each paper's
pipeline writes the reproduced values; this module joins the two and assigns a verdict:

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
  :class:`Margin` and the margin's uncertainty: a margin inside it decides nothing;
* a row whose paper value a calibration of the reproduction was fitted to (``calibrated``
  says which) is CALIBRATED, whatever it would be otherwise: counted apart, never as evidence.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

from rotorvib.comparison.choices import CHOICE_SEPARATOR, alternatives_text, choices_text, joined
from rotorvib.io.tables import write_table
from rotorvib.comparison.paper_values import paper_says

COLUMNS = ("paper", "item", "quantity", "unit", "source", "paper_value", "reproduced",
           "rel_error", "paper_says", "margin", "uncertainty", "margin_unit", "margin_basis",
           "verdict", "finding", "choices", "alternatives", "explanation")
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


@dataclass(frozen=True)
class Margin:
    """How far a claim is from failing, and how well that is known.

    ``value`` is positive where the claim holds and negative where it fails (in ``unit``, e.g.
    the relative amount by which one amplitude is below another); ``uncertainty`` >= 0 is the
    size of the noise of the quantity it is measured on, from ``basis`` (seed spread of a GA,
    the step of a grid, an integration tolerance, a bootstrap interval; 0 for exact arithmetic
    or counts).  The claim holds when ``value > uncertainty``, fails when ``value <
    -uncertainty`` and is undecided in between; with ``uncertainty == 0`` a margin of exactly
    0 holds (an inclusive bound, e.g. no grid point differs).  A NaN margin decides nothing
    (its uncertainty may be NaN too: a quantity with no value, e.g. every run censored); an
    infinite one decides by its sign."""

    value: float
    uncertainty: float
    unit: str
    basis: str

    def __post_init__(self):
        if not (self.uncertainty >= 0 or math.isnan(self.value) and math.isnan(self.uncertainty)):
            raise ValueError(f"a margin's uncertainty must be >= 0, not {self.uncertainty!r}")

    def holds(self) -> bool | None:
        """True, False, or None when the margin lies inside its uncertainty (or is NaN)."""
        v, u = float(self.value), float(self.uncertainty)
        if math.isnan(v) or (u > 0 and abs(v) <= u):
            return None
        return v >= 0 if u == 0 else v > 0


@dataclass(frozen=True)
class Reproduced:
    """One reproduced quantity, as written by a paper's comparison-values script.

    ``holds`` (claims only) pairs each variant the claim was evaluated under with whether it
    holds there (None: undetermined); ``variants`` (numbers only) pairs each other variant with
    its value; ``implied`` is the value the paper's own other numbers imply, when the paper
    states the quantity twice; ``interval`` (numbers) the values the reproduction cannot tell
    from ``reproduced``; ``margin`` (claims) is the reproduction's :class:`Margin`;
    ``calibrated`` names the calibration fitted to the paper's value, where one was; ``cause``
    names the one cause several rows share, where their explanations differ in more than their
    numbers (the finding they make, :func:`with_findings`); ``choices`` the project's choices
    the row rests on, each as ``"key = value (why)"`` (a configuration key or a constant of
    this module): a tolerance, a parameter the paper does not give, a grid, a range's edge.
    Those evaluated under alternatives name them in ``holds`` (:func:`under_choice`)."""

    paper: str
    quantity: str
    reproduced: float | None
    explanation: str
    holds: tuple[tuple[str, bool | None], ...] = ()
    implied: float | None = None
    variants: tuple[tuple[str, float], ...] = ()
    margin: Margin | None = None
    interval: tuple[float, float] | None = None
    calibrated: str = ""
    cause: str = ""
    choices: tuple[str, ...] = ()

    def __post_init__(self):
        for choice in self.choices:
            if not choice.strip() or CHOICE_SEPARATOR in choice:
                raise ValueError(f"{self.quantity}: a choice must be a non-empty text without "
                                 f"{CHOICE_SEPARATOR!r}, not {choice!r}")

    @classmethod
    def of(cls, paper: str, quantity: str, value, explanation: str,
           implied: float | None = None,
           interval: tuple[float, float] | None = None, cause: str = "",
           choices: tuple[str, ...] = (), calibrated: str = "") -> "Reproduced":
        """A numeric row with ``value`` as float."""
        return cls(paper, quantity, float(value), explanation,
                   implied=None if implied is None else float(implied),
                   interval=None if interval is None else (float(interval[0]),
                                                            float(interval[1])),
                   calibrated=calibrated, cause=cause, choices=tuple(choices))

    @classmethod
    def claim(cls, paper: str, quantity: str, holds, explanation: str, *,
              choices: tuple[str, ...], calibrated: str = "") -> "Reproduced":
        """A claim row; ``holds`` is a :class:`Margin` (the claim holds as the margin decides),
        None (undecidable, e.g. for want of material the paper does not give) or a mapping
        variant -> Margin/None; ``choices`` (required: a claim states what it rests on, ``()``
        for a test of the paper's own numbers by exact or closed-form arithmetic) and
        ``calibrated`` as the class says."""
        pairs = tuple(holds.items()) if isinstance(holds, dict) else (("", holds),)
        for k, v in pairs:
            if not (v is None or isinstance(v, Margin)):
                raise TypeError(f"claim {quantity!r}: variant {k!r} needs a Margin or None, "
                                f"not {type(v).__name__}")
        return cls(paper, quantity, None, explanation,
                   holds=tuple((str(k), None if v is None else v.holds()) for k, v in pairs),
                   margin=pairs[0][1], calibrated=calibrated, choices=tuple(choices))


def within_band(ds, quantity: str, margin: tuple[float, float], points=None) -> Margin:
    """The :class:`Margin` of "a value lies within the band of an uncertainty study" from the
    study ``ds`` and ``(margin, uncertainty)`` of :func:`rotorvib.methods.bands.band_margin`,
    in the quantity's units; ``points``: the sample's size, where not the study's."""
    q = list(ds.quantity_name.values).index(quantity)
    n = ds.sizes["sample"] if points is None else points
    return Margin(*margin, str(ds.quantity_units.values[q]),
                  f"bootstrap of the band's edges over {n} samples")


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


def merge_variants(rows_by_variant: dict[str, list[Reproduced]],
                   choice: str) -> list[Reproduced]:
    """One row per quantity from rows evaluated under several variants (e.g. kinematics).

    The first variant is the reproduction: numeric rows keep its value and quote the others';
    claim rows hold under each variant (and each alternative of a choice evaluated within it,
    :func:`under_choice`) as that variant's row says, and quote each variant's explanation
    where it differs from the first. The variants are a choice too, ``choice`` (e.g.
    ``"paper_b.kinematics = printed (...)"``), which leads every merged row's choices."""
    (first, rows), *others = rows_by_variant.items()
    other = {name: {r.quantity: r for r in rs} for name, rs in others}
    merged = []
    for row in rows:
        alt = {name: by_quantity[row.quantity] for name, by_quantity in other.items()}
        if row.reproduced is not None:
            quoted = "".join(f"; {name}: {r.reproduced:.4g}" for name, r in alt.items())
            merged.append(Reproduced(row.paper, row.quantity, row.reproduced,
                                     row.explanation + quoted, implied=row.implied,
                                     variants=tuple((n, r.reproduced) for n, r in alt.items()),
                                     interval=row.interval, cause=row.cause,
                                     calibrated=row.calibrated, choices=(choice, *row.choices)))
            continue
        holds = tuple((joined(name, k), h) for name, r in (((first, row),) + tuple(alt.items()))
                      for k, h in r.holds)
        text = f"{first}: {row.explanation}" + "".join(
            f" | {name}: {r.explanation}" for name, r in alt.items()
            if r.explanation != row.explanation)
        merged.append(Reproduced(row.paper, row.quantity, None, text, holds=holds,
                                 margin=row.margin, calibrated=row.calibrated, cause=row.cause,
                                 choices=(choice, *row.choices)))
    return merged


MARGIN_COLUMNS = ("margin", "uncertainty", "margin_unit", "margin_basis")


def build_table(paper_values: list[dict], reproduced: list[Reproduced]) -> list[dict]:
    """Join paper values and reproduced values; every paper value must be reproduced exactly once.

    Raises ``ValueError`` for a paper value nobody reproduced, a reproduced quantity the data
    file does not know, a row other than MATCH or EXPECTED without an explanation, or a claim
    decided without a :class:`Margin`.
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
    """Verdict counts of rows and of distinct findings (:func:`with_findings`) in the groups of
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
