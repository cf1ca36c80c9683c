"""The ball-balancer engine against scipy, against paper B's printed polar equations, across
kinematic conventions and across the fixed and rotating frames."""

import logging
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from numba import njit
from scipy.integrate import ode, solve_ivp

from conftest import ROOT
from oracles.printed_balancer import polar_to_fixed, rhs_polar_printed
from rotorvib.methods.integrate import IntegrationError
from rotorvib.models.balancer import dop853, engine, layout, settling, simulate
from rotorvib.models.balancer.borrowed import borrowed
from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.kinematics import profile_speed
from rotorvib.models.balancer.parameters import (
    Balancer,
    Dimensionless,
    SpeedProfile,
    fixed_parameters,
    fixed_state,
    rotating_parameters,
)
from rotorvib.models.balancer.simulate import MAX_STEPS, check_batch, run, run_batch

R_THR, F_THR = 1e-4, 1.0


def paper_b(m_bar=0.01, eps_bar=0.012, beta=1.0, zeta=0.01):
    return Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=m_bar, eps_bar=eps_bar, zeta=zeta,
                                 beta=beta)


def ic(deg=(40.0, 45.0), r0=1e-3):
    return fixed_state(2, r0=r0, theta0=0.0, phi0=np.radians(deg))


def scipy_reference(form, p, y0, t):
    def f(tt, y):
        dy = np.empty_like(y)
        engine.rhs(form, tt, y, p, dy)
        return dy
    sol = solve_ivp(f, (t[0], t[-1]), y0, method="DOP853", rtol=1e-12, atol=1e-15, t_eval=t)
    assert sol.success
    return sol.y.T


@pytest.mark.parametrize("case", [
    dict(b=paper_b(), prof=SpeedProfile(200.0, "runup", 0.5, "printed"), deg=(40, 45), t=3.0),
    dict(b=paper_b(), prof=SpeedProfile(200.0, "runup", 0.5, "consistent"), deg=(260, 265), t=3.0),
    dict(b=paper_b(beta=0.2, m_bar=0.006), prof=SpeedProfile(230.0, "constant"), deg=(110, 115),
         t=2.0),
    dict(b=paper_b(beta=0.0), prof=SpeedProfile(150.0, "constant"), deg=(45, 90), t=1.0),
])
def test_engine_matches_scipy_dop853(case):
    p = fixed_parameters(case["b"], case["prof"])
    y0 = ic(case["deg"])
    traj = run(layout.FIXED, p, y0, BalanceCriterion(R_THR, F_THR, case["t"], 1e-3), rtol=1e-11, atol=1e-14, store=True)
    ref = scipy_reference(layout.FIXED, p, y0, traj.t)
    scale = np.max(np.abs(ref), axis=0)
    assert np.max(np.abs(traj.y - ref) / scale) < 1e-7


def hairer_reference(form, p, y0, t):
    """Hairer and Wanner's own DOP853 (Fortran, through scipy's ``ode``) at rtol 1e-12: an
    implementation independent of the engine's and of scipy's Python one, at a quarter of the
    latter's cost on a 20 s run."""
    def f(tt, y):
        dy = np.empty_like(y)
        engine.rhs(form, tt, y, p, dy)
        return dy
    solver = ode(f).set_integrator("dop853", rtol=1e-12, atol=1e-15, nsteps=10**8)
    solver.set_initial_value(y0, t[0])
    out = [y0]
    for tt in t[1:]:
        out.append(solver.integrate(tt))
        assert solver.successful()
    return np.array(out)


def test_full_runup_balance_time_matches_scipy():
    """Paper B's run-up, 20 s: balance time from the engine's default tolerance and from
    Hairer's DOP853 at rtol 1e-12 agree to 1e-3 s."""
    b, prof = paper_b(), SpeedProfile(200.0, "runup", 0.5, "printed")
    p, y0 = fixed_parameters(b, prof), ic((40, 45))
    res = run(layout.FIXED, p, y0, BalanceCriterion(R_THR, F_THR, 20.0, 1e-3))
    t = np.arange(20001) * 1e-3
    ref = hairer_reference(layout.FIXED, p, y0, t)
    r = np.hypot(ref[:, 0], ref[:, 1])
    last_above = np.flatnonzero(r >= R_THR)[-1]
    t_ref = t[last_above] + (r[last_above] - R_THR) / (r[last_above] - r[last_above + 1]) * 1e-3
    assert not res.censored
    assert res.balance_time == pytest.approx(t_ref, abs=1e-3)
    assert 1.0 < res.balance_time < 20.0


