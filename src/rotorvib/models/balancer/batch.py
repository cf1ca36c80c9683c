"""Many balancer runs in parallel (numba ``prange``), with either integrator."""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from rotorvib.models.balancer.analysers import N_METRICS
from rotorvib.models.balancer.dop853 import DOP853, integrate_dop853
from rotorvib.models.balancer.engine import integrate


@njit(cache=True, parallel=True, error_model="numpy")
def integrate_batch(form, params, y0s, t_end, rtol, atol, sample_dt, r_threshold,
                    f_threshold, max_steps, stops, order, method, A, B, C, E3, E5, D):
    """Run the engine's ``integrate`` (``method`` DOPRI5) or ``integrate_dop853`` (DOP853,
    tableau ``A`` .. ``D``) for every row of ``params``/``y0s`` in parallel (``prange`` over the shuffled
    ``order``, since run lengths vary a lot), each with its row of ``stops`` (:mod:`settling`);
    return the metrics, one row per run."""
    n_runs = params.shape[0]
    result = np.empty((n_runs, N_METRICS))
    for q in prange(n_runs):
        i = order[q]
        empty = np.empty((0, y0s.shape[1]))
        if method == DOP853:
            result[i, :] = integrate_dop853(form, params[i], y0s[i], 0.0, t_end, rtol, atol,
                                            sample_dt, r_threshold, f_threshold, max_steps,
                                            empty, stops[i], A, B, C, E3, E5, D)
        else:
            result[i, :] = integrate(form, params[i], y0s[i], 0.0, t_end, rtol, atol,
                                     sample_dt, r_threshold, f_threshold, max_steps, empty,
                                     stops[i])
    return result
