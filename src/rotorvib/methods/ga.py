"""Seeded, vectorised genetic-algorithm minimisation (pymoo) with a per-generation history, and
the Pareto front of two or more objectives by NSGA-II.

Importing this module imports pymoo (and ``scipy.spatial``, about a tenth of a second): the
results are plain data in :mod:`rotorvib.methods.optima`, and a module whose other functions
serve jobs that run no search imports the search where it runs it."""

from __future__ import annotations

from typing import Callable

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.algorithms.soo.nonconvex.ga import GA
from pymoo.core.callback import Callback
from pymoo.core.problem import Problem
from pymoo.operators.crossover.sbx import SBX
from pymoo.operators.mutation.pm import PM

from rotorvib.checks import finite_array, integer, number
from rotorvib.methods.optima import GAResult, ParetoFront


class _HandedOver(Problem):
    """Box-bounded single-objective problem whose values are computed outside pymoo (all the
    problems of a lockstep run in one batch) and handed over before each evaluation."""

    def __init__(self, lower, upper):
        super().__init__(n_var=len(lower), n_obj=1, xl=lower, xu=upper)
        self._x = self._f = None

    def hand_over(self, x: np.ndarray, f: np.ndarray) -> None:
        self._x, self._f = x, f

    def _evaluate(self, x, out, *args, **kwargs):
        if not np.array_equal(x, self._x):
            raise RuntimeError("pymoo evaluated other points than it asked for")
        out["F"] = self._f[:, None]


def _checked(f, x: np.ndarray, worst: float = np.inf) -> np.ndarray:
    """The objective's values for the population ``x``: one finite number per point, or
    ``inf`` where the population it joins has a finite ``worst``."""
    f = np.asarray(f, dtype=float)
    if f.shape != (len(x),):
        raise ValueError(f"objective: returned shape {f.shape} for a population of "
                         f"{len(x)}, expected ({len(x)},)")
    bad = ~np.isfinite(f) & ~((f == np.inf) & np.isfinite(worst))
    if bad.any():
        raise FloatingPointError(f"objective: non-finite value at {int(bad.sum())} of "
                                 f"{len(x)} points, first x = {x[np.argmax(bad)].tolist()}")
    return f


def _worst(algorithm) -> float:
    """The largest objective value of ``algorithm``'s population; ``inf`` while it has fewer
    than ``pop_size`` members (an offspring then survives whatever its value)."""
    pop = algorithm.pop
    if pop is None or len(pop) < algorithm.pop_size:
        return np.inf
    return float(np.max(pop.get("F")))


class _History(Callback):
    def __init__(self, progress: Callable[[int, float], None] | None):
        super().__init__()
        self.rows = []
        self.progress = progress

    def notify(self, algorithm):
        f = algorithm.pop.get("F")[:, 0]
        best = algorithm.opt[0]
        self.rows.append((float(best.F[0]), float(np.mean(f)), algorithm.evaluator.n_eval,
                          np.array(best.X, dtype=float)))
        if self.progress is not None:
            self.progress(algorithm.n_gen, float(best.F[0]))

    def result(self, algorithm) -> GAResult:
        best_f, mean_f, n_eval, best_x = zip(*self.rows)
        opt = algorithm.result()
        return GAResult(x=np.asarray(opt.X, dtype=float), f=float(opt.F[0]),
                        history={"best_f": np.array(best_f), "mean_f": np.array(mean_f),
                                 "n_eval": np.array(n_eval), "best_x": np.array(best_x)})


def _check_arguments(lower, upper, pop_size, n_gen, seed, sbx_eta, pm_eta):
    lower = finite_array("lower", lower, shape=(None,))
    upper = finite_array("upper", upper, shape=lower.shape)
    if lower.size == 0 or np.any(lower >= upper):
        raise ValueError(f"lower = {lower.tolist()}, upper = {upper.tolist()}: need "
                         "lower < upper in every variable")
    integer("pop_size", pop_size, 2)
    integer("n_gen", n_gen, 1)
    for value in np.atleast_1d(np.asarray(seed, dtype=object)):
        integer("seed", value, 0)
    number("sbx_eta", sbx_eta)
    number("pm_eta", pm_eta)
    return lower, upper


