"""How a balancer run ends: balanced, locked in a non-synchronous whirl, or not (yet) balanced.

A run whose balls settle anywhere in the disk's frame whirls synchronously: the disk's centre
turns with the disk at the steady radius of the unbalance ``U = M eps + m R sum_j e^{i phi_j}``::

    r_sync = |U| Omega^2 / |k - M_t Omega^2 + i c Omega|,   M_t = M + n m,

which is at most ``r_max = (M eps + n m R) Omega^2 / |k - M_t Omega^2 + i c Omega|``, the balls
all on the unbalance's side.  A whirl larger than that at the run's end is no synchronous state:
the balls lag the disk and the rotor whirls near its critical speed (a non-synchronous lock,
which a linearly stable balanced state does not rule out) -- unless it is what is left of the
passage: a free whirl from the peak ``F_max / k`` decays at ``c / (2 M_t)``, so a run whose
passage could still leave more than ``r_max`` at its end is not called locked (it is not
balanced, no more).  Numba-free, like :mod:`layout`.
"""

from __future__ import annotations

import numpy as np

from rotorvib.models.balancer.layout import ABOVE_BOUND, OK, P_FIXED, metric

BALANCED, NON_SYNCHRONOUS, NOT_BALANCED, FAILED = 0, 1, 2, 3
#: The outcomes by code, as the datasets' flag meanings name them.
OUTCOMES = ("balanced", "non_synchronous_whirl", "not_balanced_by_t_end", "failed")
OUTCOME_TEXT = {BALANCED: "balanced", NON_SYNCHRONOUS: "locked in a non-synchronous whirl",
                NOT_BALANCED: "not balanced by t_end", FAILED: "failed (no metrics)"}


def synchronous_bound(params) -> np.ndarray:
    """``r_max`` of the module docstring for each row of FIXED parameters ``params`` (m): the
    largest whirl radius a synchronous state can have at the operating speed."""
    p = {name: np.asarray(params, float)[..., i] for i, name in enumerate(P_FIXED)}
    total = p["M"] + p["n"] * p["m"]
    omega = p["Omega"]
    return ((p["M"] * p["eps"] + p["n"] * p["m"] * p["R"]) * omega**2
            / np.abs(p["k"] - total * omega**2 + 1j * p["c"] * omega))


def passage_remnant(metrics, params) -> np.ndarray:
    """The most of the passage's whirl that can be left at a run's end (m): its peak
    ``F_max / k`` decayed at ``c / (2 M_t)`` from the peak's time to the end."""
    p = {name: np.asarray(params, float)[..., i] for i, name in enumerate(P_FIXED)}
    rate = p["c"] / (2 * (p["M"] + p["n"] * p["m"]))
    elapsed = metric(metrics, "t_stop") - metric(metrics, "force_max_time")
    return metric(metrics, "force_max") / p["k"] * np.exp(-rate * elapsed)


def outcome(metrics, params) -> np.ndarray:
    """The outcome code (:data:`OUTCOMES`) of each run from its metrics row and its FIXED
    parameters, as floats: balanced; a whirl above :func:`synchronous_bound` at the end that
    the passage cannot have left (:func:`passage_remnant`): a non-synchronous lock; else not
    balanced by ``t_end``; failed (a status that is neither OK nor ABOVE_BOUND, or no end
    radius); NaN (unknown) for a run stopped above its batch's balance-time bound, whose
    metrics are all unknown."""
    status, r_end = metric(metrics, "status"), metric(metrics, "r_end")
    ended = (status == OK) & np.isfinite(r_end)
    bound = synchronous_bound(params)
    return np.select([status == ABOVE_BOUND, ~ended, metric(metrics, "balanced") == 1,
                      (r_end > bound) & (passage_remnant(metrics, params) < bound)],
                     [np.nan, FAILED, BALANCED, NON_SYNCHRONOUS], NOT_BALANCED)
