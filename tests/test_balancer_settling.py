"""Stopping a balancer run once its answer is known (rotorvib.models.balancer.settling): the
bounds vanish at the balanced states, hold along whole trajectories, and stopping changes no
metric of a batch while it saves most of the integration, and a run given a balance-time bound
stops once its balance time is known to exceed it."""

import fcntl
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest

import rotorvib.models.balancer.simulate as runner
from rotorvib.methods.numba_cache import LOCK, MANIFEST, compile_lock, drop_if_stale
from rotorvib.models.balancer import engine, layout, settling
from rotorvib.models.balancer.certificates import (
    _rotating_rows,
    certificates,
    linearisation,
    residual_whirl,
)
from rotorvib.models.balancer.criteria import BalanceCriterion, StopRule
from rotorvib.models.balancer.kinematics import disk_kinematics
from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.parameters import (
    Balancer,
    SpeedProfile,
    fixed_parameters,
    fixed_state,
    rotating_parameters,
)
from rotorvib.models.balancer.simulate import run, run_batch, simulate
from rotorvib.models.balancer.stability import jacobian

RULE = StopRule(margin=0.5, check_dt=0.02, neutral=1e-9)
MARGINAL = 0.006            # kg: m/M = eps_bar/2 at eps_bar = 0.012, the existence bound (34)
BEYOND = 0.0059             # kg: 2 m R = 0.983 M eps, a residual whirl of about 2.5e-5 m
# beyond the bound, residual whirls of 0.63, 0.71 and 0.55 of the threshold 1e-4 m: above the
# margin's share of it (mass, beta, kinematics, initial ball angles)
NEAR_THRESHOLD = [(0.012 / 2 * 0.96, 0.5, "printed", (40, 45)),
                  (0.012 / 2 * 0.955, 0.2, "consistent", (260, 265)),
                  (0.012 / 2 * 0.965, 1.0, "printed", (110, 115))]


def machine(mass=0.01, beta=1.0, eps_bar=0.012):
    return Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=mass, eps_bar=eps_bar, zeta=0.01,
                                 beta=beta)


def certificate(b, profile):
    return certificates(fixed_parameters(b, profile), RULE, 1e-3)[0]


@pytest.mark.parametrize("mass", [0.01, 0.02, MARGINAL])
def test_the_bounds_vanish_at_both_balanced_states(mass):
    b = machine(mass)
    S = certificate(b, SpeedProfile(200.0, "constant"))
    assert S[settling.ENABLED] == 1.0
    assert S[settling.QUASI_STATIC] == float(mass == MARGINAL)
    alpha = b.balanced_angle()
    for phi0 in ([alpha, -alpha], [-alpha, alpha], [alpha + 2 * np.pi, -alpha]):
        y = fixed_state(2, r0=0.0, theta0=0.0, phi0=phi0)
        for t in (0.3, 7.1):
            phi, phid, _ = disk_kinematics(t, fixed_parameters(b, SpeedProfile(200.0)))
            b_r, b_f = settling.bounds(S, y, phi, phid)
            assert b_r < 1e-12 and b_f < 1e-8
    # a deviation of one ball by 1e-3 rad is seen (first order, or second at the bound)
    y = fixed_state(2, r0=0.0, theta0=0.0, phi0=[alpha + 1e-3, -alpha])
    assert settling.bounds(S, y, 0.3, 200.0)[0] > 1e-8


@pytest.mark.parametrize("mass, omega", [(0.01, 2.0), (MARGINAL, 2.2), (0.02, 0.7)])
def test_the_linearisation_of_the_compiled_form_is_the_symbolic_one(mass, omega):
    """J by differences of the compiled rotating form against the sympy linearisation of the
    energies (rotorvib.models.balancer.stability), beta = 0.5, at and off the existence bound."""
    d = machine(mass, beta=0.5).dimensionless()
    alpha = np.arccos(max(-1.0, -1 / (2 * d.rho)))
    J = linearisation(np.array([d.mu, d.rho, d.zeta, d.beta, 2.0, omega, 1.0, 0.0]),
                      np.array([0.0, 0.0, alpha, -alpha, 0.0, 0.0, 0.0, 0.0]))
    assert np.abs(J - jacobian(d.mu, d.rho, d.zeta, d.beta, omega)).max() < 1e-9


