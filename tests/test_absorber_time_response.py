"""Paper C time integration: exact resonance solution, steady state, linearisation, failures."""

from dataclasses import replace

import numpy as np
import pytest

from rotorvib.methods.integrate import IntegrationError, integrate
from rotorvib.models.absorber.frequency_response import matrices, steady_state
from rotorvib.models.absorber.time_response import (
    linear_response,
    rhs_linear,
    rhs_nonlinear,
    simulate,
)


def test_bare_rotor_at_resonance_matches_the_exact_solution(rotor):
    """J theta'' + k_t theta = Gamma0 cos(w_n t) from rest: theta = Gamma0 t sin(w_n t)/(2 J w_n)."""
    t = np.linspace(0.0, 0.5, 4001)
    theta = simulate(rotor, (), rotor.omega_n, t)[:, 0]
    exact = rotor.Gamma0 * t * np.sin(rotor.omega_n * t) / (2 * rotor.J * rotor.omega_n)
    assert np.max(np.abs(theta - exact)) < 1e-8 * np.max(np.abs(exact))


def test_long_run_settles_on_the_frequency_response(rotor, table2):
    period = 2 * np.pi / rotor.omega_n
    t = np.linspace(1.5, 1.5 + period, 201)
    t = np.concatenate([[0.0], t])
    q = simulate(rotor, table2, rotor.omega_n, t, model="linear")[1:]
    steady = np.abs(steady_state(rotor, table2, rotor.omega_n))
    np.testing.assert_allclose(np.max(np.abs(q), axis=0), steady, rtol=2e-3)


def test_nonlinear_tends_to_linear_as_amplitude_shrinks(rotor, table2):
    """The neglected terms are cubic, so the relative gap falls ~100x per 10x in amplitude."""
    t = np.linspace(0.0, 0.3, 3001)
    gaps = []
    for scale in (100.0, 10.0):
        r = replace(rotor, Gamma0=rotor.Gamma0 * scale)
        lin, non = (simulate(r, table2, r.omega_n, t, model=m)[:, 0] for m in ("linear", "nonlinear"))
        gaps.append(np.max(np.abs(non - lin)) / np.max(np.abs(lin)))
    assert gaps[0] / gaps[1] == pytest.approx(100, rel=0.3)


def test_default_tolerance_is_converged(rotor, table2):
    """rtol = 1e-10 (config) agrees with rtol = 1e-12 to far below plotting resolution."""
    t = np.linspace(0.0, 0.5, 2001)
    a = simulate(rotor, table2, rotor.omega_n, t, rtol=1e-10, atol=1e-13)
    b = simulate(rotor, table2, rotor.omega_n, t, rtol=1e-12, atol=1e-15)
    assert np.max(np.abs(a - b)) < 1e-7 * np.max(np.abs(b))


def test_failed_integration_raises():
    with pytest.raises(IntegrationError, match="non-finite|failed"):
        integrate(lambda t, y: y**2, [1.0], np.linspace(0.0, 2.0, 5), rtol=1e-8, atol=1e-12)


def test_unknown_model_is_refused(rotor):
    with pytest.raises(ValueError, match="model"):
        simulate(rotor, (), rotor.omega_n, np.linspace(0, 1, 3), model="exact")


def test_exact_linear_response_equals_the_integrated_one(rotor, table2):
    """Eigen-decomposition plus steady state against Runge-Kutta on eq. (14), from rest, at
    resonance and off it; the exact one starts at rest to rounding."""
    t = np.linspace(0.0, 0.5, 2001)
    for w in (rotor.omega_n, 0.9 * rotor.omega_n):
        exact = linear_response(rotor, table2, w, t)
        ode = simulate(rotor, table2, w, t, model="linear", rtol=1e-11, atol=1e-14)
        scale = np.abs(ode).max(axis=0)                 # per coordinate: rad, m, m
        np.testing.assert_allclose(exact / scale, ode / scale, rtol=0, atol=1e-8)
        np.testing.assert_allclose(exact[0], 0.0, atol=1e-15)


def test_without_absorber_the_nonlinear_equations_are_the_linear_ones(rotor):
    """With no set, (8)-(10) reduce to (14), J theta'' + k_t theta = Gamma: the time-response
    study integrates that case once for both models."""
    M, C, K = matrices(rotor, ())
    empty = np.array([])
    for t, y in zip(np.random.default_rng(0).uniform(0, 1, 5),
                    np.random.default_rng(1).normal(size=(5, 2))):
        np.testing.assert_allclose(
            rhs_nonlinear(t, y, rotor.J, rotor.k_t, rotor.Gamma0, empty, empty, empty, empty,
                          rotor.omega_n),
            rhs_linear(t, y, np.linalg.inv(M), C, K, rotor.Gamma0, rotor.omega_n),
            rtol=1e-14, atol=0)
