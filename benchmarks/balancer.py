"""Benchmark of the ball-balancer engine against scipy's solve_ivp and numbalsoda.

Paper B's Fig 7 run (run-up of eq. 37, printed kinematics, two balls; machine, run and balance
criterion from ``config/config.yaml``, run from the repository root).  Every integrator -- the
engine with DOPRI5 and with DOP853, ``solve_ivp`` RK45 and DOP853 with the right-hand side as plain Python
(``rhs_fixed.py_func``) and compiled, numbalsoda's ``dop853`` and ``lsoda`` (a benchmark-only
dependency, ``benchmarks/requirements.txt``) on the same compiled right-hand side -- runs at the
loosest tolerance of a ladder (rtol 1e-5 ... 1e-10, atol = 1e-3 rtol) whose balance time lies
within ``--target`` seconds of a reference (the engine at rtol 1e-12), so that the ratios
compare equal accuracy; then the time of a batch of run-ups on all cores and the
cached-compilation time of a fresh process.

    python -m benchmarks.balancer [--runs 1000] [--target 1e-6] [--convergence | --stop |
                                   --ga-bound N]

``--convergence`` prints the convergence study behind paper B's integrator
(``paper_b.balance.integrator`` in the config): the errors
of the balance, envelope and force decay times and of the peak force of the same run, both
methods, rtol = 1e-6 ... 1e-10 (atol = 1e-3 rtol), against DOP853 at rtol 1e-13; then the
largest errors over a batch of ``--runs`` random run-ups (DOP853 with the stop rule, against
rtol 1e-12) and the batch's time at each rtol against rtol 1e-7.

``--stop`` prints the evidence behind stopping runs early (``paper_b.balance.stop``): the batch
of random run-ups with the configured integrator, a quarter of them beyond the existence bound,
with and without the stop rule, side by side: time, the share of runs that ended early (beyond
the bound: of those that balance and of those that never do) and the number of metrics that
differ (none may).

``--ga-bound N`` prints the evidence behind bounding the GA's runs: paper B's GA, its first ``N``
searches with the configured population and generations, with every run stopped once its
balance time exceeds the worst of its population (as the workflow runs it) and with every run
to its end, paired: CPU time, integration steps, the share of runs stopped above their bound,
and the searches whose results differ (none may).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from rotorvib.methods.ga import minimise_many
from rotorvib.models.balancer import engine, layout, settling
from rotorvib.models.balancer.certificates import certificates
from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.kinematics import disk_kinematics
from rotorvib.models.balancer.layout import METRICS, metric
from rotorvib.models.balancer.simulate import run, run_batch
from rotorvib.papers.b.optimise import balance_time_objectives, ga_searches
from rotorvib.papers.b.setup import Setup
from rotorvib.pipeline.config import load_yaml, validate_config

CONFIG = validate_config(load_yaml("config/config.yaml"), load_yaml("config/schema.yaml"))
B = CONFIG["paper_b"]
SETUP = Setup.from_paper_b(B)
CRITERION = SETUP.criterion
T_END, DT, R_THR = CRITERION.t_end, CRITERION.sample_dt, CRITERION.r_threshold


def case():
    """Fig 7's run (config paper_b.time_responses.fig7) under the printed kinematics."""
    fig7 = B["time_responses"]["fig7"]
    return SETUP.run_inputs(mass=fig7["m_bar"] * SETUP.M, eps_bar=fig7["eps_bar"],
                            beta=fig7["beta"], phi0_deg=fig7["phi0"], kinematics="printed")


def balance_time_of(t, r):
    above = np.flatnonzero(r >= R_THR)
    if above.size == 0 or above[-1] == len(r) - 1:
        return np.nan
    i = above[-1]
    return t[i] + (r[i] - R_THR) / (r[i] - r[i + 1]) * (t[i + 1] - t[i])


TIMES = np.arange(int(round(T_END / DT)) + 1) * DT
LADDER = (1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10)


def engine_run(p, y0, rtol, method="dopri5"):
    return run(layout.FIXED, p, y0, CRITERION, rtol=rtol, atol=rtol * 1e-3,
               method=method).balance_time


def scipy_run(p, y0, rtol, method, compiled):
    rhs = engine.rhs_fixed if compiled else engine.rhs_fixed.py_func

    def f(t, y):
        dy = np.empty_like(y)
        rhs(t, y, p, dy)
        return dy

    sol = solve_ivp(f, (0.0, T_END), y0, method=method, rtol=rtol, atol=rtol * 1e-3,
                    t_eval=TIMES)
    return balance_time_of(TIMES, np.hypot(sol.y[0], sol.y[1]))