def test_cartesian_printed_form_equals_paper_b_polar_equations():
    """Eqs (7)-(9) integrated literally in polar coordinates (r > 0 throughout) coincide with
    the regular Cartesian form under the printed kinematics, during the run-up."""
    b, prof = paper_b(), SpeedProfile(200.0, "runup", 0.5, "printed")
    y0 = ic((40, 45))
    t = np.linspace(0.0, 0.4, 401)
    polar0 = np.concatenate(([1e-3, 0.0], y0[2:4], np.zeros(4)))
    sol = solve_ivp(rhs_polar_printed, (0, 0.4), polar0, method="DOP853", rtol=1e-12,
                    atol=1e-15, t_eval=t, args=(b, prof))
    assert sol.success and np.all(sol.y[0] > 0)
    traj = run(layout.FIXED, fixed_parameters(b, prof), y0, BalanceCriterion(R_THR, F_THR, 0.4, 1e-3), rtol=1e-12, atol=1e-15, store=True)
    ref = polar_to_fixed(sol.y.T, 2)
    scale = np.max(np.abs(ref), axis=0)
    assert np.max(np.abs(traj.y - ref) / scale) < 1e-7


def test_printed_and_consistent_kinematics_coincide_at_constant_speed():
    b = paper_b()
    y0 = ic((110, 115))
    out = [run(layout.FIXED, fixed_parameters(b, SpeedProfile(200.0, "constant", kinematics=k)),
               y0, BalanceCriterion(R_THR, F_THR, 2.0, 1e-3), store=True).y
           for k in ("printed", "consistent")]
    np.testing.assert_array_equal(out[0], out[1])


def test_printed_and_consistent_kinematics_differ_during_runup():
    b = paper_b()
    res = [run(layout.FIXED, fixed_parameters(b, SpeedProfile(200.0, "runup", kinematics=k)),
               ic(), BalanceCriterion(R_THR, F_THR, 20.0, 1e-3))
           for k in ("printed", "consistent")]
    assert abs(res[0].balance_time - res[1].balance_time) > 1e-3


@pytest.mark.parametrize("profile", ["constant", "runup"])
def test_rotating_frame_equals_fixed_frame(profile):
    """Digest A's dimensionless rotating-frame form reproduces the fixed-frame trajectory through
    u + i v = (x + i y) exp(-i Phi) / R, tau = w_n t (consistent kinematics)."""
    b = paper_b(beta=0.5)
    prof = SpeedProfile(200.0, profile, 0.5, "consistent")
    d, wn = b.dimensionless(), b.omega_n_total
    y0 = ic((40, 45))
    fixed = run(layout.FIXED, fixed_parameters(b, prof), y0, BalanceCriterion(R_THR, F_THR, 1.0, 1e-3), rtol=1e-12, atol=1e-15, store=True)
    rot_prof = SpeedProfile(prof.omega / wn, profile, prof.t_ramp * wn, "consistent")
    Om = profile_speed(rot_prof, 0.0)[0][0]
    # at rest in the fixed frame: u' + i v' = -i Omega (u + i v)
    y0r = np.concatenate((y0[:2] / b.R, y0[2:4], [Om * y0[1] / b.R, -Om * y0[0] / b.R], y0[6:]))
    rot = run(layout.ROTATING, rotating_parameters(d, rot_prof), y0r, BalanceCriterion(R_THR / b.R, F_THR, 1.0 * wn, 1e-3 * wn), rtol=1e-12,
              atol=1e-15, store=True)
    phase = np.array(profile_speed(prof, fixed.t)[3])
    z = (rot.y[:, 0] + 1j * rot.y[:, 1]) * b.R * np.exp(1j * phase)
    scale = np.max(np.abs(fixed.y[:, 0]))
    assert np.max(np.abs(z.real - fixed.y[:, 0])) < 1e-7 * scale
    assert np.max(np.abs(z.imag - fixed.y[:, 1])) < 1e-7 * scale
    np.testing.assert_allclose(rot.y[:, 2:4], fixed.y[:, 2:4], atol=1e-7)


