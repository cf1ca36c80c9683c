"""Public simulation API of the ball-balancer engine: one run, a trajectory, a batch.

A failed integration raises :class:`~rotorvib.methods.integrate.IntegrationError` (single runs) or is
flagged in the ``status`` column (batches, with :func:`check_batch` to raise); a run that is not
balanced by its end is *censored*: its balance time is NaN and ``censored`` is True.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotorvib.checks import finite_array, flag, instance, integer, number
from rotorvib.io.progress import Progress
from rotorvib.methods.integrate import IntegrationError, check_tolerances
from rotorvib.methods.numba_cache import compile_lock, record
from rotorvib.models.balancer import dop853, engine, inputs, layout, settling
from rotorvib.models.balancer.certificates import certificates
from rotorvib.models.balancer.criteria import ATOL, METHOD, RTOL, BalanceCriterion, StopRule
from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.outcomes import outcome
from rotorvib.models.balancer.parameters import (Balancer, SpeedProfile, fixed_parameters,
                                                 fixed_state)

MAX_STEPS = 50_000_000
#: Threads that a batch shares its runs out to (:func:`use_threads`): all cores by default.
THREADS = os.cpu_count() or 1
#: Runs of a batch whose stop certificates are computed and held at a time (a row is 1.3 KB;
#: computing one takes about 12 KB while it lasts: tracemalloc).
CERTIFICATE_CHUNK = 4096
#: The compiled integrators this process has called (compiled or loaded from the cache) already.
_READY: set = set()


@contextmanager
def _first_use(integrator):
    """The first time this process runs ``integrator``, run the block under the package's
    compile lock (:func:`rotorvib.methods.numba_cache.compile_lock`): jobs that start together
    on an empty cache compile it once, not once each; then record the numba files in the
    package's manifest, so that a later process finds a damaged one."""
    if integrator in _READY:
        yield
        return
    package = Path(__file__).parent
    with compile_lock(package):
        yield
        record(package)              # the numba files now written or loaded, as they are
    _READY.add(integrator)


@dataclass(frozen=True)
class RunResult:
    """Balance time (threshold and envelope definitions) and bearing force of one run."""

    balance_time: float
    censored: bool
    envelope_time: float
    envelope_censored: bool
    force_max: float
    force_max_time: float
    force_decay_time: float
    force_censored: bool
    t_end: float
    n_steps: int

    @classmethod
    def from_metrics(cls, m, t_end) -> "RunResult":
        value = {name: float(metric(m, name)) for name in layout.METRICS}
        return cls(balance_time=value["balance_time"], censored=not value["balanced"],
                   envelope_time=value["envelope_time"],
                   envelope_censored=not value["envelope_balanced"],
                   force_max=value["force_max"], force_max_time=value["force_max_time"],
                   force_decay_time=value["force_decay_time"],
                   force_censored=not value["force_decayed"], t_end=float(t_end),
                   n_steps=int(value["n_steps"]))


@dataclass(frozen=True)
class Trajectory:
    """Sampled solution: ``t`` and ``y`` (rows of the form's state), with the run's result."""

    t: np.ndarray
    y: np.ndarray
    result: RunResult

    @property
    def n_balls(self) -> int:
        return self.y.shape[1] // 2 - 2

    @property
    def r(self) -> np.ndarray:
        """Whirl radius of the geometric centre (m in the FIXED form, units of R in ROTATING)."""
        return np.hypot(self.y[:, 0], self.y[:, 1])

    def bearing_force(self, k: float, c: float) -> np.ndarray:
        """``F = k r + c r'`` (paper B, eq. 40) at the samples (FIXED form)."""
        n = self.n_balls
        x, y, xd, yd = self.y[:, 0], self.y[:, 1], self.y[:, n + 2], self.y[:, n + 3]
        r = self.r
        rdot = np.divide(x * xd + y * yd, r, out=np.zeros_like(r), where=r > 0)
        return k * r + c * rdot


def _checked(form, params, y0s, criterion, rtol, atol, names=("params", "y0s")):
    """The form code and the parameter and state rows of a run or batch, checked
    (:mod:`inputs`) with the criterion and tolerances: ``ValueError`` naming the argument."""
    form = inputs.form(form)
    instance("criterion", criterion, BalanceCriterion)
    check_tolerances(rtol, atol)
    params = inputs.parameter_rows(form, params, names[0])
    inputs.work(form, params, criterion.t_end, names[0])
    return form, params, inputs.state_rows(form, params, y0s, *names[::-1])