def test_the_batch_groups_are_those_of_each_machine():
    """The certificates' rotating-form rows, built for a batch at once, are bit for bit those
    that each machine's checked groups give one at a time (Balancer.dimensionless,
    rotating_parameters), over machines far apart."""
    rng = np.random.default_rng(5)
    machines = [Balancer.from_paper_b(M=M, k=k, R=R, m_bar=m_bar, eps_bar=e, zeta=z, beta=b)
                for M, k, R, m_bar, e, z, b in rng.uniform(
                    [0.1, 1e2, 0.01, 1e-3, 1e-3, 0.0, 0.01], [50, 1e6, 1.0, 0.1, 0.1, 0.2, 5.0],
                    (200, 7))]
    fixed = np.array([fixed_parameters(b, SpeedProfile(1.0)) for b in machines])
    W = rng.uniform(0.1, 10.0, len(machines))
    expected = np.array([rotating_parameters(b.dimensionless(), SpeedProfile(w))
                         for b, w in zip(machines, W)])
    assert np.array_equal(_rotating_rows(fixed, W), expected)


def test_no_certificate_without_a_rest_point_that_decays():
    subcritical = SpeedProfile(50.0, "constant")        # below omega_n: the state is unstable
    S = certificate(machine(), subcritical)
    assert S[settling.ENABLED] == 0.0 and S[settling.CHECK_EVERY] == np.inf
    assert certificate(machine(), SpeedProfile(200.0, "runup", 0.5))[settling.T_FROM] == 0.5
    # beyond the existence bound below the critical speed, the balls rest beside the unbalance
    S = certificate(machine(mass=0.005), subcritical)
    assert S[settling.ENABLED] == 1.0 and abs(S[settling.A1]) < 0.1


def _rotating(b, omega):
    """The rotating form's parameter row of machine ``b`` at the constant speed ``omega``."""
    p = fixed_parameters(b, SpeedProfile(omega))
    return _rotating_rows(p[None], np.array([omega / np.sqrt(b.k / (b.M + b.n * b.m))]))[0]


def _at_rest(b, profile, t):
    """Machine ``b`` at its residual whirl at time ``t`` of ``profile`` (constant speed by
    then): the rotating-form rest point, the fixed-frame state there and the disk's angle and
    rate."""
    p = _rotating(b, profile.omega)
    rest = residual_whirl(*p[:3], p[5])[0]
    phi, phid, _ = disk_kinematics(t, fixed_parameters(b, profile))
    y = fixed_state(2, r0=0.0, theta0=0.0, phi0=rest[2:4])
    turn = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    y[0:2] = b.R * turn @ rest[0:2]
    y[4:6] = phid * np.array([-y[1], y[0]])                 # whirling with the disk
    return rest, y, phi, phid


def test_the_residual_whirl_is_a_rest_point_of_the_compiled_form():
    """Beyond the existence bound, over machines and speeds far apart: the residual whirl makes
    the compiled rotating form's right-hand side vanish to round-off, with both balls at one
    angle along the whirl, outwards (the ball equation's tangential pull vanishes)."""
    rng = np.random.default_rng(8)
    for _ in range(50):
        eps_bar = rng.uniform(0.002, 0.05)
        b = machine(mass=eps_bar / 2 * rng.uniform(0.05, 0.999), beta=rng.uniform(0.05, 2.0),
                    eps_bar=eps_bar)
        p = _rotating(b, rng.uniform(20.0, 600.0))
        rest = residual_whirl(*p[:3], p[5])[0]
        f = np.empty(8)
        engine.rhs_rotating(0.0, rest, p, f)
        assert np.abs(f).max() < 1e-14 * max(1.0, np.abs(rest).max() * p[5] ** 2)
        assert rest[2] == rest[3]
        assert abs(settling._wrap(np.angle(rest[0] + 1j * rest[1]) - rest[2])) < 1e-12


@pytest.mark.parametrize("kinematics", ["printed", "consistent"])
def test_a_run_beyond_the_bound_settles_at_the_certified_residual_whirl(kinematics):
    """Simulated without stopping from IC1 through the run-up, the run ends at the certificate's
    rest point: r at the residual whirl's radius and both balls at its angle; its bounds there
    are that radius and its force (k + c Omega) r_e, nothing more."""
    b = machine(BEYOND, beta=0.5)
    profile = SpeedProfile(200.0, "runup", 0.5, kinematics)
    S = certificate(b, profile)
    assert S[settling.ENABLED] == 1.0 and S[settling.QUASI_STATIC] == 1.0
    rest, y, phi, phid = _at_rest(b, profile, 200.0)
    assert rest[2] == S[settling.A1] == S[settling.A2]
    r_e = b.R * np.hypot(rest[0], rest[1])
    assert 2e-5 < r_e < 3e-5
    tr = simulate(b, profile, np.radians([40.0, 45.0]), 200.0, store=True, method="dop853",
                  rtol=1e-10, atol=1e-13, sample_dt=0.01)
    assert tr.r[-1] == pytest.approx(r_e, rel=1e-4)
    assert np.abs(settling._wrap(tr.y[-1, 2:4] - rest[2])).max() < 1e-3
    b_r, b_f = settling.bounds(S, y, phi, phid)
    assert b_r == pytest.approx(r_e, rel=1e-9)
    assert b_f == pytest.approx((b.k + b.c * 200.0) * r_e, rel=1e-9)


