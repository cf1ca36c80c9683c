"""The symbolic comparison of printed equations (rotorvib.methods.symbolic)."""

import numpy as np
import sympy as sp

from rotorvib.methods.symbolic import compare, trig_normal_form

a, b, x, r = sp.symbols("a b x r", real=True)


def _at_random_points(expr, other, n=5):
    rng = np.random.default_rng(3)
    free = sorted(expr.free_symbols | other.free_symbols, key=str)
    f, g = sp.lambdify(free, expr), sp.lambdify(free, other)
    points = rng.uniform(-3, 3, size=(n, len(free)))
    return np.array([f(*p) for p in points]), np.array([g(*p) for p in points])


def test_the_normal_form_proves_pythagorean_identities_of_expanded_sums():
    for identity in (sp.sin(a + b) ** 2 + sp.cos(a + b) ** 2 - 1,
                     sp.cos(x) ** 4 - sp.sin(x) ** 4 - sp.cos(2 * x),
                     sp.sin(a - b) * sp.cos(a + b) - (sp.sin(2 * a) - sp.sin(2 * b)) / 2):
        expanded = sp.expand(sp.expand_trig(identity))
        assert expanded != 0 and trig_normal_form(expanded) == 0


def test_the_normal_form_keeps_the_value_and_does_not_zero_a_non_identity():
    for expr in (sp.sin(x) ** 2 - sp.cos(x) ** 2, a * sp.cos(b) ** 5 + sp.cos(a) ** 3 * sp.sin(b)):
        normal = trig_normal_form(expr)
        assert normal != 0 and not normal.has(sp.cos(x) ** 2)
        np.testing.assert_allclose(*_at_random_points(expr, normal), rtol=1e-12, atol=1e-12)


def test_compare_finds_the_scale_of_a_printed_equation_through_trigonometric_identities():
    xdd = sp.Function("q")(sp.Symbol("t")).diff(sp.Symbol("t"), 2)
    derived = r * (sp.sin(a) ** 2 + sp.cos(a) ** 2) * xdd + r * sp.sin(a + b)
    printed = xdd + sp.sin(a) * sp.cos(b) + sp.cos(a) * sp.sin(b)
    check = compare("T", "(1)", "scaled", derived, printed, proportional_to=xdd)
    assert check.passed and check.difference == "0 (printed = derived / r)"
    wrong = compare("T", "(1)", "scaled", derived, printed + sp.cos(a) ** 2, proportional_to=xdd)
    assert not wrong.passed and wrong.difference == "-cos(a)**2"
