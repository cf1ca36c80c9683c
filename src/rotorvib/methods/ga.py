"""Seeded, vectorised genetic-algorithm minimisation (pymoo) with a per-generation history."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from pymoo.algorithms.soo.nonconvex.ga import GA
from pymoo.core.callback import Callback
from pymoo.core.problem import Problem
from pymoo.operators.crossover.sbx import SBX
from pymoo.operators.mutation.pm import PM
from pymoo.optimize import minimize as pymoo_minimize

from rotorvib.checks import finite_array, integer


@dataclass(frozen=True)
class GAResult:
    """Optimum ``x`` with objective ``f``, and per-generation ``history`` arrays:
    ``best_f``, ``mean_f`` (population), ``n_eval`` (cumulative) and ``best_x``."""

    x: np.ndarray
    f: float
    history: dict[str, np.ndarray]


class _Batch(Problem):
    """Box-bounded single-objective problem evaluated on the whole population at once."""

    def __init__(self, objective, lower, upper):
        super().__init__(n_var=len(lower), n_obj=1, xl=np.asarray(lower, float),
                         xu=np.asarray(upper, float))
        self._objective = objective

    def _evaluate(self, x, out, *args, **kwargs):
        f = np.asarray(self._objective(x), dtype=float)
        if f.shape != (len(x),):
            raise ValueError(f"objective: returned shape {f.shape} for a population of "
                             f"{len(x)}, expected ({len(x)},)")
        bad = ~np.isfinite(f)
        if bad.any():
            raise FloatingPointError(f"objective: non-finite value at {int(bad.sum())} of "
                                     f"{len(x)} points, first x = {x[np.argmax(bad)].tolist()}")
        out["F"] = f[:, None]


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


def minimise(objective: Callable[[np.ndarray], np.ndarray], lower, upper, *, pop_size: int,
             n_gen: int, seed: int, sbx_eta: float = 15.0, pm_eta: float = 20.0,
             progress: Callable[[int, float], None] | None = None) -> GAResult:
    """Minimise ``objective(X) -> f`` (``X`` of shape ``(pop, n_var)``) over the box
    ``[lower, upper]`` with pymoo's real-coded GA (tournament selection, SBX crossover,
    polynomial mutation, fitness survival) for exactly ``n_gen`` generations.

    Deterministic for a given ``seed``.  ``progress(generation, best_f)`` is called per generation.
    Bad arguments (non-finite or empty box, ``lower >= upper``, non-integer sizes) raise
    ``ValueError`` naming them; a non-finite objective value raises ``FloatingPointError``.
    """
    lower = finite_array("lower", lower, shape=(None,))
    upper = finite_array("upper", upper, shape=lower.shape)
    if lower.size == 0 or np.any(lower >= upper):
        raise ValueError(f"lower = {lower.tolist()}, upper = {upper.tolist()}: need "
                         "lower < upper in every variable")
    pop_size, n_gen = integer("pop_size", pop_size, 2), integer("n_gen", n_gen, 1)
    seed = integer("seed", seed, 0)
    for name, eta in (("sbx_eta", sbx_eta), ("pm_eta", pm_eta)):
        if not (np.isfinite(eta) and eta > 0):
            raise ValueError(f"{name} = {eta!r}: must be a finite number > 0")
    algorithm = GA(pop_size=pop_size, crossover=SBX(eta=sbx_eta), mutation=PM(eta=pm_eta),
                   eliminate_duplicates=True)
    history = _History(progress)
    result = pymoo_minimize(_Batch(objective, lower, upper), algorithm, ("n_gen", n_gen),
                            seed=seed, callback=history, verbose=False)
    best_f, mean_f, n_eval, best_x = zip(*history.rows)
    return GAResult(x=np.asarray(result.X, dtype=float), f=float(result.F[0]),
                    history={"best_f": np.array(best_f), "mean_f": np.array(mean_f),
                             "n_eval": np.array(n_eval), "best_x": np.array(best_x)})
