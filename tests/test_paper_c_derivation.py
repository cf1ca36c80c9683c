"""Paper C's printed equations against a sympy derivation, and the numeric model against both."""

import numpy as np
import pytest
import sympy as sp

from rotorvib.models.absorber.frequency_response import matrices, theta_eq20
from rotorvib.models.absorber.parameters import dual_to_vector
from rotorvib.papers.c import derivation as d


@pytest.fixture(scope="module")
def checks():
    return d.checks()


def test_equations_of_motion_8_to_10_are_derived(checks):
    by_eq = {c.equation: c for c in checks if c.equation in ("(3)", "(8)", "(9)", "(10)")}
    assert all(c.passed for c in by_eq.values())
    assert "derived / 2" in by_eq["(9)"].difference


def test_only_the_printed_determinant_fails(checks):
    failed = [(c.equation, c.difference) for c in checks if not c.passed]
    assert failed[0] == ("det(A)", "-2*a13*a22*a31")
    assert [eq for eq, _ in failed] == ["det(A)", "(20)"]
    assert len(checks) == 14


def test_numeric_matrices_equal_the_symbolic_ones(rotor, table2):
    M, C, K = d.printed_matrices()
    s1, s2 = table2
    values = {d.J: rotor.J, d.kt: rotor.k_t, d.m1: s1.m, d.m2: s2.m, d.d1: s1.d, d.d2: s2.d,
              d.c1: s1.c, d.c2: s2.c, d.k1: s1.k, d.k2: s2.k}
    for sym, num in zip((M, C, K), matrices(rotor, table2)):
        np.testing.assert_allclose(np.array(sym.subs(values), dtype=float), num, rtol=1e-14)


def test_eq20_numeric_equals_symbolic_inverse(rotor, table2):
    s1, s2 = table2
    w = 0.93 * rotor.omega_n
    A = d.printed_A_entries().subs({d.J: rotor.J, d.kt: rotor.k_t, d.m1: s1.m, d.m2: s2.m,
                                    d.d1: s1.d, d.d2: s2.d, d.c1: s1.c, d.c2: s2.c, d.k1: s1.k,
                                    d.k2: s2.k, d.w: w})
    theta = complex(sp.N(A.inv()[0, 0] * rotor.Gamma0))
    assert theta_eq20(rotor, dual_to_vector(table2), w) == pytest.approx(theta, rel=1e-12)