def test_balanced_angle_and_existence_bound():
    b = paper_b(m_bar=0.01, eps_bar=0.012)
    assert np.cos(b.balanced_angle()) == pytest.approx(-0.012 / (2 * 0.01))
    assert b.can_balance() and not paper_b(m_bar=0.0059, eps_bar=0.012).can_balance()
    assert Dimensionless(0.01, 1.0, 0.05, 0.5).balanced_angle() == pytest.approx(2 * np.pi / 3)
    with pytest.raises(ValueError, match="existence bound"):
        paper_b(m_bar=0.005, eps_bar=0.012).balanced_angle()


def test_long_run_settles_on_the_balanced_angle():
    b = paper_b(beta=0.5)
    traj = run(layout.FIXED, fixed_parameters(b, SpeedProfile(200.0, "constant")), ic((100, 140)), BalanceCriterion(R_THR, F_THR, 30.0, 1e-2), store=True)
    phi = np.mod(traj.y[-1, 2:4] + np.pi, 2 * np.pi) - np.pi
    np.testing.assert_allclose(np.sort(phi), [-b.balanced_angle(), b.balanced_angle()], atol=1e-4)
    assert traj.r[-1] < 1e-7
    assert not traj.result.censored


def test_unbalanced_run_is_censored_not_a_number():
    b = paper_b(beta=0.0)       # beta = 0: the balanced state is unstable (paper B, Fig 6)
    res = run(layout.FIXED, fixed_parameters(b, SpeedProfile(200.0, "constant")), ic((45, 90)), BalanceCriterion(R_THR, F_THR, 5.0, 1e-3))
    assert res.censored and np.isnan(res.balance_time)


def test_failures_are_reported():
    b = paper_b()
    p = fixed_parameters(b, SpeedProfile(200.0, "constant"))
    p_bad = p.copy()
    p_bad[0] = np.nan
    # the public entry points refuse the bad input before integrating ...
    with pytest.raises(ValueError, match=r"p\[0\] = nan: must be finite"):
        run(layout.FIXED, p_bad, ic(), BalanceCriterion(R_THR, F_THR, 1.0, 1e-3))
    # ... and the engine itself flags a failed run in its batch instead of returning numbers
    metrics = np.stack([engine.integrate(layout.FIXED, q, ic(), 0.0, 0.5, 1e-8, 1e-11, 1e-3,
                                         R_THR, F_THR, MAX_STEPS, np.empty((0, ic().size)),
                                         settling.disabled()) for q in (p, p_bad)])
    assert metrics[0, 0] == layout.OK and metrics[1, 0] != layout.OK
    with pytest.raises(IntegrationError, match="1 of 2"):
        check_batch(metrics)


def test_batch_equals_single_runs():
    b = [paper_b(beta=x) for x in (0.2, 0.6, 1.0)]
    P = np.stack([fixed_parameters(bi, SpeedProfile(200.0, "runup", kinematics="printed"))
                  for bi in b])
    Y = np.stack([ic(d) for d in ((40, 45), (110, 115), (260, 265))])
    batch = run_batch(layout.FIXED, P, Y, BalanceCriterion(R_THR, F_THR, 8.0, 1e-3), progress=False, chunk=2)
    for i in range(3):
        single = run(layout.FIXED, P[i], Y[i], BalanceCriterion(R_THR, F_THR, 8.0, 1e-3))
        assert batch[i, 2] == single.balance_time or (np.isnan(batch[i, 2]) and single.censored)
        assert batch[i, 6] == single.force_max


@pytest.mark.parametrize("method", ["dopri5", "dop853"])
def test_a_batch_on_many_threads_equals_it_on_one(method, monkeypatch):
    """The threads share the runs out as they come free; every metric is the same to the bit
    (and the rows stay in the order of the inputs)."""
    rng = np.random.default_rng(5)
    P = np.stack([fixed_parameters(paper_b(beta=x), SpeedProfile(200.0, "runup", 0.5, "printed"))
                  for x in rng.uniform(0.2, 1.5, 12)])
    Y = np.stack([ic(tuple(d)) for d in rng.uniform(0, 360, (12, 2))])
    batches = []
    for threads in (1, 3):
        monkeypatch.setattr(simulate, "THREADS", threads)
        batches.append(run_batch(layout.FIXED, P, Y, BalanceCriterion(R_THR, F_THR, 2.0, 1e-3),
                                 method=method, progress=True, chunk=5))
    np.testing.assert_array_equal(*batches)
    assert len(np.unique(batches[0][:, 6])) == 12


