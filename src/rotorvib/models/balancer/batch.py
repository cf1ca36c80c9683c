"""Many balancer runs in parallel (numba ``prange``): one compiled batch per integrator, so
that a batch compiles only the integrator it runs (each takes about ten seconds to compile)."""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from rotorvib.models.balancer.analysers import N_METRICS
from rotorvib.models.balancer.dop853 import integrate_dop853
from rotorvib.models.balancer.engine import integrate


@njit(cache=True, parallel=True, error_model="numpy")
def batch_dopri5(form, params, y0s, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                 max_steps, stops, order):
    """The engine's ``integrate`` (DOPRI5) for every row of ``params``/``y0s`` in parallel
    (``prange`` over the shuffled ``order``, since run lengths vary a lot), each with its row of
    ``stops`` (:mod:`settling`); the metrics, one row per run."""
    result = np.empty((params.shape[0], N_METRICS))
    for q in prange(params.shape[0]):
        i = order[q]
        result[i, :] = integrate(form, params[i], y0s[i], 0.0, t_end, rtol, atol, sample_dt,
                                 r_threshold, f_threshold, max_steps,
                                 np.empty((0, y0s.shape[1])), stops[i])
    return result


@njit(cache=True, parallel=True, error_model="numpy")
def batch_dop853(form, params, y0s, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                 max_steps, stops, order, A, B, C, E3, E5, D):
    """:func:`batch_dopri5` with ``integrate_dop853`` (tableau ``A`` .. ``D``)."""
    result = np.empty((params.shape[0], N_METRICS))
    for q in prange(params.shape[0]):
        i = order[q]
        result[i, :] = integrate_dop853(form, params[i], y0s[i], 0.0, t_end, rtol, atol,
                                        sample_dt, r_threshold, f_threshold, max_steps,
                                        np.empty((0, y0s.shape[1])), stops[i],
                                        A, B, C, E3, E5, D)
    return result
