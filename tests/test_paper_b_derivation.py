"""Paper B's printed equations against the sympy derivation from its energies (2)-(6)."""

import pytest
import sympy as sp

import rotorvib.methods.symbolic as symbolic
from rotorvib.papers.b.derivation import checks

SHORTENED = []   # (leftover, its shortened form) of every FAIL row's difference


@pytest.fixture(scope="module")
def table():
    plain = symbolic.shortened

    def recorded(expr):
        result = plain(expr)
        SHORTENED.append((expr, result))
        return result

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(symbolic, "shortened", recorded)
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


def test_every_zero_difference_is_settled_by_the_normal_form(table):
    """Expansion and the trigonometric normal form prove every PASS row: the shortening (which
    only rewrites) sees only leftovers that are not 0 in the normal form, from the FAIL rows."""
    assert SHORTENED
    assert all(symbolic.trig_normal_form(leftover) != 0 for leftover, _ in SHORTENED)
    assert len(SHORTENED) <= sum(c.difference.count("]: ") or 1
                                 for c in table.values() if not c.passed)


def test_a_shortened_leftover_equals_the_leftover(table):
    """Each shortened FAIL leftover is the leftover itself: their difference, expanded with
    the trigonometric functions of sums expanded, is 0 in the normal form; and it is shorter,
    the printed rates' leftover of (7) by a factor of more than five."""
    assert SHORTENED
    for leftover, short in SHORTENED:
        assert short != 0
        assert symbolic.trig_normal_form(sp.expand(sp.expand_trig(short - leftover))) == 0
        assert sp.count_ops(short) <= sp.count_ops(leftover)
    rates = table[("(7)", "as printed (rates w + w' t, 2 w') vs Lagrange with the consistent "
                          "Phi' = w")].difference
    assert "cos(Phi(t) + phi1(t) - theta(t))" in rates and len(rates) < 700
