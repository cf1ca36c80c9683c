"""Paper B's printed equations against the sympy derivation from its energies (2)-(6)."""

import sys

import pytest
import sympy as sp

import rotorvib.methods.symbolic as symbolic
from rotorvib.papers.b.derivation import checks

SIMPLIFIED = []   # (caller, whether the result is 0) of every simplify made by the checks


@pytest.fixture(scope="module")
def table():
    full = sp.simplify

    def recorded(expr, *args, **kwargs):
        result = full(expr, *args, **kwargs)
        SIMPLIFIED.append((sys._getframe(1).f_code.co_name, result == 0))
        return result

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(symbolic.sp, "simplify", recorded)
        return {(c.equation, c.description): c for c in checks()}


def _status(table, equation, start):
    rows = [c for (eq, desc), c in table.items() if eq == equation and desc.startswith(start)]
    assert len(rows) == 1, (equation, start)
    return rows[0]


@pytest.mark.parametrize("equation", ["(7)", "(8)", "(9), ball 1", "(9), ball 2"])
def test_printed_equations_hold_under_the_printed_convention_only(table, equation):
    assert _status(table, equation, "as printed vs Lagrange with Phi = w t, w'' t dropped").passed
    exact = _status(table, equation, "as printed vs Lagrange with Phi = w t exactly")
    assert not exact.passed and "Derivative(omega(t), (t, 2))" in exact.difference
    assert not _status(table, equation, "as printed (rates w + w' t, 2 w')").passed
    assert _status(table, equation, "printed form with Phi' = w").passed
    assert _status(table, equation, "as printed vs consistent kinematics at constant").passed


def test_mass_matrix_14_has_sign_errors_in_the_cosine_entries(table):
    row = _status(table, "(14)", "mass matrix")
    assert not row.passed
    assert row.difference.count("cos(") == 4 and "[0," not in row.difference


def test_equilibria_and_linearisation(table):
    for eq in ("(16)", "(17)", "(33)", "(34)", "(24)"):
        assert all(c.passed for (e, _), c in table.items() if e == eq), eq
    assert _status(table, "(23)", "C*, columns r' and psi', balanced state").passed
    any_r = _status(table, "(23)", "C*, columns r' and psi' (the legible ones), any r*")
    assert not any_r.passed and "r_star" in any_r.difference


def test_every_zero_difference_is_settled_without_simplify(table):
    """Expansion and the trigonometric normal form prove every PASS row; ``simplify`` (slow)
    is reached only by the leftovers of FAIL rows, to shorten what they print."""
    reduced = [zero for caller, zero in SIMPLIFIED if caller == "_reduce"]
    assert reduced and not any(reduced)
