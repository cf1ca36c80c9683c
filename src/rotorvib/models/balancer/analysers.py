"""In-loop analysers of a balancer run: from samples ``(t, r, F)`` of the whirl radius and the
bearing force, the balance time (threshold and envelope definitions), the force maximum and its
decay time and the whirl radius at the end, kept in one array while the integrator runs and
returned as one metrics row.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorvib.models.balancer.layout import COLUMN, METRICS, N_METRICS

# the metrics' columns (layout.METRICS) as compiled-in constants
(_M_STATUS, _M_STEPS, _M_BAL_T, _M_BAL, _M_ENV_T, _M_ENV, _M_F_MAX, _M_F_MAX_T, _M_F_T, _M_F_DONE,
 _M_T_STOP, _M_R_END, _M_OUTCOME) = (COLUMN[name] for name in METRICS)


# analyser state carried between samples (indices into one array)
(_R_PREV, _T_PREV, _R_PREV2, _F_PREV, _BAL_T, _BAL, _PEAK_T, _PEAK_R, _ENV_T, _ENV, _F_MAX,
 _F_MAX_T, _F_T, _F_DONE, _R_LAST) = range(15)


@njit(cache=True, error_model="numpy")
def new_analysers():
    acc = np.full(15, np.nan)
    acc[_R_PREV] = acc[_R_PREV2] = acc[_PEAK_R] = -1.0
    acc[_BAL] = acc[_ENV] = acc[_F_DONE] = 0.0
    acc[_F_MAX] = -np.inf
    return acc


@njit(cache=True, error_model="numpy")
def _crossing(t_a, v_a, t_b, v_b, level):
    return t_a + (v_a - level) / (v_a - v_b) * (t_b - t_a)


@njit(cache=True, error_model="numpy")
def _stays_below(acc, i_time, i_flag, first, previous, value, t, threshold):
    """Time after which ``value`` stays below ``threshold``: the crossing after the last sample
    at or above it (flag 0 while it is above)."""
    if value >= threshold:
        acc[i_flag] = 0.0
    elif first:
        acc[i_time], acc[i_flag] = t, 1.0
    elif previous >= threshold:
        acc[i_time] = _crossing(acc[_T_PREV], previous, t, value, threshold)
        acc[i_flag] = 1.0


@njit(cache=True, error_model="numpy")
def observe(acc, t, r, force, r_threshold, f_threshold):
    """Feed one sample ``(t, r, F)`` to the balance-time, envelope and force analysers."""
    first = acc[_R_PREV] < 0.0
    _stays_below(acc, _BAL_T, _BAL, first, acc[_R_PREV], r, t, r_threshold)
    # envelope: piecewise linear through the local maxima of r
    if acc[_R_PREV2] >= 0.0 and acc[_R_PREV2] < acc[_R_PREV] >= r:
        if acc[_PEAK_R] >= r_threshold > acc[_R_PREV]:
            acc[_ENV_T] = _crossing(acc[_PEAK_T], acc[_PEAK_R], acc[_T_PREV], acc[_R_PREV],
                                    r_threshold)
            acc[_ENV] = 1.0
        elif acc[_R_PREV] >= r_threshold:
            acc[_ENV] = 0.0
        acc[_PEAK_T], acc[_PEAK_R] = acc[_T_PREV], acc[_R_PREV]
    # bearing force: maximum, and decay below the force threshold for good
    if force > acc[_F_MAX]:
        acc[_F_MAX], acc[_F_MAX_T] = force, t
    _stays_below(acc, _F_T, _F_DONE, first, acc[_F_PREV], force, t, f_threshold)
    acc[_R_PREV2], acc[_R_PREV], acc[_F_PREV], acc[_T_PREV] = acc[_R_PREV], r, force, t
    acc[_R_LAST] = r


@njit(cache=True, error_model="numpy")
def answers_settled(acc):
    """Balance time, envelope time and force decay time all fixed unless a later sample rises
    above its threshold again."""
    return acc[_BAL] == 1.0 and acc[_ENV] == 1.0 and acc[_F_DONE] == 1.0


@njit(cache=True, error_model="numpy")
def answers_undefined(acc):
    """Balance time, envelope time and force decay time all undefined (NaN) unless a later
    sample falls below its threshold: the last sample is above both."""
    return acc[_BAL] == 0.0 and acc[_ENV] == 0.0 and acc[_F_DONE] == 0.0


@njit(cache=True, error_model="numpy")
def balance_time_above(acc, bound):
    """The balance time is certain to exceed ``bound``: the last sample, later than ``bound``, is
    at or above the threshold, or ``r`` crossed below it after ``bound`` (a later rise only moves
    the balance time later, and a run above the threshold at ``t_end`` has none)."""
    if acc[_BAL] == 1.0:
        return acc[_BAL_T] > bound
    return acc[_T_PREV] > bound


@njit(cache=True, error_model="numpy")
def forget(acc):
    """Leave every metric unknown (NaN): a run that stops before its metrics are known."""
    acc[_BAL] = acc[_ENV] = acc[_F_DONE] = np.nan
    acc[_F_MAX] = acc[_F_MAX_T] = acc[_R_LAST] = np.nan


@njit(cache=True, error_model="numpy")
def force_maximum(acc):
    return acc[_F_MAX]


@njit(cache=True, error_model="numpy")
def metrics_row(acc, status, steps, t_stop, r_threshold):
    """The metrics row (``METRICS``) of a run that ended at ``t_stop`` with ``status``."""
    # the envelope falls below the threshold after its last peak without a further peak
    if (acc[_ENV] == 0.0 and acc[_PEAK_R] >= r_threshold > acc[_R_LAST]
            and acc[_T_PREV] > acc[_PEAK_T]):
        acc[_ENV_T] = _crossing(acc[_PEAK_T], acc[_PEAK_R], acc[_T_PREV], acc[_R_LAST],
                                r_threshold)
        acc[_ENV] = 1.0
    m = np.full(N_METRICS, np.nan)
    m[_M_STATUS], m[_M_STEPS] = status, steps
    m[_M_BAL_T] = acc[_BAL_T] if acc[_BAL] == 1.0 else np.nan
    m[_M_BAL] = acc[_BAL]
    m[_M_ENV_T] = acc[_ENV_T] if acc[_ENV] == 1.0 else np.nan
    m[_M_ENV] = acc[_ENV]
    m[_M_F_MAX], m[_M_F_MAX_T] = acc[_F_MAX], acc[_F_MAX_T]
    m[_M_F_T] = acc[_F_T] if acc[_F_DONE] == 1.0 else np.nan
    m[_M_F_DONE] = acc[_F_DONE]
    m[_M_T_STOP] = t_stop
    m[_M_R_END] = acc[_R_LAST]       # the outcome is classified after the run (outcomes)
    return m