def minimise_many(objectives: Callable[[list[np.ndarray], np.ndarray], list[np.ndarray]],
                  n_problems: int, lower, upper, *, pop_size: int, n_gen: int, seed,
                  sbx_eta: float = 15.0, pm_eta: float = 20.0,
                  progress: Callable[[int, float], None] | None = None) -> list[GAResult]:
    """Minimise ``n_problems`` objectives over the same box ``[lower, upper]`` with pymoo's
    real-coded GA (tournament selection, SBX crossover, polynomial mutation, fitness survival),
    each for exactly ``n_gen`` generations from ``seed`` (one for all, or one per problem: the
    same problem under several seeds gives the spread of its optimum), in lockstep: every
    generation, ``objectives([X_0, ..., X_{n-1}], worst) -> [f_0, ..., f_{n-1}]`` evaluates all
    the populations in one call (one batch of runs keeps every core busy).  Each algorithm draws
    from its own random generator, so the results equal those of ``n_problems`` separate runs of
    :func:`minimise`.  ``progress(generation, best_f)`` follows the first problem.

    ``worst[i]`` is the largest value of problem ``i``'s population (``inf`` for the first
    one).  Fitness survival keeps the ``pop_size`` smallest values of the population and its
    offspring together, so an offspring whose value exceeds ``worst[i]`` can never survive (the
    whole population beats it): the objective may score it ``inf`` instead of computing its
    value, and the search goes exactly as it would have (tested).

    Bad arguments (non-finite or empty box, ``lower >= upper``, non-integer sizes) raise
    ``ValueError`` naming them; a non-finite objective value (``inf`` but beyond a finite
    ``worst``) raises ``FloatingPointError``.
    """
    lower, upper = _check_arguments(lower, upper, pop_size, n_gen, seed, sbx_eta, pm_eta)
    n_problems = integer("n_problems", n_problems, 1)
    seeds = [seed] * n_problems if np.ndim(seed) == 0 else list(seed)
    if len(seeds) != n_problems:
        raise ValueError(f"seed: one seed or one per problem ({n_problems}), not {len(seeds)}")
    runs = []
    for i in range(n_problems):
        problem = _HandedOver(lower, upper)
        algorithm = GA(pop_size=pop_size, crossover=SBX(eta=sbx_eta), mutation=PM(eta=pm_eta),
                       eliminate_duplicates=True)
        history = _History(progress if i == 0 else None)
        algorithm.setup(problem, termination=("n_gen", n_gen), seed=seeds[i], callback=history,
                        verbose=False)
        runs.append((problem, algorithm, history))
    while runs[0][1].has_next():
        worst = np.array([_worst(algorithm) for _, algorithm, _ in runs])
        asked = [algorithm.ask() for _, algorithm, _ in runs]
        xs = [pop.get("X") for pop in asked]
        fs = [_checked(f, x, w) for f, x, w in zip(objectives(xs, worst), xs, worst)]
        for (problem, algorithm, _), pop, x, f in zip(runs, asked, xs, fs):
            problem.hand_over(x, f)
            algorithm.evaluator.eval(problem, pop, algorithm=algorithm)
            algorithm.tell(infills=pop)
    return [history.result(algorithm) for _, algorithm, history in runs]


def minimise(objective: Callable[[np.ndarray], np.ndarray], lower, upper, *, pop_size: int,
             n_gen: int, seed: int, sbx_eta: float = 15.0, pm_eta: float = 20.0,
             progress: Callable[[int, float], None] | None = None) -> GAResult:
    """Minimise ``objective(X) -> f`` (``X`` of shape ``(pop, n_var)``) over the box
    ``[lower, upper]``: :func:`minimise_many` with one problem.  Deterministic for a ``seed``."""
    return minimise_many(lambda xs, _: [objective(xs[0])], 1, lower, upper, pop_size=pop_size,
                         n_gen=n_gen, seed=seed, sbx_eta=sbx_eta, pm_eta=pm_eta,
                         progress=progress)[0]


class _Vectorised(Problem):
    """Box-bounded problem with ``n_obj`` objectives evaluated on a whole population at once."""

    def __init__(self, objectives, n_obj, lower, upper):
        super().__init__(n_var=len(lower), n_obj=n_obj, xl=lower, xu=upper)
        self._objectives = objectives

    def _evaluate(self, x, out, *args, **kwargs):
        f = np.asarray(self._objectives(x), dtype=float)
        if f.shape != (len(x), self.n_obj):
            raise ValueError(f"objectives: returned shape {f.shape} for a population of "
                             f"{len(x)}, expected ({len(x)}, {self.n_obj})")
        for j in range(self.n_obj):
            _checked(f[:, j], x)
        out["F"] = f


def pareto_front(objectives: Callable[[np.ndarray], np.ndarray], n_obj: int, lower, upper, *,
                 pop_size: int, n_gen: int, seed: int, sbx_eta: float = 15.0,
                 pm_eta: float = 20.0,
                 progress: Callable[[int], None] | None = None) -> ParetoFront:
    """Minimise ``objectives(X) -> F`` (``X`` of shape ``(pop, n_var)``, ``F`` of shape
    ``(pop, n_obj)``) over the box ``[lower, upper]`` with pymoo's NSGA-II (non-dominated
    sorting and crowding distance; SBX crossover, polynomial mutation) for exactly ``n_gen``
    generations; deterministic for a ``seed``.  ``progress(generation)`` is called after each
    generation.  Argument errors as :func:`minimise_many`."""
    lower, upper = _check_arguments(lower, upper, pop_size, n_gen, seed, sbx_eta, pm_eta)
    problem = _Vectorised(objectives, integer("n_obj", n_obj, 2), lower, upper)
    algorithm = NSGA2(pop_size=pop_size, crossover=SBX(eta=sbx_eta), mutation=PM(eta=pm_eta),
                      eliminate_duplicates=True)
    algorithm.setup(problem, termination=("n_gen", n_gen), seed=seed, verbose=False)
    while algorithm.has_next():
        algorithm.next()
        if progress is not None:
            progress(algorithm.n_gen - 1)   # pymoo counts on to the generation it runs next
    opt = algorithm.result()
    order = np.argsort(opt.F[:, 0], kind="stable")
    return ParetoFront(x=np.asarray(opt.X, float)[order], f=np.asarray(opt.F, float)[order],
                       n_eval=int(algorithm.evaluator.n_eval))