def numbalsoda_solvers(n_state, n_param):
    """numbalsoda's ``dop853`` and ``lsoda`` on the engine's compiled right-hand side, as
    ``{name: run(p, y0, rtol)}``; empty where numbalsoda is not installed."""
    try:
        import numbalsoda
    except ImportError:
        return {}
    from numba import carray, cfunc

    rhs_fixed = engine.rhs_fixed

    @cfunc(numbalsoda.lsoda_sig)
    def rhs(t, u, du, p):
        rhs_fixed(t, carray(u, (n_state,)), carray(p, (n_param,)), carray(du, (n_state,)))

    def runner(solver):
        def run_one(p, y0, rtol):
            usol, ok = solver(rhs.address, y0.copy(), TIMES, data=p.copy(), rtol=rtol,
                              atol=rtol * 1e-3, mxstep=10**8)
            return balance_time_of(TIMES, np.hypot(usol[:, 0], usol[:, 1])) if ok else np.nan
        return run_one

    return {"numbalsoda dop853, compiled rhs": runner(numbalsoda.dop853),
            "numbalsoda lsoda, compiled rhs": runner(numbalsoda.lsoda)}


def at_equal_accuracy(run_one, p, y0, reference, target, repeats):
    """The loosest rtol of :data:`LADDER` whose balance time is within ``target`` of
    ``reference``, and the best of ``repeats`` timed runs there: ``(rtol, seconds, error)``."""
    for rtol in LADDER:
        error = abs(run_one(p, y0, rtol) - reference)
        if error <= target:
            elapsed, _ = best_of(repeats, lambda: run_one(p, y0, rtol))
            return rtol, elapsed, error
    return np.nan, np.nan, np.nan


def best_of(n, fn):
    times = []
    for _ in range(n):
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return min(times), out


def convergence(p, y0):
    """Balance time, envelope time, force decay time and peak force of both methods against
    the tolerance, beside a reference (DOP853 at rtol 1e-13)."""
    ref = run(layout.FIXED, p, y0, CRITERION, rtol=1e-13, atol=1e-16, method="dop853")
    print(f"reference: balance {ref.balance_time:.9f} s, envelope {ref.envelope_time:.9f} s, "
          f"force decay {ref.force_decay_time:.9f} s, peak force {ref.force_max:.9f} N")
    print(f"{'method':>7} {'rtol':>6} {'steps':>7} {'d balance (s)':>14} {'d envelope (s)':>15} "
          f"{'d decay (s)':>12} {'d peak (rel)':>13}")
    for method in ("dopri5", "dop853"):
        for rtol in (1e-6, 3e-7, 1e-7, 1e-8, 1e-9, 1e-10):
            res = run(layout.FIXED, p, y0, CRITERION, rtol=rtol, atol=rtol * 1e-3, method=method)
            print(f"{method:>7} {rtol:6.0e} {res.n_steps:7d} "
                  f"{res.balance_time - ref.balance_time:14.1e} "
                  f"{res.envelope_time - ref.envelope_time:15.1e} "
                  f"{res.force_decay_time - ref.force_decay_time:12.1e} "
                  f"{res.force_max / ref.force_max - 1:13.1e}")