def test_a_batchs_progress_is_logged_with_the_runs_done_of_the_total(caplog):
    """A job's log (rotorvib.io.progress) shows the runs done of the total, from the first
    chunk to the last, each line with the time elapsed and left."""
    rng = np.random.default_rng(6)
    P = np.stack([fixed_parameters(paper_b(beta=x), SpeedProfile(200.0, "runup", 0.5, "printed"))
                  for x in rng.uniform(0.2, 1.5, 7)])
    Y = np.stack([ic(tuple(d)) for d in rng.uniform(0, 360, (7, 2))])
    caplog.set_level(logging.INFO, logger="rotorvib.progress")
    run_batch(layout.FIXED, P, Y, BalanceCriterion(R_THR, F_THR, 0.5, 1e-3), chunk=2)
    done = [int(m.group(1)) for r in caplog.records if (m := re.fullmatch(
        r"balancer runs: (\d+) of 7, [\d.]+ s elapsed, about \S+ s left", r.getMessage()))]
    assert done[0] == 3 and done[-1] == 7 and done == sorted(done), caplog.text
    caplog.clear()
    run_batch(layout.FIXED, P, Y, BalanceCriterion(R_THR, F_THR, 0.5, 1e-3), progress=False)
    assert not caplog.records


DOP853_CASE = dict(b=paper_b(), prof=SpeedProfile(200.0, "runup", 0.5, "printed"), deg=(40, 45))


def test_dop853_takes_scipys_steps():
    """The same method and step control as scipy's DOP853: at equal tolerances the engine
    accepts the same number of steps (scipy's nfev = 1 + 12 per attempted step, its dense
    output aside) and lands on the same states to round-off."""
    p, y0 = fixed_parameters(DOP853_CASE["b"], DOP853_CASE["prof"]), ic(DOP853_CASE["deg"])
    t_end, rtol, atol = 1.0, 1e-7, 1e-10
    traj = run(layout.FIXED, p, y0, BalanceCriterion(R_THR, F_THR, t_end, 1e-3), rtol=rtol,
               atol=atol, method="dop853", store=True)

    def f(tt, y):
        dy = np.empty_like(y)
        engine.rhs(layout.FIXED, tt, y, p, dy)
        return dy

    sol = solve_ivp(f, (0.0, t_end), y0, method="DOP853", rtol=rtol, atol=atol, dense_output=True)
    assert traj.result.n_steps == sol.t.size - 1
    ref = sol.sol(traj.t).T   # scipy's dense output of the same steps
    scale = np.max(np.abs(ref), axis=0)
    assert np.max(np.abs(traj.y - ref) / scale) < 1e-9


def test_dop853_converges_at_order_eight_on_the_runup():
    """The error of the state at t = 0.3 s against a tight reference falls as h^8 with the
    step: halving the tolerance ladder's step size (rtol / 2^8) halves the step."""
    p, y0 = fixed_parameters(DOP853_CASE["b"], DOP853_CASE["prof"]), ic(DOP853_CASE["deg"])
    crit = BalanceCriterion(R_THR, F_THR, 0.3, 0.3)
    ref = run(layout.FIXED, p, y0, crit, rtol=1e-13, atol=1e-16, method="dop853", store=True).y[-1]
    errors, steps = [], []
    for rtol in (1e-6, 1e-6 / 2**8, 1e-6 / 2**16):
        traj = run(layout.FIXED, p, y0, crit, rtol=rtol, atol=rtol * 1e-3, method="dop853",
                   store=True)
        errors.append(np.max(np.abs(traj.y[-1] - ref) / np.abs(ref).max()))
        steps.append(traj.result.n_steps)
    orders = np.log(np.array(errors[:-1]) / errors[1:]) / np.log(np.array(steps[1:]) / steps[:-1])
    assert np.all((orders > 6.5) & (orders < 9.5)), (orders, errors, steps)


