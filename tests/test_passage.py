"""The critical-speed passage of frozen balls (rotorvib.models.balancer.passage) against the Cornu
spiral, the quasi-static limit, an integration of the same linear rotor, and the package's
engine with balls that cannot move."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import fresnel

from rotorvib.models.balancer.kinematics import disk_kinematics
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters
from rotorvib.models.balancer.passage import passage_peak
from rotorvib.papers.b.prediction import passage


def _slow_sweep_errors(c: float, ramps, limit) -> list[float]:
    """The relative error of the passage's peak against ``limit(b, passage)`` on a rotor of
    damping ``c`` run up to 200 rad/s (its critical speed 100 rad/s) over each ramp."""
    b = Balancer(M=1.0, m=1e-9, R=0.1, eps=1e-3, k=1e4, c=c, D=0.0)
    out = []
    for t_ramp in ramps:
        p = passage_peak(b, SpeedProfile(200.0, "runup", t_ramp, "consistent"), [0.0, 0.0])
        out.append(p.radius / limit(b, p) - 1)
    return out


def test_a_slow_undamped_sweep_peaks_at_the_cornu_spirals_greatest_reach():
    """r_pk -> sqrt(pi) max |(C(x) + 1/2, S(x) + 1/2)| eps_u / (2 sqrt(eta)) = 1.467 eps_u /
    sqrt(eta) (the Fresnel integrals on a fine grid) as eta = a / w^2 -> 0: the error falls as
    sqrt(eta), halving for each fourfold slower ramp, and is under 2 % at eta = 1.25e-3."""
    x = np.linspace(0.0, 3.0, 300_001)
    s, c = fresnel(x)
    cornu = np.sqrt(np.pi) * np.hypot(c + 0.5, s + 0.5).max() / 2
    assert cornu == pytest.approx(1.467, abs=5e-4)
    errors = _slow_sweep_errors(0.0, (2.0, 8.0, 32.0), lambda b, p: cornu * (
        b.M * b.eps + b.n * b.m * b.R) / b.total_mass / np.sqrt(p.acceleration / 100.0**2))
    assert 0 < errors[-1] < 0.02
    assert [e1 / e0 for e0, e1 in zip(errors, errors[1:])] == pytest.approx([0.5, 0.5], abs=0.05)


def test_a_slow_damped_sweep_peaks_at_the_steady_resonance():
    """zeta_t = 0.2: r_pk -> eps_u / (2 zeta_t sqrt(1 - zeta_t^2)), the steady response's
    greatest value over speed, as the ramp slows; the error falls as eta (a quarter for each
    fourfold slower ramp), under 3e-3 at a 128 s ramp."""
    def steady(b, _):
        zeta = b.c / (2 * np.sqrt(b.k * b.total_mass))
        return b.eps / (2 * zeta * np.sqrt(1 - zeta**2))

    errors = _slow_sweep_errors(40.0, (8.0, 32.0, 128.0), steady)
    assert 0 < errors[-1] < 3e-3
    assert [e1 / e0 for e0, e1 in zip(errors, errors[1:])] == pytest.approx([0.27, 0.27],
                                                                            abs=0.05)


def _integrated_peak(b: Balancer, profile: SpeedProfile, phi0_deg, z0: complex,
                     t_end: float) -> tuple[float, float]:
    """Peak whirl radius and its time of M_t z'' + c z' + k z = U (Phi'^2 - i Phi'') e^{i Phi}
    from rest at ``z0`` (balls frozen at ``phi0_deg``), integrated by scipy's DOP853."""
    p = fixed_parameters(b, profile)
    unbalance = b.M * b.eps + b.m * b.R * np.exp(1j * np.radians(phi0_deg)).sum()

    def rhs(t, y):
        phi, rate, acceleration = disk_kinematics(t, p)
        z, v = y[0] + 1j * y[1], y[2] + 1j * y[3]
        a = (unbalance * (rate**2 - 1j * acceleration) * np.exp(1j * phi) - b.c * v
             - b.k * z) / b.total_mass
        return [v.real, v.imag, a.real, a.imag]

    sol = solve_ivp(rhs, (0.0, t_end), [z0.real, z0.imag, 0.0, 0.0], method="DOP853",
                    rtol=1e-10, atol=1e-14, max_step=2e-4)
    r = np.hypot(sol.y[0], sol.y[1])
    return float(r.max()), float(sol.t[r.argmax()])


@pytest.mark.parametrize("kinematics", ["printed", "consistent"])
@pytest.mark.parametrize("machine", ["paper_b", "heavy"])
def test_the_passage_is_the_integrated_frozen_ball_rotor(setup, kinematics, machine):
    """Duhamel's integral against scipy's integration of the same rotor, balls frozen, from
    eq. 36's initial whirl: the peak bearing force within 2e-4 and its time within 2e-4 s, for
    6 and 14 g balls from IC1, IC2 and IC3 at 220 rad/s (6 g, eps_bar 0.012, IC1, printed:
    90.5 N), on paper B's machine and on a rotor of twice its mass and stiffness with
    eps_bar 0.02."""
    import dataclasses

    machine_setup = setup if machine == "paper_b" else dataclasses.replace(
        setup, M=2 * setup.M, k=2 * setup.k)
    eps_bar = 0.012 if machine == "paper_b" else 0.02
    forces = []
    for mass in (0.006, 0.014):
        for ic in ([40.0, 45.0], [110.0, 115.0], [260.0, 265.0]):
            closed = passage(machine_setup, mass=mass, eps_bar=eps_bar, phi0_deg=ic,
                             kinematics=kinematics, speed=220.0)
            b = machine_setup.balancer(mass=mass, eps_bar=eps_bar, beta=0.0)
            radius, time = _integrated_peak(
                b, machine_setup.profile(kinematics, 220.0), ic,
                machine_setup.r0 * np.exp(1j * machine_setup.theta0), 2 * closed.time)
            assert closed.force == pytest.approx(b.k * radius, rel=2e-4)
            assert closed.time == pytest.approx(time, abs=2e-4)
            forces.append(closed.force)
    if machine == "paper_b" and kinematics == "printed":
        assert forces[0] == pytest.approx(90.5, abs=0.05)


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
