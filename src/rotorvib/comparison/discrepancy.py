"""Discrepancy analysis: which computed alternative reproduces a printed value, and what a stated
parameter would have to be to reproduce it.

For a printed value ``P`` of a quantity the reproduction computes as ``q``, a *hypothesis* is a
named alternative computation with its value ``q_h``; it *reproduces* ``P`` when
``|q_h - P| <= tol |P|`` (``tol`` = 1 %, the MATCH tolerance of
:mod:`rotorvib.comparison.verdicts`).
Kinds of hypothesis:

* ``definition``: another definition the paper leaves open (balance or decay criterion, envelope);
* ``variant``: another modelling variant (kinematics, construction, objective);
* ``parameter slip``: one stated parameter off by a decade or read in the wrong unit
  (:func:`parameter_slips`), everything else as stated;
* ``unit of the result``: the printed number is ``q`` in another unit (``q f`` for the
  conversion factors ``f`` of the quantity's unit);
* ``rounding``: ``q`` rounded to the printed number of decimals is ``P``.

The last two need no model and apply to every row (:func:`generic_hypotheses`).  *Inversion*
(:func:`invert`): for one parameter ``p`` over ``[a, b]``, the root of ``q(p) - P``, bracketed on
a scan and refined by Brent's method; a bracket across which ``q`` jumps (no ``p`` gives a value
within ``tol`` of ``P``) is reported as a jump, not as a root.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from rotorvib.comparison.verdicts import MATCH_TOL, judged_against, relative_error, verdict
from rotorvib.io.coords import label_coord, labels
from rotorvib.io.tables import write_table
from rotorvib.comparison.paper_values import decimals

KINDS = ("definition", "variant", "parameter slip", "unit of the result", "rounding")
REPRODUCES_WITHIN = MATCH_TOL
MISSES = ("MINOR", "MAJOR")

_DECADE = {"x 10": 10.0, "/ 10": 0.1}
#: Misreadings of a value in a unit: label -> factor applied to the stated value.
UNIT_SLIPS = {
    "m": {"read as cm": 0.01, "read as mm": 1e-3, "cm read as m": 100.0},
    "kg": {"read as g": 1e-3, "g read as kg": 1e3},
    "rad": {"degrees read as rad": math.pi / 180, "rad read as degrees": 180 / math.pi},
    "degree": {"rad read as degrees": math.pi / 180, "degrees read as rad": 180 / math.pi},
    "rad/s": {"Hz read as rad/s": 2 * math.pi, "rad/s read as Hz": 1 / (2 * math.pi)},
    "s": {"ms read as s": 1e-3},
}


@dataclass(frozen=True)
class Hypothesis:
    """The value of ``quantity`` under one named hypothesis (NaN: undefined there, e.g. the
    run never balances)."""

    quantity: str
    name: str
    kind: str
    value: float

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"hypothesis kind {self.kind!r} is not one of {KINDS}")


@dataclass(frozen=True)
class Inversion:
    """The value of ``parameter`` that reproduces the printed value of ``quantity``; ``needed``
    is NaN when no value in ``[lower, upper]`` does (``status`` says why)."""

    quantity: str
    parameter: str
    stated: float
    needed: float
    lower: float
    upper: float
    status: str  # "solved", "jump" or "none"

    def text(self) -> str:
        if self.status == "solved":
            return (f"needs {self.parameter} = {self.needed:.4g} "
                    f"({100 * (self.needed / self.stated - 1):+.0f} %)")
        if self.status == "jump":
            return (f"{self.parameter}: jumps across the printed value near {self.needed:.4g}, "
                    "no value reproduces it")
        return f"{self.parameter}: no value in [{self.lower:.3g}, {self.upper:.3g}]"


def reproduces(printed: float, value: float, tol: float = REPRODUCES_WITHIN) -> bool:
    """Whether ``value`` reproduces the ``printed`` number: finite and within ``tol`` relative
    error, ``|value - printed| <= tol |printed|``."""
    return bool(np.isfinite(value)) and relative_error(printed, value) <= tol


def misses(paper_values: list[dict], reproduced) -> dict[str, tuple[float, str]]:
    """``{quantity: (value judged against, verdict)}`` of the printed numbers the reproduction
    misses (MINOR or MAJOR in :func:`rotorvib.comparison.verdicts.verdict`): the printed value, or the
    one the paper's other numbers imply where it contradicts itself
    (:func:`rotorvib.comparison.verdicts.judged_against`), which the hypotheses must then reproduce."""
    printed = {p["quantity"]: p["value"] for p in paper_values
               if p["source"] == "printed" and p["value"] is not None}
    out = {}
    for r in reproduced:
        if r.quantity in printed and r.reproduced is not None:
            _, v = verdict(printed[r.quantity], r.reproduced, implied=r.implied,
                           interval=r.interval)
            if v in MISSES:
                out[r.quantity] = (judged_against(printed[r.quantity], r.implied), v)
    return out


def unit_factors(unit: str) -> dict[str, float]:
    """Decade slips and the misreadings of ``unit``: label -> factor."""
    return {**_DECADE, **UNIT_SLIPS.get(unit, {})}


def parameter_slips(name: str, unit: str, stated: float) -> list[tuple[str, float]]:
    """``[(label, slipped value)]`` for a stated parameter: off by a decade either way and
    misread in its unit."""
    return [(f"{name} {label}", stated * f) for label, f in unit_factors(unit).items()]


def generic_hypotheses(quantity: str, unit: str, printed_text: str,
                       reproduced: float) -> list[Hypothesis]:
    """The model-free hypotheses of a row: rounding to the printed decimals and the result
    misread in its unit (or off by a decade)."""
    n = decimals(printed_text)
    rows = [Hypothesis(quantity, f"rounded as printed ({n} decimal{'' if n == 1 else 's'})",
                       "rounding", float(round(reproduced, n)))]
    rows += [Hypothesis(quantity, f"reproduced x {f:.4g} ({label})", "unit of the result",
                        reproduced * f) for label, f in unit_factors(unit).items()]
    return rows


def invert(evaluate, target: float, stated: float, lower: float, upper: float, *,
           quantity: str, parameter: str, n_scan: int = 9,
           tol: float = REPRODUCES_WITHIN) -> Inversion:
    """The value of a parameter in ``[lower, upper]`` (both > 0, scanned on ``n_scan``
    log-spaced points) at which ``evaluate`` (array of parameter values -> array of quantity
    values, NaN allowed) equals ``target``; of several brackets, the one nearest ``stated``."""
    xs = np.geomspace(lower, upper, n_scan)
    gaps = np.asarray(evaluate(xs), float) - target
    brackets = [i for i in range(n_scan - 1) if np.isfinite(gaps[i]) and np.isfinite(gaps[i + 1])
                and (gaps[i] == 0 or np.sign(gaps[i]) != np.sign(gaps[i + 1]))]
    result = dict(quantity=quantity, parameter=parameter, stated=stated, lower=lower, upper=upper)
    if not brackets:
        return Inversion(needed=math.nan, status="none", **result)
    i = min(brackets, key=lambda j: abs(math.log(math.sqrt(xs[j] * xs[j + 1]) / stated)))
    if gaps[i] == 0:
        return Inversion(needed=float(xs[i]), status="solved", **result)

    def gap(x):
        value = float(np.asarray(evaluate(np.array([x])), float)[0]) - target
        if not math.isfinite(value):
            raise ValueError("undefined inside the bracket")
        return value

    from scipy.optimize import brentq  # here: the comparison and report jobs never invert

    try:
        root = brentq(gap, xs[i], xs[i + 1], xtol=1e-4 * xs[i], rtol=1e-4)
    except ValueError:
        return Inversion(needed=math.nan, status="none", **result)
    status = "solved" if abs(gap(root)) <= tol * abs(target) else "jump"
    return Inversion(needed=float(root), status=status, **result)


def _strings(dim: str, values, long_name: str):
    return (dim, np.array(values, dtype=str), {"long_name": long_name})


def to_dataset(baselines: dict[str, float], hypotheses: list[Hypothesis],
               inversions: list[Inversion], attrs: dict) -> xr.Dataset:
    """One paper's discrepancy analysis as a dataset: each analysed quantity's value under the
    stated parameters (``baseline``, the model's reproduction), every hypothesis and every
    inversion.  Values are in the unit of their quantity (``data/paper_values.csv``)."""
    same_unit = "in the unit of the quantity (data/paper_values.csv)"
    return xr.Dataset({
        "baseline": ("quantity", np.array(list(baselines.values()), float),
                     {"long_name": f"value under the stated parameters, {same_unit}",
                      "units": "1"}),
        "hypothesis_quantity": _strings("hypothesis", [h.quantity for h in hypotheses],
                                        "quantity the hypothesis is about"),
        "hypothesis_name": _strings("hypothesis", [h.name for h in hypotheses], "hypothesis"),
        "hypothesis_kind": _strings("hypothesis", [h.kind for h in hypotheses],
                                    f"kind of hypothesis, one of {', '.join(KINDS)}"),
        "hypothesis_value": ("hypothesis", np.array([h.value for h in hypotheses], float),
                             {"long_name": f"value under the hypothesis, {same_unit}",
                              "units": "1"}),
        **{f"inversion_{name}": _strings("inversion", [getattr(v, name) for v in inversions],
                                         long_name)
           for name, long_name in (("quantity", "quantity inverted for"),
                                   ("parameter", "parameter varied"),
                                   ("status", "solved, jump (no value within the tolerance) "
                                              "or none (no bracket in the range)"))},
        **{f"inversion_{name}": ("inversion", np.array([getattr(v, name) for v in inversions],
                                                       float),
                                 {"long_name": long_name, "units": "1"})
           for name, long_name in (("stated", "stated value of the parameter"),
                                   ("needed", "value that reproduces the printed number"),
                                   ("lower", "lower end of the range searched"),
                                   ("upper", "upper end of the range searched"))},
    }, coords=label_coord("quantity", list(baselines),
                          "analysed quantity (data/paper_values.csv)"), attrs=attrs)


def from_dataset(ds: xr.Dataset):
    """``(baselines, hypotheses, inversions)`` of :func:`to_dataset`."""
    baselines = dict(zip(labels(ds, "quantity"), map(float, ds.baseline.values)))
    hypotheses = [Hypothesis(str(q), str(n), str(k), float(v)) for q, n, k, v in zip(
        ds.hypothesis_quantity.values, ds.hypothesis_name.values, ds.hypothesis_kind.values,
        ds.hypothesis_value.values)]
    names = ("quantity", "parameter", "stated", "needed", "lower", "upper", "status")
    inversions = [Inversion(*(str(v) if isinstance(v, str) else float(v) for v in values))
                  for values in zip(*(ds[f"inversion_{n}"].values.tolist() for n in names))]
    return baselines, hypotheses, inversions


#: The model of a quantity must give the reproduction's own value within this (relative).
BASELINE_TOL = 1e-3


@dataclass(frozen=True)
class Analysis:
    """One printed number the reproduction misses, with every hypothesis and inversion;
    ``printed`` is the value it is judged against (the implied one where the paper contradicts
    itself, :func:`rotorvib.comparison.verdicts.judged_against`)."""

    paper: str
    quantity: str
    printed: float
    reproduced: float
    verdict: str
    hypotheses: tuple[Hypothesis, ...]
    inversions: tuple[Inversion, ...] = ()
    #: hypothesis name -> (missed numbers of the paper it reproduces, missed numbers tried on)
    support: tuple[tuple[str, int, int], ...] = ()

    @property
    def reproduced_by(self) -> list[Hypothesis]:
        return [h for h in self.hypotheses if reproduces(self.printed, h.value)]

    @property
    def closest(self) -> Hypothesis | None:
        """The hypothesis nearest the printed value (rounding aside: it only restates the
        reproduction)."""
        finite = [h for h in self.hypotheses if math.isfinite(h.value) and h.kind != "rounding"]
        return min(finite, key=lambda h: relative_error(self.printed, h.value), default=None)

    def text(self) -> str:
        """One sentence for the comparison row: what reproduces the printed value, or the
        closest of the hypotheses, and what single parameter change would."""
        n = len(self.hypotheses)
        hits = self.reproduced_by
        support = {name: (k, m) for name, k, m in self.support}

        def also(h):
            k, m = support.get(h.name, (1, 1))
            return f"; it reproduces {k} of the {m} missed numbers it was tried on" if m > 1 else ""

        if hits:
            named = "; ".join(f"{h.name} ({h.value:.4g}{also(h)})" for h in hits[:3])
            more = f" and {len(hits) - 3} more" if len(hits) > 3 else ""
            text = f"{len(hits)} of {n} hypotheses reproduce the printed value within 1 %: {named}{more}"
        else:
            c = self.closest
            text = (f"none of {n} hypotheses comes within 1 %" + (
                f"; closest: {c.name} gives {c.value:.4g} "
                f"({100 * relative_error(self.printed, c.value):.0f} % off)" if c else ""))
        solved = sorted((i for i in self.inversions if i.status == "solved"),
                        key=lambda i: abs(math.log(i.needed / i.stated)))
        if solved:
            text += "; a single parameter that would: " + ", ".join(i.text() for i in solved[:3])
        elif self.inversions:
            text += (f"; no single one of {len(self.inversions)} parameters within "
                     f"[{self.inversions[0].lower / self.inversions[0].stated:g}, "
                     f"{self.inversions[0].upper / self.inversions[0].stated:g}] x its stated "
                     "value reproduces it")
        return text


def analyse(table: list[dict], paper_values: list[dict], reproduced, datasets) -> list[Analysis]:
    """An :class:`Analysis` of every MINOR/MAJOR row of the comparison ``table``: the model-free
    hypotheses, the variants the reproduction quotes, and each paper's computed hypotheses and
    inversions (``datasets``: ``from_dataset`` triples).  Raises ``ValueError`` when a model's
    baseline differs from the reproduced value by more than :data:`BASELINE_TOL`."""
    text = {(p["paper"], p["quantity"]): p["value_text"] for p in paper_values}
    variants = {(r.paper, r.quantity): r.variants for r in reproduced}
    implied = {(r.paper, r.quantity): r.implied for r in reproduced}
    baselines, computed, inverted = {}, {}, {}
    for b, hyps, invs in datasets:
        baselines.update(b)
        for h in hyps:
            computed.setdefault(h.quantity, []).append(h)
        for i in invs:
            inverted.setdefault(i.quantity, []).append(i)
    out = []
    for row in table:
        if row["verdict"] not in MISSES:
            continue
        q, value = row["quantity"], row["reproduced"]
        if q in baselines and relative_error(value, baselines[q]) > BASELINE_TOL:
            raise ValueError(f"{q}: the discrepancy model gives {baselines[q]:.6g}, the "
                             f"reproduction {value:.6g}: the analysis would not be about it")
        own = computed.get(q, [])
        quoted = [] if any(h.kind == "variant" for h in own) else [
            Hypothesis(q, f"{name} variant", "variant", v)
            for name, v in variants.get((row["paper"], q), ())]
        hyps = generic_hypotheses(q, row["unit"], text[(row["paper"], q)], value) + own + quoted
        target = judged_against(row["paper_value"], implied.get((row["paper"], q)))
        out.append(Analysis(row["paper"], q, target, value, row["verdict"],
                            tuple(hyps), tuple(inverted.get(q, ()))))
    return [replace(a, support=_support(out, a.paper)) for a in out]


def _support(analyses: list[Analysis], paper: str) -> tuple[tuple[str, int, int], ...]:
    """For each model hypothesis of ``paper``: on how many of its missed numbers it reproduces
    the printed value, and on how many it was tried (a slip that explains one number and
    breaks the others is a coincidence, not a cause)."""
    counts: dict[str, list[int]] = {}
    for a in analyses:
        if a.paper != paper:
            continue
        for h in a.hypotheses:
            if h.kind in ("definition", "variant", "parameter slip"):
                c = counts.setdefault(h.name, [0, 0])
                c[0] += reproduces(a.printed, h.value)
                c[1] += 1
    return tuple((name, k, m) for name, (k, m) in counts.items())


def annotate(table: list[dict], analyses: list[Analysis]) -> list[dict]:
    """The comparison rows with each missed row's explanation followed by its analysis."""
    by_quantity = {(a.paper, a.quantity): a for a in analyses}
    return [{**row, "explanation": f"{row['explanation']}. Discrepancy analysis: "
             f"{by_quantity[row['paper'], row['quantity']].text()}"}
            if (row["paper"], row["quantity"]) in by_quantity else row for row in table]


def totals(analyses: list[Analysis]) -> str:
    """``"discrepancies (26): 9 reproduced by a hypothesis, 17 by none of their 12-45"``."""
    return _totals_text([(len(a.hypotheses), bool(a.reproduced_by)) for a in analyses])


def totals_of_rows(rows: list[dict]) -> str:
    """:func:`totals` from the rows of ``results/discrepancies.csv`` (:func:`table_rows`) read
    back as text; inversions are not hypotheses."""
    counts: dict[tuple[str, str], tuple[int, bool]] = {}
    for row in rows:
        key = (row["paper"], row["quantity"])
        n, hit = counts.get(key, (0, False))
        if row["kind"] != "inversion":
            n, hit = n + 1, hit or row["reproduces"] == "True"
        counts[key] = (n, hit)
    return _totals_text(list(counts.values()))


def _totals_text(counts: list[tuple[int, bool]]) -> str:
    """The totals sentence from (number of hypotheses, reproduced by one) per missed number."""
    hit = sum(1 for _, reproduced in counts if reproduced)
    missed = [n for n, reproduced in counts if not reproduced]
    text = f"discrepancies ({len(counts)}): {hit} reproduced by a hypothesis"
    if missed:
        text += (f", {len(missed)} ruled out (none of their {min(missed)}-{max(missed)} "
                 "hypotheses reproduces the printed value)")
    return text


TABLE_COLUMNS = ("paper", "quantity", "verdict", "printed", "kind", "hypothesis", "value",
                 "rel_error", "reproduces")


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def table_rows(analyses: list[Analysis]) -> list[dict]:
    """One row per hypothesis and per inversion (kind ``inversion``: ``value`` is the
    parameter value that reproduces the printed number); a value that does not exist (a
    hypothesis under which the quantity never comes, an inversion without a solution) is
    none, an empty cell."""
    rows = []
    for a in analyses:
        head = {"paper": a.paper, "quantity": a.quantity, "verdict": a.verdict,
                "printed": a.printed}
        rows += [{**head, "kind": h.kind, "hypothesis": h.name, "value": _finite(h.value),
                  "rel_error": relative_error(a.printed, h.value) if math.isfinite(h.value)
                  else None, "reproduces": reproduces(a.printed, h.value)}
                 for h in a.hypotheses]
        rows += [{**head, "kind": "inversion", "hypothesis": i.text(), "value": _finite(i.needed),
                  "rel_error": None, "reproduces": i.status == "solved"} for i in a.inversions]
    return rows


def write_files(analyses: list[Analysis], csv_path, md_path) -> None:
    """``results/discrepancies.{csv,md}``: the totals, one summary line per missed number and
    every hypothesis and inversion."""
    summary = ["| paper | quantity | verdict | printed | reproduced | analysis |",
               "|---|---|---|---|---|---|"] + [
        f"| {a.paper} | {a.quantity} | {a.verdict} | {a.printed:.4g} | {a.reproduced:.4g} | "
        f"{a.text()} |" for a in analyses]
    notes = [f"Totals: {totals(analyses)}. A hypothesis reproduces a printed value when it "
             "comes within 1 % of it; kinds: " + ", ".join(KINDS) + "; an inversion gives the "
             "value of one parameter that reproduces it, all others as stated.",
             "\n".join(summary), "## Every hypothesis and inversion"]

    def percent(row):
        return {} if row["rel_error"] is None else {"rel_error": f"{100 * row['rel_error']:.2f} %"}

    write_table(table_rows(analyses), csv_path, md_path,
                title="Discrepancies: what reproduces the printed numbers the reproduction misses",
                notes=notes, markdown_cells=percent)
