"""The project's choices a comparison row rests on, and the alternatives it is evaluated under.

A row of :mod:`rotorvib.comparison.table` names each choice it rests on as ``"key = value (why)"``
(a configuration key, or a constant of the comparison): a tolerance, a parameter the paper does
not give, a grid, a range's edge. :func:`under_choice` evaluates a claim at the used value and
at each declared alternative; :class:`Close` is the comparison's reading of "close" with its
alternatives. A verdict that flips between them is DEPENDS, naming the values.
"""

from __future__ import annotations

from dataclasses import dataclass

#: Between two choices of a row (a choice's own text never holds it).
CHOICE_SEPARATOR = " | "
#: Between the parts of one variant's name (a kinematics and a choice's value evaluated in it).
VARIANT_JOIN = " & "


def joined(variant: str, choice: str) -> str:
    """One variant's name with a choice's value evaluated within it (``"printed & c = 0.1"``)."""
    return f"{variant}{VARIANT_JOIN}{choice}" if choice else variant


def under_choice(evaluate, key: str, used, alternatives, unit: str = "") -> dict:
    """A claim evaluated with one of the project's choices at the value ``used`` and at each
    of ``alternatives``: ``{"key = value unit": evaluate(value)}``, the used value first (its
    margin is the row's). Passed as a claim's ``holds``, the verdict is DEPENDS, naming the
    values, where the choice decides it (:func:`rotorvib.comparison.verdicts.claim_verdict`)."""
    def name(value):
        said = f"{value:g}" if isinstance(value, (int, float)) else str(value)
        return f"{key} = {said}" + (f" {unit}" if unit else "")

    return {name(v): evaluate(v) for v in (used, *alternatives)}


@dataclass(frozen=True)
class Close:
    """The comparison's reading of "close", "near", "similar" (``comparison.close``, a relative
    difference) and the alternatives a claim on closeness is evaluated under as well
    (``comparison.close_alternatives``). Formats as its value (``f"{close:.0%}"``)."""

    value: float
    alternatives: tuple[float, ...] = ()

    KEY = "comparison.close"

    @classmethod
    def from_config(cls, comparison: dict) -> "Close":
        """From the ``comparison`` config section."""
        return cls(float(comparison["close"]),
                   tuple(float(v) for v in comparison.get("close_alternatives", ())))

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)

    def margins(self, evaluate, more=()) -> dict:
        """``evaluate(close)`` (a :class:`rotorvib.comparison.reproduced.Margin`) at the standard, its alternatives and
        ``more`` (:func:`under_choice`)."""
        return under_choice(evaluate, self.KEY, self.value, (*self.alternatives, *more))

    @property
    def choice(self) -> str:
        """The choice a claim on closeness rests on, for its ``choices``."""
        said = ", ".join(f"{v:g}" for v in self.alternatives)
        return (f"{self.KEY} = {self.value:g} (chosen: the papers' 'close'"
                + (f"; alternatives {said} evaluated)" if said else ")"))


#: What a claim that declares no choice rests on.
NO_CHOICE = "none: the paper's own numbers, exact or closed-form arithmetic"


def choices_text(row, tolerances: str) -> str:
    """The choices a row rests on, as the comparison CSV gives them: a claim's declared ones
    (:data:`NO_CHOICE` where it declares none); a number's, with the tolerances of its
    verdict."""
    if row.reproduced is None and row.calibrated == "" and not row.choices:
        return NO_CHOICE
    said = () if row.reproduced is None else (tolerances,)
    return CHOICE_SEPARATOR.join((*row.choices, *said))


def alternatives_text(row) -> str:
    """The alternatives a row was evaluated under, with what each gave: a claim's variants and
    whether it holds under each, a number's other variants and their values; empty where it
    was evaluated once."""
    if row.reproduced is not None:
        return "; ".join(f"{name}: {value:.4g}" for name, value in row.variants)
    named = [(k, h) for k, h in row.holds if k]
    return "; ".join(f"{k}: {_HOLDS_WORD[h]}" for k, h in named)


_HOLDS_WORD = {True: "holds", False: "fails", None: "undetermined"}
