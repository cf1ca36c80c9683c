"""The closed-form critical-speed passage (rotorvib.models.balancer.passage) against the Cornu
spiral, the quasi-static limit, an integration of the same linear rotor, and the package's
engine with balls that cannot move; and the balance time and design rule built on it."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import fresnel

from rotorvib.models.balancer.kinematics import disk_kinematics
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters
from rotorvib.models.balancer.passage import passage_peak, peak_factor
from rotorvib.papers.b.prediction import design_rule, passage, predicted_balance_time


def test_the_undamped_peak_is_the_cornu_spirals_greatest_reach():
    """E(sigma, 0, 0) = sqrt(pi) |(C(x) + 1/2, S(x) + 1/2)| at x = sigma / sqrt(pi): its
    greatest value, found on a fine grid of the Fresnel integrals, and where it is."""
    x = np.linspace(0.0, 3.0, 300_001)
    s, c = fresnel(x)
    reach = np.hypot(c + 0.5, s + 0.5)
    peak, sigma = peak_factor(0.0)
    assert peak == pytest.approx(np.sqrt(np.pi) * reach.max(), rel=1e-6)
    assert sigma == pytest.approx(np.sqrt(np.pi) * x[reach.argmax()], abs=2e-3)


@pytest.mark.parametrize("d", [20.0, 80.0])
def test_a_heavily_damped_passage_is_quasi_static(d):
    """For d >> 1 the peak is the steady resonance 1/d (r_pk = eps_u / (2 zeta)), reached at
    the crossing; the error falls as 1/d^2."""
    peak, sigma = peak_factor(d)
    assert peak * d == pytest.approx(1.0, abs=2.0 / d**2)
    assert abs(sigma) < 2.0 / d


def _integrated_peak(b: Balancer, profile: SpeedProfile, t_end: float) -> tuple[float, float]:
    """Peak whirl radius and its time of M_t z'' + c z' + k z = U (Phi'^2 - i Phi'') e^{i Phi}
    from rest (balls frozen at angle 0), integrated by scipy."""
    p = fixed_parameters(b, profile)
    unbalance = b.M * b.eps + b.n * b.m * b.R

    def rhs(t, y):
        phi, rate, acceleration = disk_kinematics(t, p)
        z, v = y[0] + 1j * y[1], y[2] + 1j * y[3]
        a = (unbalance * (rate**2 - 1j * acceleration) * np.exp(1j * phi) - b.c * v
             - b.k * z) / b.total_mass
        return [v.real, v.imag, a.real, a.imag]

    sol = solve_ivp(rhs, (0.0, t_end), [0.0] * 4, rtol=1e-10, atol=1e-14, max_step=1e-3)
    r = np.hypot(sol.y[0], sol.y[1])
    return float(r.max()), float(sol.t[r.argmax()])


def test_the_closed_form_converges_to_the_integration_as_the_run_up_slows():
    """Paper B's rotor and run-up shape, the ramp 0.5, 2 and 8 s (eta = 0.08, 0.02, 0.005):
    the closed form's peak is within 7 % of the integrated one at paper B's ramp, its time
    within 5 ms, and the error falls as sqrt(eta) (halves for each fourfold slower ramp)."""
    b = Balancer(M=1.0, m=1e-9, R=0.1, eps=1e-3, k=1e4, c=2.0, D=0.0)
    errors = []
    for t_ramp in (0.5, 2.0, 8.0):
        profile = SpeedProfile(200.0, "runup", t_ramp, "consistent")
        closed = passage_peak(b, profile, [0.0, 0.0])
        radius, time = _integrated_peak(b, profile, 2 * closed.time)
        errors.append(closed.radius / radius - 1)
        assert closed.time == pytest.approx(time, abs=5e-3)
        assert closed.force == pytest.approx(b.k * closed.radius)
    assert abs(errors[0]) < 0.07
    assert [e1 / e0 for e0, e1 in zip(errors, errors[1:])] == pytest.approx([0.5, 0.5], abs=0.08)


def test_balls_that_cannot_move_pass_as_the_closed_form_says(setup):
    """The package's engine with ball damping so large that the balls keep their angles in the
    disk's frame through the passage: its peak bearing force and time against the closed form
    (the frozen balls' unbalance adds to the disk's), within the closed form's own error."""
    from rotorvib.models.balancer.layout import METRICS

    phi0 = [40.0, 45.0]
    metrics = setup.runs([setup.run_inputs(mass=0.01, eps_bar=0.012, beta=200.0,
                                           phi0_deg=phi0, kinematics="consistent")],
                         progress=False)[0]
    closed = passage(setup, mass=0.01, eps_bar=0.012, phi0_deg=phi0, kinematics="consistent")
    assert closed.force == pytest.approx(metrics[METRICS.index("force_max")], rel=0.1)
    assert closed.time == pytest.approx(metrics[METRICS.index("force_max_time")], abs=0.01)


def test_no_passage_below_the_critical_speed(setup):
    """A run-up that never reaches sqrt(k / M_t) has no passage: NaN, not a number."""
    low = passage(setup, mass=0.01, eps_bar=0.012, phi0_deg=[0.0, 0.0],
                  kinematics="consistent", speed=90.0)
    assert np.isnan(low.force) and np.isnan(low.time)


def test_the_design_rule_answers_fast_and_never_recommends_what_does_not_balance(setup):
    """The rule's recommendation is the grid's least mean predicted time, within a band that
    contains it; masses below the existence bound (m < eps_bar M / 2) are never recommended,
    and a grid of only such masses is refused."""
    ics = [[40.0, 45.0], [110.0, 115.0], [260.0, 265.0]]
    kwargs = dict(eps_bar=0.012, phi0_deg=ics, kinematics="printed", neutral=1e-9, share=0.1)
    rule = design_rule(setup, masses=[0.004, 0.008, 0.012], betas=[0.2, 0.5, 1.0],
                       error_band=(-0.1, 0.2), **kwargs)
    assert np.isnan(rule.mean_time[0]).all() and rule.mass > 0.004
    assert rule.time == pytest.approx(np.nanmin(rule.mean_time))
    assert rule.band[0] < rule.time < rule.band[1]
    direct = predicted_balance_time(setup, mass=rule.mass, beta=rule.beta, **kwargs)
    assert rule.time == pytest.approx(np.mean(direct))
    with pytest.raises(ValueError, match="no design of the grid balances"):
        design_rule(setup, masses=[0.002, 0.004], betas=[0.5], **kwargs)