@pytest.mark.parametrize("mass, beta, kinematics, phi0", [
    (MARGINAL, 0.2, "printed", (40, 45)), (MARGINAL, 1.0, "consistent", (110, 115)),
    (0.01, 1.0, "printed", (260, 265)), (0.02, 0.3, "consistent", (10, 200)),
    (BEYOND, 0.5, "printed", (40, 45)), (BEYOND, 0.2, "consistent", (260, 265)),
    *NEAR_THRESHOLD])
def test_the_departure_from_the_rest_point_never_exceeds_its_bound_later(mass, beta, kinematics,
                                                                         phi0):
    """Along a whole run-up, at every sample after the ramp where the stop test could pass
    (``B_r - r_e <= margin (r_threshold - r_e)``, ``r_e`` the rest point's whirl: 0 at the
    balanced states), r at all later samples departs from r_e by at most ``B_r - r_e`` (no use
    of the margin); the bound is tight where r is one whirl mode (largest ratio near 1). Beyond
    the existence bound, within 1 %: the quasi-static whirl of the balls' current angles is the
    rest point's only at rest, and the departure came out at 1.003 of its bound at most, where
    the margin leaves a factor of 2."""
    b = machine(mass, beta)
    profile = SpeedProfile(200.0, "runup", 0.5, kinematics)
    p = fixed_parameters(b, profile)
    S = certificate(b, profile)
    r_e = settling.rest_whirl(S)[0]
    balanced = 2 * b.m * b.R >= b.M * b.eps
    if balanced:
        assert r_e < 1e-15
    else:
        rest = _at_rest(b, profile, 20.0)[0]
        assert r_e == pytest.approx(b.R * np.hypot(rest[0], rest[1]), rel=1e-12)
    tr = simulate(b, profile, np.radians(phi0), 20.0, store=True, method="dop853", rtol=1e-9,
                  atol=1e-12)
    later_max = np.maximum.accumulate(tr.r[::-1])[::-1]
    ratios = []
    for i in range(600, len(tr.t), 7):
        phi, phid, _ = disk_kinematics(tr.t[i], p)
        b_r = settling.bounds(S, tr.y[i], phi, phid)[0]
        if b_r - r_e <= RULE.margin * (1e-4 - r_e):
            ratios.append((later_max[i] - r_e) / (b_r - r_e))
    assert len(ratios) > 1000                   # from about 2 s after balancing on
    assert 0.9 < max(ratios) <= 1.0 + (1e-6 if balanced else 1e-2)


