"""Symbolic checking of printed equations (sympy): Lagrange's equations and a PASS/FAIL table.

Every paper's derivation module produces :class:`Check` rows; :func:`write_checks` writes them as
CSV and Markdown in one format for all papers.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import sympy as sp
from sympy.simplify.fu import TR10i

from rotorvib.io.tables import write_table


@dataclass(frozen=True)
class Check:
    """One printed equation checked against the derivation."""

    paper: str
    equation: str
    description: str
    passed: bool
    difference: str = "0"

    @property
    def status(self) -> str:
        return "PASS" if self.passed else "FAIL"


def lagrange_equations(T, V, coords, t, forces) -> list[sp.Expr]:
    """``d/dt dL/dq' - dL/dq - Q`` for each generalised coordinate ``q(t)`` with ``L = T - V``."""
    L = T - V
    return [sp.expand(sp.diff(sp.diff(L, q.diff(t)), t) - sp.diff(L, q) - Q)
            for q, Q in zip(coords, forces)]


def trig_normal_form(expr, of=sp.cos):
    """``expr`` expanded with every ``cos(x)**n`` (``n >= 2``) written as
    ``(1 - sin(x)**2)**(n // 2) * cos(x)**(n % 2)`` (with ``of=sp.sin``, the mirror image: every
    ``sin(x)**n`` lowered through ``1 - cos(x)**2``).

    For a polynomial in the sines and cosines of independent arguments this is its remainder
    modulo the identities ``sin(x)**2 + cos(x)**2 = 1`` (each a Groebner basis element in its
    own two variables), a canonical form: it is 0 exactly when the polynomial vanishes
    identically.  A zero result is therefore a proof that ``expr`` is 0, at the cost of one
    expansion; a non-zero one proves nothing when the arguments are related."""
    other = sp.sin if of is sp.cos else sp.cos

    def is_power(e):
        return e.is_Pow and isinstance(e.base, of) and e.exp.is_Integer and e.exp >= 2

    def lowered(e):
        n = int(e.exp)
        return (1 - other(e.base.args[0]) ** 2) ** (n // 2) * e.base ** (n % 2)

    return sp.expand(expr.replace(is_power, lowered))


def shortened(expr):
    """A non-zero leftover in a short form for a FAIL row to print: :func:`trig_normal_form`
    (the Pythagorean terms that cancel go), the common factors taken out, the products of sines
    and cosines contracted to sines and cosines of sums (``cos a cos b - sin a sin b ->
    cos(a + b)``, sympy's ``fu.TR10i``) and the common factors taken out again; of the forms
    with cosine powers and with sine powers lowered, the one with fewer operations, then the
    shorter text (``-cos(a)**2``, not ``sin(a)**2 - 1``).  Each step is an identity, so the
    result equals ``expr`` (tested).  On the leftovers of papers B and C it gives full
    ``simplify``'s forms at about a fiftieth of its time, and it also shortens the two of over
    300 operations that ``simplify`` was too slow for (printed rates in (7)-(8))."""
    return min((sp.factor_terms(TR10i(sp.factor_terms(trig_normal_form(expr, of))))
                for of in (sp.cos, sp.sin)), key=lambda e: (sp.count_ops(e), len(sp.sstr(e))))


def _reduce(expr):
    """Bring a difference to zero if it is one: expansion with the trigonometric functions of
    sums expanded, then :func:`trig_normal_form`, settle every zero of papers B and C (tested);
    a leftover that is neither is :func:`shortened` where that makes it shorter."""
    original = sp.expand(expr)
    if original == 0:
        return original
    expr = sp.expand(sp.expand_trig(original))
    if expr == 0 or trig_normal_form(expr) == 0:
        return sp.Integer(0)
    expr = shortened(expr)
    return expr if sp.count_ops(expr) < sp.count_ops(original) else original


def compare(paper: str, equation: str, description: str, derived, printed, *,
            proportional_to=None) -> Check:
    """PASS when ``derived - s * printed`` simplifies to zero.

    With ``proportional_to`` (a term such as ``u''``) the scale ``s`` is the ratio of the two
    coefficients of that term (a printed equation may be the derived one divided by a constant),
    each in :func:`trig_normal_form`, cancelled; otherwise ``s = 1``.  The difference is
    reported in the printed equation's scale.
    """
    derived, printed = sp.expand(derived), sp.expand(printed)
    scale = sp.Integer(1)
    if proportional_to is not None:
        scale = sp.cancel(trig_normal_form(derived.coeff(proportional_to))
                          / trig_normal_form(printed.coeff(proportional_to)))
    diff = _reduce(derived / scale - printed)
    text = "0" if diff == 0 else sp.sstr(sp.factor(diff))
    if scale != 1 and diff == 0:
        text = f"0 (printed = derived / {scale})"
    return Check(paper, equation, description, diff == 0, text)


def compare_matrices(paper: str, equation: str, description: str, derived: sp.Matrix,
                     printed: sp.Matrix) -> Check:
    """A :class:`Check` that ``derived - printed`` simplifies to the zero matrix; its detail
    lists every entry that does not."""
    diff = (derived - printed).applyfunc(_reduce)
    bad = [f"[{i},{j}]: {sp.sstr(diff[i, j])}" for i in range(diff.rows)
           for j in range(diff.cols) if diff[i, j] != 0]
    return Check(paper, equation, description, not bad, "; ".join(bad) or "0")


def write_checks(checks: list[Check], csv_path: str | Path, md_path: str | Path) -> None:
    """Write the PASS/FAIL table of printed equations as CSV and Markdown."""
    n_fail = sum(not c.passed for c in checks)
    rows = [{"paper": c.paper, "equation": c.equation, "check": c.description,
             "status": c.status, "difference": c.difference} for c in checks]
    write_table(rows, csv_path, md_path, title="Printed equations checked symbolically",
                notes=[f"{len(checks)} checks, {len(checks) - n_fail} PASS, {n_fail} FAIL."])
