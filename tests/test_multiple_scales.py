"""Multiple-scales solutions: the one-term solution is the linearised one, the two-term error
falls faster, resonances are reported; on the balancer, exact derivatives and error orders."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from rotorvib.methods.multiple_scales import ConstantsDiverged, MultipleScales
from rotorvib.models.balancer import engine, layout, stability
from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.expansion import balanced_state, taylor_at
from rotorvib.models.balancer.parameters import Dimensionless, SpeedProfile, rotating_parameters
from rotorvib.models.balancer.simulate import run
from rotorvib.papers.a.studies import offset_vector

J2 = np.array([[0.0, 1.0], [-4.0, -0.3]])        # damped oscillator ...
T2 = np.zeros((2, 2, 2))
T2[1, 0, 0] = 2.0                                  # ... with a quadratic spring x'' = ... - x^2
CASE = dict(mu=0.01, rho=1.0, zeta=0.05, beta=0.5, omega=2.0)


def exact_quadratic(x0, tau):
    f = lambda t, x: J2 @ x + 0.5 * np.einsum("ijk,j,k->i", T2, x, x)   # noqa: E731
    return solve_ivp(f, (tau[0], tau[-1]), x0, t_eval=tau, rtol=1e-12, atol=1e-15).y.T


def test_one_term_is_the_linearised_solution():
    ms = MultipleScales.at(J2, T2)
    tau = np.linspace(0, 10, 101)
    x0 = np.array([0.1, -0.05])
    linear = np.array([expm(J2 * t) @ x0 for t in tau])
    np.testing.assert_allclose(ms.one_term(x0, tau), linear, atol=1e-13)


def test_two_term_error_falls_faster_than_one_term():
    ms = MultipleScales.at(J2, T2)
    tau = np.linspace(0, 15, 301)
    errors = []
    for delta in (0.02, 0.01):
        x0 = np.array([delta, 0.0])
        exact = exact_quadratic(x0, tau)
        errors.append([np.abs(ms.one_term(x0, tau) - exact).max(),
                       np.abs(ms.two_term(x0, tau) - exact).max()])
    (e1a, e2a), (e1b, e2b) = errors
    assert np.log2(e1a / e1b) == pytest.approx(2, abs=0.15)
    assert np.log2(e2a / e2b) == pytest.approx(3, abs=0.2)
    assert e2b < e1b / 10


def test_two_term_initial_conditions_are_met():
    ms = MultipleScales.at(J2, T2)
    x0 = np.array([0.05, 0.02])
    np.testing.assert_allclose(ms.two_term(x0, np.array([0.0]))[0], x0, atol=1e-12)


def test_linear_constants_meet_the_initial_state_and_keep_the_order():
    """The linear constants start exactly at x0, differ from the nonlinear ones by O(delta^3)
    (slope 3 in delta), and the solution they give errs at the two-term order."""
    ms = MultipleScales.at(J2, T2)
    tau = np.linspace(0, 15, 301)
    gaps, errors = [], []
    for delta in (0.02, 0.01):
        x0 = np.array([delta, 0.5 * delta])
        np.testing.assert_allclose(ms.two_term(x0, tau[:1], constants="linear")[0], x0,
                                   atol=1e-15)
        first, second = ms.linear_two_term_constants(x0)
        np.testing.assert_array_equal(second, ms.one_term_constants(x0))
        gaps.append(np.abs(first - ms.two_term_constants(x0)).max())
        errors.append(np.abs(ms.two_term(x0, tau, constants="linear")
                             - exact_quadratic(x0, tau)).max())
    assert np.log2(gaps[0] / gaps[1]) == pytest.approx(3, abs=0.1)
    assert np.log2(errors[0] / errors[1]) == pytest.approx(3, abs=0.2)
    with pytest.raises(ValueError, match="constants must be"):
        ms.two_term(x0, tau, constants="quadratic")


def test_resonances_are_reported():
    T = np.zeros((3, 3, 3))
    exact = MultipleScales.at(np.diag([-1.0, -2.0, -3.0]), T)          # -1 + -2 = -3
    assert any({r.j, r.k} == {0, 1} and r.l == 2 and r.distance == 0
               for r in exact.resonances(tolerance=1e-6))
    with pytest.raises(ArithmeticError, match="resonance"):
        exact.two_term(np.ones(3), np.array([0.0]))
    near = MultipleScales.at(np.diag([-1.0, -2.5, -3.52]), T)        # -1 - 2.5 ~ -3.52
    assert [(r.j, r.k, r.l) for r in near.resonances(tolerance=0.01)] == [(0, 1, 2)]
    # the nearest resonance of two and of three exponents, relative to max|lambda|
    assert exact.resonance_distance(2) == 0.0
    assert near.resonance_distance(2) == pytest.approx(0.02 / 3.52, rel=1e-12)
    apart = MultipleScales.at(np.diag([-1.0, -1.7, -10.0]), T)
    assert apart.resonance_distance(2) == pytest.approx(0.3 / 10.0, rel=1e-12)  # 2 x -1, -1.7
    assert apart.resonance_distance(3) == pytest.approx(1.3 / 10.0, rel=1e-12)  # 3 x -1, -1.7


@pytest.fixture(scope="module")
def balancer():
    z = balanced_state(CASE["rho"])
    J, T = taylor_at(**CASE, state=z)
    return z, J, T


def test_balancer_jacobian_and_quadratic_terms_are_exact(balancer):
    z, J, T = balancer
    np.testing.assert_allclose(J, stability.jacobian(**CASE), atol=1e-13)
    p = rotating_parameters(Dimensionless(CASE["mu"], CASE["rho"], CASE["zeta"], CASE["beta"]),
                            SpeedProfile(CASE["omega"], "constant"))

    def f(x):
        out = np.empty(8)
        engine.rhs_rotating(0.0, x, p, out)
        return out

    h, rng = 1e-4, np.random.default_rng(0)
    u, v = rng.normal(size=8), rng.normal(size=8)
    mixed = (f(z + h * (u + v)) - f(z + h * (u - v)) - f(z - h * (u - v)) + f(z - h * (u + v)))
    np.testing.assert_allclose(mixed / (4 * h * h), np.einsum("ijk,j,k->i", T, u, v), atol=1e-7)


def test_balancer_error_orders_against_runge_kutta(balancer):
    z, J, T = balancer
    ms = MultipleScales.at(J, T)
    p = rotating_parameters(Dimensionless(CASE["mu"], CASE["rho"], CASE["zeta"], CASE["beta"]),
                            SpeedProfile(CASE["omega"], "constant"))
    errors = []
    for delta in (0.025, 0.0125):
        x0 = delta * np.array([0.5, 0.0, 1.0, -0.7, 0.0, 0.0, 0.0, 0.0])
        rk = run(layout.ROTATING, p, z + x0, BalanceCriterion(1e-9, 1e-9, 60.0, 0.05), rtol=1e-12, atol=1e-14, store=True)
        errors.append([np.abs(ms.one_term(x0, rk.t) - (rk.y - z)).max(),
                       np.abs(ms.two_term(x0, rk.t) - (rk.y - z)).max()])
    (e1a, e2a), (e1b, e2b) = errors
    assert np.log2(e1a / e1b) == pytest.approx(2, abs=0.2)
    assert np.log2(e2a / e2b) == pytest.approx(3, abs=0.3)
    assert e2b < e1b


def test_an_offset_beyond_the_expansion_is_its_own_error(config):
    """Found by the fuzzer (paper_a.case.omega = 0.002): so slow, the configured offset is too
    far from the balanced state: the two-term constants' equations (eq. 39) have no solution
    near the one-term constants. The error has its own type, by which the workflow's jobs name
    the config key; the same direction 1e4 times closer converges, its residual within the
    solver's tolerance."""
    slow = {**CASE, "omega": 0.002}
    ms = MultipleScales.at(*taylor_at(**slow, state=balanced_state(slow["rho"])))
    offset = offset_vector(**config["paper_a"]["initial_offset"])
    with pytest.raises(ConstantsDiverged, match="did not converge"):
        ms.two_term_constants(offset)
    near = offset * 1e-4
    a = ms.two_term_constants(near)
    x = ms.modes @ a + np.einsum("j,k,jki->i", a, a, ms.second_order)
    assert np.abs(x - near).max() < 1e-9 * np.linalg.norm(near)