def _raise_on_failure(m):
    status = int(metric(m, "status"))
    if status != layout.OK:
        raise IntegrationError(f"balancer integration failed: {layout.STATUS_TEXT[status]} "
                               f"after {int(metric(m, 'n_steps'))} steps")


def _integrator(method: str):
    """The compiled integrator of ``method`` and the arguments that follow the common ones
    (DOP853's tableau)."""
    if not isinstance(method, str) or method not in dop853.METHODS:
        raise ValueError(f"method = {method!r}: must be one of {sorted(dop853.METHODS)}")
    if dop853.METHODS[method] == dop853.DOP853:
        return dop853.integrate_dop853, dop853.tableau()
    return engine.integrate, ()


def run(form: int, p: np.ndarray, y0: np.ndarray, criterion: BalanceCriterion, *,
        rtol: float = RTOL, atol: float = ATOL, method: str = METHOD, store: bool = False):
    """Integrate one run from t = 0 to ``criterion.t_end`` with ``method`` ("dopri5" or
    "dop853"); return a :class:`Trajectory` (``store=True``) or a :class:`RunResult`.
    ``p`` is a parameter row of the form's layout (``layout.P_FIXED`` or ``layout.P_ROT``),
    ``y0`` the state of its ``n`` balls, ``2 (n + 2)`` entries; ``ValueError`` names an argument
    out of range (:mod:`inputs`)."""
    p, y0 = finite_array("p", p, shape=(None,)), finite_array("y0", y0, shape=(None,))
    form, params, states = _checked(form, p[None], y0[None], criterion, rtol, atol,
                                    names=("p", "y0"))
    flag("store", store)
    integrate, tableau = _integrator(method)
    c = criterion
    out = np.empty((c.n_samples if store else 0, states.shape[1]))
    args = (form, params[0], states[0], 0.0, float(c.t_end), rtol, atol,
            c.sample_dt, c.r_threshold, c.f_threshold, MAX_STEPS, out, settling.disabled())
    with _first_use(integrate):
        m = integrate(*args, *tableau)
    _raise_on_failure(m)
    if form == layout.FIXED:
        m[layout.COLUMN["outcome"]] = outcome(m, params[0])
    result = RunResult.from_metrics(m, c.t_end)
    if not store:
        return result
    return Trajectory(t=c.times, y=out, result=result)


def simulate(b: Balancer, profile: SpeedProfile, phi0, t_end: float, *, r0: float = 1e-3,
             theta0: float = 0.0, sample_dt: float = 1e-3, r_threshold: float = 1e-4,
             f_threshold: float | None = None, store: bool = False, **tolerances):
    """Paper B's balancer from rest relative to the disk, C at ``(r0, theta0)``, balls at
    ``phi0`` (rad) (eq. 36).  The force threshold defaults to ``k r_threshold`` (the force of
    the balance criterion).  Returns a :class:`RunResult`, or a :class:`Trajectory` with
    ``store=True``.  Raises ``ValueError`` naming an argument out of range: ``b`` and
    ``profile`` check their own fields, the rest is checked here and by :func:`run`."""
    instance("b", b, Balancer)
    instance("profile", profile, SpeedProfile)
    y0 = fixed_state(b.n, r0=number("r0", r0, inclusive=True),
                     theta0=number("theta0", theta0, minimum=-np.inf),
                     phi0=finite_array("phi0", phi0, shape=(b.n,)))
    criterion = BalanceCriterion(r_threshold=r_threshold, t_end=t_end, sample_dt=sample_dt,
                                 f_threshold=b.k * r_threshold if f_threshold is None
                                 else f_threshold)
    return run(layout.FIXED, fixed_parameters(b, profile), y0, criterion, store=store,
               **tolerances)