def test_stopping_changes_no_metric_and_saves_most_of_the_work(monkeypatch):
    """Random run-ups over the GA's bounds, half of them at the existence bound, and three
    groups beyond it: 2 m R within 2 % below M eps and 3.5-4.5 % below it (a residual whirl
    below the threshold, and above its margin's share of it) and 0.2-0.6 of M eps (one well
    above it, never balanced); both kinematics, three eccentricities: every
    metric equal bit for bit with and without stopping, the balanced runs end long before
    t_end, and so do those that never balance beyond the bound (the others at the bound or
    above it run to t_end); certificates computed a few runs at a time give the same metrics
    as all at once."""
    rng = np.random.default_rng(3)
    params, y0s, kappas = [], [], []
    for i in range(80):
        eps_bar = rng.choice([0.007, 0.009, 0.012])
        kappa = (rng.uniform(0.2, 0.6) if i >= 64 else rng.uniform(0.955, 0.965) if i >= 56
                 else rng.uniform(0.98, 1.0) if i >= 48 else None)
        mass = (eps_bar / 2 * kappa if kappa else MARGINAL if i % 2
                else rng.uniform(0.006, 0.02))
        b = machine(mass, rng.uniform(0.1, 1.0), eps_bar)
        kappas.append(2 * b.m * b.R / (b.M * b.eps))
        params.append(fixed_parameters(b, SpeedProfile(200.0, "runup", 0.5,
                                                       ("printed", "consistent")[i // 2 % 2])))
        y0s.append(fixed_state(2, r0=1e-3, theta0=0.0, phi0=rng.uniform(0, 2 * np.pi, 2)))
    criterion = BalanceCriterion(r_threshold=1e-4, f_threshold=1.0, t_end=20.0, sample_dt=1e-3)
    kw = dict(method="dop853", rtol=1e-7, atol=1e-10, progress=False)
    full = run_batch(layout.FIXED, np.array(params), np.array(y0s), criterion, **kw)
    stopped = run_batch(layout.FIXED, np.array(params), np.array(y0s), criterion, stop=RULE, **kw)
    for name in ("status", "balance_time", "balanced", "envelope_time", "envelope_balanced",
                 "force_max", "force_max_time", "force_decay_time", "force_decayed"):
        np.testing.assert_array_equal(metric(stopped, name), metric(full, name), err_msg=name)
    balanced = metric(full, "balanced") == 1.0
    beyond = np.array(kappas) < 0.7
    t_stop = metric(stopped, "t_stop")
    assert balanced.mean() > 0.7 and np.all(metric(full, "t_stop") == 20.0)
    assert np.all(t_stop[balanced] < 20.0) and np.all(t_stop[~balanced & ~beyond] == 20.0)
    assert np.all(~balanced[beyond]) and np.all(t_stop[beyond] < 20.0)
    assert np.all(t_stop[balanced] > metric(full, "balance_time")[balanced])
    assert metric(stopped, "n_steps").sum() < 0.5 * metric(full, "n_steps").sum()
    monkeypatch.setattr(runner, "CERTIFICATE_CHUNK", 5)
    chunked = run_batch(layout.FIXED, np.array(params), np.array(y0s), criterion, stop=RULE, **kw)
    assert chunked.tobytes() == stopped.tobytes()


def test_a_run_stops_once_its_balance_time_exceeds_its_bound():
    """A GA needs a run's balance time only below its bound (the worst of its population):
    random run-ups over the GA's bounds, each with a bound of 0-8 s or none. A run may stop early
    with status ABOVE_BOUND and every metric unknown only if it balances later than its bound
    or never, and must once it balanced later than its bound; every other run keeps all its
    metrics bit for bit."""
    rng = np.random.default_rng(5)
    n = 40
    params = np.array([fixed_parameters(machine(rng.uniform(0.006, 0.02), rng.uniform(0.1, 1.0)),
                                        SpeedProfile(200.0, "runup", 0.5,
                                                     ("printed", "consistent")[i % 2]))
                       for i in range(n)])
    y0s = np.array([fixed_state(2, r0=1e-3, theta0=0.0, phi0=rng.uniform(0, 2 * np.pi, 2))
                    for _ in range(n)])
    bounds = np.where(np.arange(n) % 5 == 0, np.inf, rng.uniform(0.0, 8.0, n))
    criterion = BalanceCriterion(r_threshold=1e-4, f_threshold=1.0, t_end=10.0, sample_dt=1e-3)
    kw = dict(method="dop853", rtol=1e-7, atol=1e-10, progress=False, stop=RULE)
    full = run_batch(layout.FIXED, params, y0s, criterion, **kw)
    bounded = run_batch(layout.FIXED, params, y0s, criterion, balance_bounds=bounds, **kw)
    above = metric(bounded, "status") == layout.ABOVE_BOUND
    time = np.where(metric(full, "balanced") == 1, metric(full, "balance_time"), np.inf)
    assert 5 < above.sum() < n - 5 and not above[np.isinf(bounds)].any()
    assert np.all(time[above] > bounds[above])
    assert np.all(above[(time > bounds) & (time < 9.9)])
    assert bounded[~above].tobytes() == full[~above].tobytes()
    unknown = [name for name in layout.METRICS if name not in ("status", "n_steps", "t_stop")]
    assert all(np.isnan(metric(bounded[above], name)).all() for name in unknown)
    assert np.all(metric(bounded, "t_stop")[above] < metric(full, "t_stop")[above])
    assert metric(bounded, "n_steps").sum() < 0.8 * metric(full, "n_steps").sum()
    with pytest.raises(ValueError, match="balance_bounds: one bound"):
        run_batch(layout.FIXED, params, y0s, criterion, balance_bounds=bounds[1:], **kw)
    with pytest.raises(ValueError, match="balance_bounds: needs a stop rule"):
        run_batch(layout.FIXED, params, y0s, criterion, balance_bounds=bounds,
                  **{**kw, "stop": None})


@pytest.mark.parametrize("kappa, beta, kinematics, phi0", [
    (0.5, 0.5, "printed", (40, 45)), (0.3, 0.2, "consistent", (260, 265))])
def test_a_run_that_never_balances_stays_above_its_lower_bounds(kappa, beta, kinematics, phi0):
    """Beyond the existence bound, along a whole run-up: at every sample after the ramp where
    the censored stop test passes (``margin L_r >= r_threshold``, ``margin L_F >=
    f_threshold``), r and F at all later samples stay above L_r and L_F (r within 1e-3 of it:
    the second-order terms, where the margin leaves a factor of 2)."""
    b = machine(0.012 / 2 * kappa, beta)
    profile = SpeedProfile(200.0, "runup", 0.5, kinematics)
    p = fixed_parameters(b, profile)
    S = certificate(b, profile)
    # at its rest point: r_min, the whirl of the least unbalance, just below the whirl there
    rest, y, phi, phid = _at_rest(b, profile, 20.0)
    r_min = settling.lower_bounds(S, y, phi, phid)[0]
    assert 2e-4 < r_min < b.R * np.hypot(rest[0], rest[1]) < r_min * (1 + 1e-3)
    tr = simulate(b, profile, np.radians(phi0), 20.0, store=True, method="dop853", rtol=1e-9,
                  atol=1e-12)
    force = tr.bearing_force(b.k, b.c)
    later_r = np.minimum.accumulate(tr.r[::-1])[::-1]
    later_f = np.minimum.accumulate(force[::-1])[::-1]
    ratios = []
    for i in range(600, len(tr.t), 7):
        phi, phid, _ = disk_kinematics(tr.t[i], p)
        l_r, l_f = settling.lower_bounds(S, tr.y[i], phi, phid)
        if RULE.margin * l_r >= 1e-4 and RULE.margin * l_f >= b.k * 1e-4:
            ratios.append((later_r[i] / l_r, later_f[i] / l_f))
    assert len(ratios) > 1000
    r_ratio, f_ratio = np.min(ratios, axis=0)
    assert r_ratio >= 1.0 - 1e-3 and f_ratio >= 1.0


def test_a_stale_numba_cache_is_emptied(tmp_path):
    (tmp_path / "a.py").write_text("x = 1\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()
    files = [cache / "a.f-1.py311.nbi", cache / "a.f-1.py311.1.nbc"]
    for f in files:
        f.write_text("compiled")
    assert drop_if_stale(tmp_path) and not any(f.exists() for f in files)
    for f in files:
        f.write_text("compiled")
    assert not drop_if_stale(tmp_path) and all(f.exists() for f in files)   # same sources
    (tmp_path / "a.py").write_text("x = 2\n")                               # one module edited
    assert drop_if_stale(tmp_path) and not any(f.exists() for f in files)
    assert (cache / MANIFEST).read_text() != ""


def test_the_compile_lock_is_exclusive_between_processes_and_released_after(tmp_path):
    """Another open of the lock file (as another process makes) cannot take it while it is
    held, and can once the block has ended."""
    def try_lock():
        with open(tmp_path / "__pycache__" / LOCK, "a") as other:
            try:
                fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                return False
            return True

    with compile_lock(tmp_path):
        assert not try_lock()
    assert try_lock()
    with compile_lock(tmp_path / "missing" / "folder"):    # cannot be made: nothing is held
        pass


def test_only_the_first_use_of_an_integrator_takes_the_compile_lock(monkeypatch):
    held = []

    @contextmanager
    def recorded(package_dir):
        held.append(Path(package_dir).name)
        yield

    monkeypatch.setattr(runner, "compile_lock", recorded)
    monkeypatch.setattr(runner, "_READY", set())
    p = fixed_parameters(machine(), SpeedProfile(200.0, "runup", 0.5, "printed"))
    y0 = fixed_state(2, r0=1e-3, theta0=0.0, phi0=np.radians([40.0, 45.0]))
    criterion = BalanceCriterion(1e-4, 1.0, 0.5, 1e-3)
    for method in ("dopri5", "dop853", "dopri5", "dop853"):
        run_batch(layout.FIXED, np.stack([p, p]), np.stack([y0, y0]), criterion, method=method,
                  progress=False)
        run(layout.FIXED, p, y0, criterion, method=method)
    assert held == ["balancer", "balancer"]