def batch_inputs(p, y0, runs):
    """``runs`` variants of the run: ball damping D scaled by 0.1 .. 1, half of them with Fig
    7's ball mass and half with any mass up to 2x it, balls anywhere."""
    rng = np.random.default_rng(1)
    params = np.repeat(p[None], runs, axis=0)
    params[:, 6] *= rng.uniform(0.1, 1.0, runs)                   # ball damping D
    params[1::2, 1] *= rng.uniform(0.6, 2.0, runs // 2)            # ball mass m (D scales too)
    params[1::2, 6] *= params[1::2, 1] / p[1]
    y0s = np.repeat(y0[None], runs, axis=0)
    y0s[:, 2:4] = rng.uniform(0, 2 * np.pi, (runs, 2))             # initial ball angles
    return params, y0s


def beyond_the_bound(p, params):
    """Every fourth run of the batch ``params`` given a ball mass 0.2 .. 1 of the existence
    bound's ``M eps / (2 R)`` (D scaled with it): some balance at a residual whirl below the
    threshold, the others never; which of the batch's runs they are."""
    rng = np.random.default_rng(2)
    beyond = np.zeros(len(params), bool)
    beyond[3::4] = True
    M, R, eps = p[0], p[2], p[3]
    mass = M * eps / (2 * R) * rng.uniform(0.2, 1.0, beyond.sum())
    params[beyond, 6] *= mass / params[beyond, 1]
    params[beyond, 1] = mass
    return beyond


def bound_room(params, y0s, runs):
    """How far the linear bounds of the stop rule miss, on ``runs`` of the batch integrated
    to ``t_end`` with every sample kept: at the first check after the run-up where the upper
    bounds pass with no margin (``B_r <= r_threshold``, ``B_F <= f_threshold``), the largest
    departure of all later samples' ``r`` and ``F`` from the rest point's ``r_e`` and ``F_e``
    over the bounds' ``B_r - r_e`` and ``B_F - F_e`` (:mod:`settling`); at the first where the lower
    bounds of a run that never balances pass with none, the smallest over ``L_r`` and ``L_F``:
    the room ``margin`` must leave (a run stops at a later check, nearer its rest point)."""
    stops = certificates(params[:runs], SETUP.stop, DT)
    above, below = np.zeros(2), np.full(2, np.inf)
    for p_i, y0, S in zip(params[:runs], y0s[:runs], stops):
        if S[settling.ENABLED] == 0.0:
            continue
        tr = run(layout.FIXED, p_i, y0, CRITERION, store=True, **SETUP.tolerances)
        values = (tr.r, tr.bearing_force(p_i[4], p_i[5]))
        high = [np.maximum.accumulate(v[::-1])[::-1] for v in values]
        low = [np.minimum.accumulate(v[::-1])[::-1] for v in values]
        upper = lower = False
        for j in range(int(S[settling.T_FROM] / DT) + 1, len(tr.t) - 1,
                       int(S[settling.CHECK_EVERY])):
            phi, phid, _ = disk_kinematics(tr.t[j], p_i)
            b = settling.bounds(S, tr.y[j], phi, phid)
            if not upper and b[0] <= R_THR and b[1] <= CRITERION.f_threshold:
                rest = settling.rest_whirl(S)
                above = np.maximum(above, [(high[i][j] - rest[i]) / (b[i] - rest[i])
                                           for i in range(2)])
                upper = True
            lo = settling.lower_bounds(S, tr.y[j], phi, phid)      # < 0 where balls can balance
            if not lower and lo[0] >= R_THR and lo[1] >= CRITERION.f_threshold:
                below = np.minimum(below, [low[0][j] / lo[0], low[1][j] / lo[1]])
                lower = True
    print(f"room for the margin ({SETUP.stop.margin:g}), {runs} of the runs to t_end: later r "
          f"and F depart from the rest point at most {above[0]:.5f} and {above[1]:.5f} of B_r - "
          f"r_e and B_F - F_e; in runs that never "
          f"balance at least {below[0]:.5f} and {below[1]:.5f} of L_r and L_F")


def stop_study(p, y0, runs):
    """The batch with the configured integrator, with and without the stop rule, paired; a
    quarter of its runs beyond the existence bound (:func:`beyond_the_bound`)."""
    params, y0s = batch_inputs(p, y0, runs)
    beyond = beyond_the_bound(p, params)
    kw = dict(progress=False, **SETUP.tolerances)
    run_batch(layout.FIXED, params[:2], y0s[:2], CRITERION, stop=SETUP.stop, **kw)  # compile
    times, metrics = {False: [], True: []}, {}
    for _ in range(3):
        for stop in (False, True):
            start = time.perf_counter()
            metrics[stop] = run_batch(layout.FIXED, params, y0s, CRITERION,
                                      stop=SETUP.stop if stop else None, **kw)
            times[stop].append(time.perf_counter() - start)
    full, stopped = metrics[False], metrics[True]
    names = [n for n in METRICS if n not in ("n_steps", "t_stop")]
    differ = sum(int(np.sum(~((metric(full, n) == metric(stopped, n))
                              | (np.isnan(metric(full, n)) & np.isnan(metric(stopped, n))))))
                 for n in names)
    balanced = metric(full, "balanced") == 1
    t_stop = metric(stopped, "t_stop")
    print(f"{runs} run-ups, {SETUP.method} rtol {SETUP.rtol:g}, stop rule {SETUP.stop}; "
          f"best of 3 on all cores")
    print(f"to t_end = {T_END:g} s: {min(times[False]):.2f} s; with the stop rule: "
          f"{min(times[True]):.2f} s ({min(times[True]) / min(times[False]):.2f}x), steps "
          f"{metric(stopped, 'n_steps').sum() / metric(full, 'n_steps').sum():.2f}x")
    print(f"balanced {balanced.mean() * 100:.0f} %; ended early "
          f"{np.mean(t_stop < T_END) * 100:.0f} %, median {np.median(t_stop[balanced] - metric(full, 'balance_time')[balanced]):.2f} s"
          f" after the balance time; metrics that differ: {differ} of {len(names) * runs}")
    for label, runs_of in (("balanced", balanced), ("never balanced", ~balanced)):
        mine = beyond & runs_of
        print(f"beyond the existence bound, {label}: {mine.sum()} runs, ended early "
              f"{np.mean(t_stop[mine] < T_END) * 100:.0f} %")
    bound_room(params, y0s, min(runs, 200))


class _Recorded(Setup):
    """Paper B's setup that keeps the metrics of every batch it runs (in ``RECORDED``)."""

    def runs(self, inputs, **kwargs):
        metrics = super().runs(inputs, **kwargs)
        RECORDED.append(metrics)
        return metrics


RECORDED: list = []


def ga_bound_study(n_searches):
    """Paper B's GA (its first ``n_searches``) with its runs bounded by the worst of their
    populations and without, paired, twice each."""
    ga = B["ga"]
    searches = ga_searches(B["kinematics"], ga["eps_bar"], B["initial_conditions"],
                           [ga["seed"], *ga["spread_seeds"]])[:n_searches]
    objectives = balance_time_objectives(_Recorded.from_paper_b(B), [p for p, _ in searches],
                                         censored_penalty=ga["censored_penalty"])

    def unbounded(xs, worst):
        return objectives(xs, np.full(len(xs), np.inf))

    def search(bounded):
        RECORDED.clear()
        start = time.process_time()
        results = minimise_many(objectives if bounded else unbounded, len(searches),
                                [ga["beta"][0], ga["mass"][0]], [ga["beta"][1], ga["mass"][1]],
                                pop_size=ga["pop_size"], n_gen=ga["n_gen"],
                                seed=[s for _, s in searches])
        return time.process_time() - start, results, np.concatenate(RECORDED)

    search(True)                                                      # compile
    cpu, out = {False: [], True: []}, {}
    for _ in range(2):
        for bounded in (False, True):
            elapsed, *out[bounded] = search(bounded)
            cpu[bounded].append(elapsed)
    (full, full_runs), (cut, cut_runs) = out[False], out[True]
    differ = sum(not (np.array_equal(a.x, b.x) and a.f == b.f
                      and all(np.array_equal(a.history[k], b.history[k]) for k in a.history))
                 for a, b in zip(full, cut))
    above = metric(cut_runs, "status") == layout.ABOVE_BOUND
    print(f"paper B's GA, {len(searches)} searches x population {ga['pop_size']} x "
          f"{ga['n_gen']} generations ({len(cut_runs)} runs), CPU seconds of 2 rounds each")
    print(f"every run to its end: {sum(cpu[False]):.1f}; bounded by the worst of its "
          f"population: {sum(cpu[True]):.1f} ({sum(cpu[True]) / sum(cpu[False]):.3f}x); steps "
          f"{metric(cut_runs, 'n_steps').sum() / metric(full_runs, 'n_steps').sum():.3f}x")
    print(f"runs stopped above their bound: {above.sum()} ({above.mean() * 100:.0f} %); "
          f"searches whose results differ: {differ} of {len(searches)}")


def batch_convergence(p, y0, runs):
    """Largest errors over a batch of random run-ups against DOP853 at rtol 1e-12, and the
    batch's time, at each rtol (DOP853, stop rule of the config)."""
    params, y0s = batch_inputs(p, y0, runs)

    def batch(rtol):
        return run_batch(layout.FIXED, params, y0s, CRITERION, method="dop853", rtol=rtol,
                         atol=rtol * 1e-3, stop=SETUP.stop, progress=False)

    ref = batch(1e-12)
    times = {rtol: best_of(3, lambda: batch(rtol)) for rtol in (1e-7, 1e-6, 3e-6, 1e-5)}
    print(f"\n{runs} random run-ups (DOP853, stop rule), largest errors against rtol 1e-12:")
    print(f"{'rtol':>6} {'time':>6} {'balance (s)':>12} {'envelope (s)':>13} {'decay (s)':>10} "
          f"{'peak (rel)':>11} {'censoring':>10}")
    for rtol, (elapsed, out) in times.items():
        errors = [np.nanmax(np.abs(metric(out, n) - metric(ref, n)))
                  for n in ("balance_time", "envelope_time", "force_decay_time")]
        peak = np.max(np.abs(metric(out, "force_max") / metric(ref, "force_max") - 1))
        flips = int(np.sum(metric(out, "balanced") != metric(ref, "balanced")))
        print(f"{rtol:6.0e} {elapsed / times[1e-7][0]:5.2f}x "
              + " ".join(f"{e:{w}.1e}" for e, w in zip(errors, (12, 13, 10)))
              + f" {peak:11.1e} {flips:10d}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--target", type=float, default=1e-6,
                        help="balance-time error allowed against the reference (s)")
    parser.add_argument("--convergence", action="store_true",
                        help="print the tolerance convergence study instead")
    parser.add_argument("--stop", action="store_true",
                        help="print the evidence of the stop rule instead")
    parser.add_argument("--ga-bound", type=int, metavar="N",
                        help="print the evidence of the GA's bounded runs (N searches) instead")
    args = parser.parse_args()
    if args.ga_bound:
        ga_bound_study(args.ga_bound)
        return
    p, y0 = case()
    if args.convergence:
        convergence(p, y0)
        batch_convergence(p, y0, args.runs)
        return
    if args.stop:
        stop_study(p, y0, args.runs)
        return
    run(layout.FIXED, p, y0, BalanceCriterion(R_THR, CRITERION.f_threshold, 0.1, DT))  # compile
    reference = engine_run(p, y0, 1e-12)
    engine_run(p, y0, 1e-6, "dop853")  # compile
    integrators = {"engine (DOPRI5, numba)": engine_run,
                   "engine (DOP853, numba)": lambda p_, y_, r: engine_run(p_, y_, r, "dop853"),
                   **numbalsoda_solvers(y0.size, p.size)}
    for compiled in (True, False):
        for method in ("DOP853", "RK45"):
            label = f"solve_ivp {method}, {'compiled' if compiled else 'plain Python'} rhs"
            integrators[label] = (lambda m, c: lambda p_, y_, r: scipy_run(p_, y_, r, m, c))(
                method, compiled)
    print(f"balance time within {args.target:g} s of {reference:.9f} s (engine, rtol 1e-12); "
          "best of 3 runs each")
    print(f"{'integrator':36s} {'rtol':>6} {'one run':>10} {'ratio':>7} {'error (s)':>10}")
    base = None
    for label, run_one in integrators.items():
        rtol, elapsed, error = at_equal_accuracy(run_one, p, y0, reference, args.target, 3)
        base = base or elapsed
        print(f"{label:36s} {rtol:6.0e} {elapsed * 1e3:8.1f} ms {elapsed / base:6.2f}x "
              f"{error:10.1e}")
    params, y0s = batch_inputs(p, y0, args.runs)
    run_batch(layout.FIXED, params[:2], y0s[:2], BalanceCriterion(R_THR, CRITERION.f_threshold, 0.1, DT),
              progress=False)
    start = time.perf_counter()
    metrics = run_batch(layout.FIXED, params, y0s, CRITERION, progress=False)
    batch = time.perf_counter() - start
    print(f"batch of {args.runs} run-ups (20 s each) on all cores: {batch:.2f} s "
          f"({np.mean(metric(metrics, 'balanced') == 1) * 100:.0f} % balanced, "
          f"{np.sum(metric(metrics, 'status') != layout.OK)} failed)")
    c = CRITERION
    probe = ("import time; t = time.perf_counter(); import numpy as np; "
             "from rotorvib.models.balancer import layout; "
             "from rotorvib.models.balancer.criteria import BalanceCriterion; "
             "from rotorvib.models.balancer.simulate import run; "
             f"run(layout.FIXED, np.array({p.tolist()}), np.array({y0.tolist()}), "
             f"BalanceCriterion({c.r_threshold!r}, {c.f_threshold!r}, 0.01, {c.sample_dt!r})); "
             "print(time.perf_counter() - t)")
    load = float(subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                                check=True).stdout)
    print(f"fresh process, cached compilation: import + first run {load:.2f} s")


if __name__ == "__main__":
    main()
