"""Paper B's rotor without balls: the package's engine against ROSS (ross-rotordynamics), an
independent finite-element rotordynamics code, and both against the closed form."""

import numpy as np
import pytest

from rotorvib.papers.b import ross_model
from rotorvib.papers.b.jeffcott import ballless, jeffcott_dataset, steady_response
from rotorvib.papers.b.setup import Setup

SPEEDS = np.array([20.0, 60.0, 95.0, 100.0, 105.0, 150.0, 300.0])


@pytest.fixture(scope="module")
def case(config):
    b = config["paper_b"]
    setup = Setup.from_paper_b(b)
    check = b["ross_check"]
    eps_bar = b["table2"]["eps_bar"]
    rotor = ballless(setup, eps_bar, check["m_bar"])
    model = ross_model.rotor(rotor.M, rotor.k, rotor.c, check["shaft"])
    unbalance = rotor.M * rotor.eps
    ds = jeffcott_dataset(
        setup, eps_bar=eps_bar, m_bar=check["m_bar"], speeds=SPEEDS, settle=check["settle"],
        t_end=1.0, dt=check["dt"],
        ross_steady=lambda w: ross_model.steady(model, unbalance, w),
        ross_runup=lambda t, kinematics: ross_model.runup(model, unbalance, t, kinematics))
    return ds, setup, check


def test_the_engine_is_the_closed_form(case):
    """Balls of mass ratio 1e-9: amplitude within 1e-6, phase within 1e-6 rad."""
    ds, setup, _ = case
    np.testing.assert_allclose(ds.amplitude_engine, ds.amplitude_closed_form, rtol=1e-6)
    np.testing.assert_allclose(ds.phase_engine, ds.phase_closed_form, atol=1e-6)
    exact = steady_response(float(ds.eps), setup.zeta, SPEEDS / float(ds.omega_n))
    assert float(ds.amplitude_closed_form[3]) == pytest.approx(abs(exact[3]))
    assert float(ds.phase_closed_form[3]) == pytest.approx(-np.pi / 2)   # at omega_n


def test_ross_agrees_within_its_shafts_compliance(case):
    """ROSS against the engine: amplitude within 1e-3, phase within 2e-3 rad.  The difference
    is the ROSS model's shaft, a compliance k/k_s in series with the support (bending and shear
    of a Timoshenko beam): against the closed form with the series stiffness
    k_eff = k / (1 + k/k_s) ROSS agrees within 1e-4 in amplitude and 5e-4 rad in phase (at the
    resonance, where the phase turns by 1/(zeta omega_n) per rad/s), and at the lowest speed its
    excess over the closed form is that compliance, amplified by 1 / (1 - (w/w_n)^2): within
    1e-3 of it (the disk's tilt and the shaft's mass, left out of the series spring, give
    5.5e-4), a tolerance far above the solve's round-off, cond(Z) eps / excess = 4e-4 at most."""
    ds, setup, check = case
    np.testing.assert_allclose(ds.amplitude_ross, ds.amplitude_engine, rtol=1e-3)
    np.testing.assert_allclose(ds.phase_ross, ds.phase_engine, atol=2e-3)
    compliance = setup.k / ross_model.shaft_stiffness(check["shaft"])
    k_eff, c = setup.k / (1 + compliance), 2 * setup.zeta * np.sqrt(setup.k * setup.M)
    series = setup.M * float(ds.eps) * SPEEDS**2 / (k_eff - setup.M * SPEEDS**2
                                                     + 1j * c * SPEEDS)
    np.testing.assert_allclose(ds.amplitude_ross, np.abs(series), rtol=1e-4)
    np.testing.assert_allclose(ds.phase_ross, np.angle(series), atol=5e-4)
    excess = float(ds.amplitude_ross[0] / ds.amplitude_closed_form[0] - 1)
    amplified = compliance / (1 - (SPEEDS[0] / float(ds.omega_n)) ** 2)
    assert excess == pytest.approx(amplified, rel=1e-3)


def test_the_direct_solve_is_well_conditioned_and_rosss_modal_route_agrees(case, config):
    """The steady response is solved from ROSS's dynamic stiffness, whose condition number
    stays below 1e8 (round-off 2e-8 of the amplitude, whatever the BLAS kernel); ROSS's own
    modal route (``run_unbalance_response``) inverts eigenvectors of condition number about
    1e10, so it agrees only within cond(psi) eps = 3e-6, amplified by up to 1/(2 zeta) = 50 at
    the resonance: within 2e-4."""
    ds, setup, check = case
    b = config["paper_b"]
    rotor = ballless(setup, b["table2"]["eps_bar"], check["m_bar"])
    model = ross_model.rotor(rotor.M, rotor.k, rotor.c, check["shaft"])
    conditions = [np.linalg.cond(ross_model.dynamic_stiffness(model, w)) for w in SPEEDS]
    assert max(conditions) < 1e8
    modal = model.run_unbalance_response(
        node=ross_model.DISK_NODE, unbalance_magnitude=rotor.M * rotor.eps, unbalance_phase=0.0,
        frequency=SPEEDS).forced_resp[ross_model.DOF_PER_NODE * ross_model.DISK_NODE]
    np.testing.assert_allclose(np.abs(modal), ds.amplitude_ross, rtol=2e-4)
    np.testing.assert_allclose(np.angle(modal), ds.phase_ross, atol=2e-4)


def test_the_run_up_through_the_critical_speed_agrees(case):
    """Paper B's run-up (its speed section, consistent kinematics): the peak whirl and its time
    agree within 1e-4 and one step; over the whole run the gap stays within 2e-3 of the peak
    (ROSS's Newmark step is second order)."""
    ds, _, check = case
    peak_engine, peak_ross = float(ds.r_engine.max()), float(ds.r_ross.max())
    assert peak_ross == pytest.approx(peak_engine, rel=1e-4)
    t = ds.t.values
    peaks = t[np.argmax(ds.r_ross.values)], t[np.argmax(ds.r_engine.values)]
    assert abs(peaks[0] - peaks[1]) <= 1.5 * check["dt"]
    assert float(np.max(np.abs(ds.r_ross - ds.r_engine))) < 2e-3 * peak_engine
    assert float(ds.speed_runup.max()) > float(ds.omega_n)      # it passes the critical speed