def run_batch(form: int, params: np.ndarray, y0s: np.ndarray, criterion: BalanceCriterion, *,
              rtol: float = RTOL, atol: float = ATOL, method: str = METHOD,
              stop: StopRule | None = None, balance_bounds=None, seed: int = 0,
              chunk: int = 256, progress: bool = True) -> np.ndarray:
    """Metrics (rows of ``layout.METRICS``, read with :func:`metric`) of many runs, on
    :data:`THREADS` threads; with a ``stop`` rule (FIXED form) a run ends once its metrics are
    known (:mod:`settling`), else at ``criterion.t_end``.  With it, ``balance_bounds`` (one per
    run, ``inf`` for none) asks only whether a run's balance time exceeds its bound: a run ends
    as soon as it is known to, with status ``layout.ABOVE_BOUND`` and every metric unknown
    (NaN) -- a search that only needs the times below a bound (:mod:`rotorvib.methods.ga`).

    Each run is one call of the compiled integrator, which releases the GIL: the threads take
    the runs of a shuffled (seeded) order one at a time as they come free, so that long and
    short runs mix, and a batch compiles nothing beyond the single run's integrator (its first
    use in a process, with the stop certificates and one run, holds the compile lock:
    :func:`_first_use`). Runs are processed in chunks of ``chunk`` so that progress can be
    logged (the runs done of the total, the time elapsed and left:
    :class:`rotorvib.io.progress.Progress`; in one piece without it); their stop certificates
    are computed :data:`CERTIFICATE_CHUNK` runs at a time, so that a batch holds little more
    than its inputs and metrics. Failed runs are flagged in the ``status`` column, not raised:
    see :func:`check_batch`.  ``params`` holds one parameter row per run
    (``layout.P_FIXED`` or ``layout.P_ROT``), ``y0s`` one state row per run; every argument is
    checked first (:mod:`inputs`), with ``ValueError`` naming it.
    """
    c = criterion
    form, params, y0s = _checked(form, params, y0s, criterion, rtol, atol)
    instance("stop", stop, StopRule, optional=True)
    if balance_bounds is not None:
        if stop is None or form != layout.FIXED:
            raise ValueError("balance_bounds: needs a stop rule and the FIXED form")
        balance_bounds = np.asarray(balance_bounds, dtype=float)
        if balance_bounds.shape != (len(params),) or np.isnan(balance_bounds).any():
            raise ValueError(f"balance_bounds: one bound (a number or inf) per run "
                             f"({len(params)}), got shape {balance_bounds.shape}")
    seed, chunk = integer("seed", seed, 0), integer("chunk", chunk, 1)
    progress = flag("progress", progress)
    integrate, tableau = _integrator(method)
    n = params.shape[0]
    order = np.random.default_rng(seed).permutation(n)
    result = np.empty((n, layout.N_METRICS))
    no_samples = np.empty((0, y0s.shape[1]))

    def stop_rows(runs):
        """The certificate rows (:mod:`settling`) of the runs ``runs`` (indices)."""
        if stop is None or form != layout.FIXED:
            return np.tile(settling.disabled(), (len(runs), 1))
        rows = certificates(params[runs], stop, c.sample_dt)
        if balance_bounds is not None:             # checked for the bound, if not to settle
            bounded = np.isfinite(balance_bounds[runs])
            rows[bounded, settling.BALANCE_BOUND] = balance_bounds[runs][bounded]
            rows[bounded, settling.CHECK_EVERY] = stop.check_every(c.sample_dt)
        return rows

    def take(runs):
        for i, stop_row in runs:
            result[i] = integrate(form, params[i], y0s[i], 0.0, float(c.t_end), rtol, atol,
                                  c.sample_dt, c.r_threshold, c.f_threshold, MAX_STEPS,
                                  no_samples, stop_row, *tableau)

    with _first_use(integrate):
        take(zip(order[:1], stop_rows(order[:1])))
    chunk = chunk if progress else n
    report = Progress("balancer runs", n) if progress and n > chunk else None
    with ThreadPoolExecutor(THREADS) as pool:
        for block in range(1, n, CERTIFICATE_CHUNK):
            runs = order[block:block + CERTIFICATE_CHUNK]
            stops = stop_rows(runs)
            for start in range(0, len(runs), chunk):
                shared = iter(zip(runs[start:start + chunk], stops[start:start + chunk]))
                list(pool.map(take, [shared] * THREADS))   # each thread takes the next run
                if report is not None:
                    report(block + min(start + chunk, len(runs)))
    if form == layout.FIXED:
        result[:, layout.COLUMN["outcome"]] = outcome(result, params)
    return result


def check_batch(metrics: np.ndarray) -> None:
    """Raise :class:`IntegrationError` listing the runs of a batch that failed (a run stopped
    above its balance-time bound has not failed)."""
    status = metric(metrics, "status")
    failed = np.flatnonzero(~np.isin(status, (layout.OK, layout.ABOVE_BOUND)))
    if failed.size:
        kinds = {layout.STATUS_TEXT[int(s)] for s in status[failed]}
        raise IntegrationError(f"{failed.size} of {len(metrics)} balancer runs failed "
                               f"({', '.join(sorted(kinds))}); first: run {failed[0]}")


def use_threads(n: int) -> None:
    """Share a batch's runs out to ``n`` threads (a workflow job's threads)."""
    global THREADS
    THREADS = max(1, int(n))
