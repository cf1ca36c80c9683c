"""A reproduced row as each paper's comparison-values script gives it (:class:`Reproduced`), a
claim's :class:`Margin`, and the rows of several variants merged into one
(:func:`merge_variants`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rotorvib.comparison.choices import CHOICE_SEPARATOR, joined


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
    numbers (the finding they make, :func:`~rotorvib.comparison.table.with_findings`);
    ``choices`` the project's choices the row rests on, each as ``"key = value (why)"`` (a
    configuration key or a constant of :mod:`rotorvib.comparison.verdicts`): a tolerance, a
    parameter the paper does not give, a grid, a range's edge. Those evaluated under
    alternatives name them in ``holds`` (:func:`~rotorvib.comparison.choices.under_choice`)."""

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


def merge_variants(rows_by_variant: dict[str, list[Reproduced]],
                   choice: str) -> list[Reproduced]:
    """One row per quantity from rows evaluated under several variants (e.g. kinematics).

    The first variant is the reproduction: numeric rows keep its value and quote the others';
    claim rows hold under each variant (and each alternative of a choice evaluated within it,
    :func:`~rotorvib.comparison.choices.under_choice`) as that variant's row says, and quote
    each variant's explanation where it differs from the first. The variants are a choice too,
    ``choice`` (e.g. ``"paper_b.kinematics = printed (...)"``), which leads every merged row's
    choices."""
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
