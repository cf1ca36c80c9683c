"""Stability of the balanced state: symbolic linearisation against the compiled right-hand
side, characteristic-polynomial coefficients, and the known limits."""

import numpy as np
import pytest
import sympy as sp

from rotorvib.models.balancer import engine, equations, stability
from rotorvib.models.balancer.parameters import Dimensionless, SpeedProfile, rotating_parameters

CASE = dict(mu=0.01, rho=1.0, zeta=0.05, beta=0.5, omega=2.0)


def finite_difference_jacobian(mu, rho, zeta, beta, omega, h=1e-7):
    d = Dimensionless(mu, rho, zeta, beta)
    p = rotating_parameters(d, SpeedProfile(omega, "constant"))
    a = d.balanced_angle()
    y = np.array([0.0, 0.0, a, -a, 0.0, 0.0, 0.0, 0.0])
    J = np.empty((8, 8))
    for j in range(8):
        plus, minus, fp, fm = y.copy(), y.copy(), np.empty(8), np.empty(8)
        plus[j] += h
        minus[j] -= h
        engine.rhs_rotating(0.0, plus, p, fp)
        engine.rhs_rotating(0.0, minus, p, fm)
        J[:, j] = (fp - fm) / (2 * h)
    return J


@pytest.mark.parametrize("case", [CASE, dict(mu=0.05, rho=0.7, zeta=0.2, beta=3.0, omega=1.3)])
def test_symbolic_linearisation_matches_compiled_rhs(case):
    J = stability.jacobian(**case)
    np.testing.assert_allclose(J, finite_difference_jacobian(**case), atol=1e-6)


def test_the_disk_phase_cancels_from_the_rotating_frame_equations():
    """Lagrange's equations carry no sin or cos of the phase W tau, and equal the expressions
    straight from the energies (phase and all) at random states, parameters and times."""
    phase = equations.OMEGA * equations.TAU
    q, eqs = equations.rotating_lagrange_equations()
    _, raw = equations.lagrange_expressions()
    assert not any(e.has(sp.sin(phase)) or e.has(sp.cos(phase)) for e in eqs)
    rng = np.random.default_rng(2)
    for _ in range(3):
        point = {sp.diff(f, equations.TAU, 2): rng.uniform(-1, 1) for f in q}
        point.update({sp.diff(f, equations.TAU): rng.uniform(-1, 1) for f in q})
        values = {f: rng.uniform(-3, 3) for f in q}
        params = dict(zip(equations.PARAMETERS, rng.uniform(0.05, 2.0, 5)))
        params[equations.TAU] = rng.uniform(0, 10)

        def at(e):
            return float(e.subs(point).subs(values).subs(params))

        for e, r in zip(eqs, raw):
            assert at(e) == pytest.approx(at(r), rel=1e-12, abs=1e-12)


def test_constant_term_changes_sign_at_rho_one_half():
    c0 = sp.factor(equations.characteristic_polynomial().coeff_monomial(1))
    assert sp.simplify(c0 - equations.OMEGA**8 * equations.MU**4 * (4 * equations.RHO**2 - 1)
                       / (4 * equations.RHO**4)) == 0
    values = [float(c0.subs({equations.MU: 0.01, equations.OMEGA: 2, equations.RHO: r}))
              for r in (0.49, 0.51)]
    assert values[0] < 0 < values[1]


def test_first_order_coefficient_changes_sign_at_omega_one():
    c1 = equations.characteristic_polynomial().coeff_monomial(equations.LAMBDA)
    W, B, MU = equations.OMEGA, equations.BETA, equations.MU
    assert sp.simplify(c1 - 2 * B * MU**3 * W**4 * (W**2 - 1)) == 0


def test_characteristic_polynomial_equals_numeric_eigenvalues():
    poly = equations.characteristic_polynomial()
    subs = {equations.MU: CASE["mu"], equations.RHO: CASE["rho"], equations.ZETA: CASE["zeta"],
            equations.BETA: CASE["beta"], equations.OMEGA: CASE["omega"]}
    coeffs = [complex(c.subs(subs)) for c in poly.all_coeffs()]
    roots = np.roots(coeffs)
    eig = stability.eigenvalues(**CASE)
    distance = np.abs(roots[:, None] - eig[None, :])
    assert np.max(distance.min(axis=1)) < 1e-8 and np.max(distance.min(axis=0)) < 1e-8


def test_known_limits():
    assert stability.max_real_part(**CASE) < 0                              # balanced, stable
    assert stability.max_real_part(**{**CASE, "omega": 0.8}) > 0           # below critical speed
    assert stability.max_real_part(**{**CASE, "beta": 0.0}) > -1e-12       # no ball damping
    # vectorised over a grid: one eigen-problem per point
    beta, omega = np.meshgrid(np.linspace(0.1, 2, 7), np.linspace(0.5, 4, 9))
    grid = stability.max_real_part(0.01, 1.0, 0.05, beta, omega)
    assert grid.shape == (9, 7)
    assert grid[0, 0] == pytest.approx(stability.max_real_part(0.01, 1.0, 0.05, 0.1, 0.5))


def test_the_slow_flow_boundary_is_exactly_omega_one_and_the_exact_one_is_smooth():
    """Digest A's small-mu slow flow loses stability exactly at Omega = 1 (the sign of
    1 - Omega^2 in Delta); the boundaries are located between grid speeds, not on them, so a
    coarse grid gives neither a zigzag nor a staircase. As mu -> 0 the exact boundary tends
    to the slow flow's."""
    from rotorvib.papers.a.studies import slow_flow_dataset

    betas, omegas = np.linspace(0.2, 2.0, 4), np.linspace(0.5, 3.0, 26)  # grid step 0.1
    ds = slow_flow_dataset(0.01, 1.0, 0.05, betas, omegas)
    np.testing.assert_allclose(ds.critical_speed_slow_flow, 1.0, atol=1e-7)
    exact = ds.critical_speed_exact.values
    assert np.all(np.diff(exact) < 0)  # falls with beta, never flat between grid points
    for beta, onset in zip(betas, exact):
        below, above = stability.max_real_part(0.01, 1.0, 0.05, beta, onset + np.array([-1e-6, 1e-6]))
        assert below > 0 > above
    small = slow_flow_dataset(1e-4, 1.0, 0.05, betas, omegas).critical_speed_exact.values
    assert np.all(np.abs(small - 1) < np.abs(exact - 1))