def test_dop853_gives_the_balance_time_of_dopri5_with_fewer_steps():
    p, y0 = fixed_parameters(DOP853_CASE["b"], DOP853_CASE["prof"]), ic(DOP853_CASE["deg"])
    crit = BalanceCriterion(R_THR, F_THR, 20.0, 1e-3)
    five = run(layout.FIXED, p, y0, crit, rtol=1e-10, atol=1e-13)
    eight = run(layout.FIXED, p, y0, crit, rtol=1e-10, atol=1e-13, method="dop853")
    assert eight.balance_time == pytest.approx(five.balance_time, abs=1e-7)
    assert eight.force_max == pytest.approx(five.force_max, rel=1e-7)
    assert eight.n_steps < five.n_steps / 3
    batch = run_batch(layout.FIXED, np.stack([p, p]), np.stack([y0, ic((110, 115))]), crit,
                      rtol=1e-10, atol=1e-13, method="dop853", progress=False)
    assert batch[0, 2] == eight.balance_time
    with pytest.raises(ValueError, match="method = 'rk4'"):
        run(layout.FIXED, p, y0, crit, method="rk4")


def test_dop853_sums_written_out_equal_the_full_tableau_sums_to_the_bit():
    """The stages, weights and dense-output rows of DOP853 sum over the tableau's non-zero
    coefficients only (rotorvib.models.balancer.dop853): against the sums over every
    coefficient, in the same order, for random stage values, every result is equal to the bit
    (an omitted non-zero coefficient or a wrong index would show)."""
    A, B, C, E3, E5, D = dop853.tableau()
    rng = np.random.default_rng(3)
    K = rng.normal(size=(16, 8))
    y, h = rng.normal(size=8), 1e-3
    p = fixed_parameters(paper_b(), SpeedProfile(200.0, "runup", 0.5, "printed"))

    def full(row, count):
        total = np.zeros(8)
        for q in range(count):
            total = total + row[q] * K[q]
        return total

    for s in [*range(1, 12), *range(13, 16)]:
        ytmp, stages = np.empty(8), K.copy()
        dop853._dop853_stages(layout.FIXED, p, 0.1, y, h, stages, A, C, s, s + 1, ytmp)
        np.testing.assert_array_equal(ytmp, y + h * full(A[s], s), err_msg=f"stage {s}")
    for w, count in ((B, 12), (E3, 13), (E5, 13)):
        np.testing.assert_array_equal([dop853._weighted(w, K, j) for j in range(8)], full(w, count))
    for r in range(4):
        np.testing.assert_array_equal([dop853._dense_weighted(D[r], K, j) for j in range(8)],
                                      full(D[r], 16))


def test_the_tableau_is_scipys_read_without_importing_scipy_integrate():
    """dop853.tableau runs scipy's file of DOP853's coefficients on its own: the arrays are
    those of ``scipy.integrate._ivp.dop853_coefficients`` (fails if the pinned scipy moves or
    changes them), and a process that reads them has not imported ``scipy.integrate``."""
    from scipy.integrate._ivp import dop853_coefficients as c

    for ours, theirs in zip(dop853.tableau(), (c.A, c.B, c.C, c.E3, c.E5, c.D)):
        np.testing.assert_array_equal(ours, theirs)
        assert ours.flags.c_contiguous and ours.dtype == float
    fresh = subprocess.run(
        [sys.executable, "-c", "import sys\nfrom rotorvib.models.balancer import dop853\n"
         "print(len(dop853.tableau()), 'scipy.integrate' in sys.modules)"],
        capture_output=True, text=True, check=True, env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert fresh.stdout == "6 False\n"


def test_a_borrowed_view_aliases_its_array_and_holds_no_reference():
    """The integrators' borrowed views (rotorvib.models.balancer.borrowed) read and write their
    array's memory with its shape and strides, a strided one and its row views included, and
    carry no memory record: returned to Python one has no base keeping the memory alive, where
    numba's own view of the same array has one."""
    @njit
    def double_through_borrowed(a):
        b = borrowed(a)
        for i in range(b.shape[0]):
            row = b[i]
            for j in range(row.size):
                row[j] *= 2.0
        return b.shape, b.strides

    @njit
    def views(a):
        return a[1:], borrowed(a)[1:]

    a = np.arange(24.0).reshape(4, 6)
    strided = a[::2, 1::2]
    assert double_through_borrowed(strided) == (strided.shape, strided.strides)
    expected = np.arange(24.0).reshape(4, 6)
    expected[::2, 1::2] *= 2.0
    assert np.array_equal(a, expected)
    own, lent = views(a)
    assert np.shares_memory(lent, a) and np.array_equal(lent, a[1:])
    assert own.base is not None and lent.base is None
