"""What a search finds, as plain data: a genetic algorithm's optimum with its history
(:class:`GAResult`) and an NSGA-II Pareto front (:class:`ParetoFront`).

Apart from the searches themselves (:mod:`rotorvib.methods.ga`, which imports pymoo): a job
that reads, gathers or writes results it did not search for imports this module only."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class GAResult:
    """Optimum ``x`` with objective ``f``, and per-generation ``history`` arrays:
    ``best_f``, ``mean_f`` (population), ``n_eval`` (cumulative) and ``best_x``."""

    x: np.ndarray
    f: float
    history: dict[str, np.ndarray]


@dataclass(frozen=True)
class ParetoFront:
    """Non-dominated designs ``x`` (rows) with objectives ``f`` (rows), sorted by the first
    objective, and the number of evaluations ``n_eval`` spent."""

    x: np.ndarray
    f: np.ndarray
    n_eval: int
