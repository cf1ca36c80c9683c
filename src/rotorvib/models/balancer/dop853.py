"""DOP853 (Hairer, Norsett & Wanner, Solving ODEs I, II.10) for the balancer engine: 12 stages
of order 8, error estimators of orders 5 and 3, FSAL, and a dense output of order 7 from three
more stages, feeding the same in-loop analysers as the engine's DOPRI5.

Its tableau is scipy's (``scipy.integrate._ivp.dop853_coefficients``), loaded only when asked
for and passed to the compiled integrator as arrays.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numba import njit

from rotorvib.models.balancer.analysers import metrics_row, new_analysers
from rotorvib.models.balancer.engine import (NON_FINITE, OK, all_finite, cannot_step,
                                             initial_step, rhs, sample_into,
                                             sampled_components)
from rotorvib.models.balancer.settling import CHECK_EVERY, settled

DOPRI5, DOP853 = 0, 1
METHODS = {"dopri5": DOPRI5, "dop853": DOP853}
_N853, _N853_DENSE = 12, 16


@lru_cache(maxsize=1)
def tableau() -> tuple:
    """``(A, B, C, E3, E5, D)`` of DOP853 as contiguous float arrays (DOPRI5's coefficients are
    compiled in)."""
    from scipy.integrate._ivp import dop853_coefficients as c

    return tuple(np.ascontiguousarray(x, dtype=float) for x in (c.A, c.B, c.C, c.E3, c.E5, c.D))


@njit(cache=True, error_model="numpy")
def _dop853_stages(form, p, t, y, h, K, A, C, first, last, ytmp):
    """Stages ``first .. last - 1`` of DOP853 into the rows of ``K`` (row 0: f(t, y))."""
    ny = y.size
    for s in range(first, last):
        for j in range(ny):
            acc = 0.0
            for q in range(s):
                acc += A[s, q] * K[q, j]
            ytmp[j] = y[j] + h * acc
        rhs(form, t + C[s] * h, ytmp, p, K[s])


@njit(cache=True, error_model="numpy")
def _dop853_error(K, y, ynew, h, rtol, atol, E3, E5):
    """Hairer's error norm of DOP853: the order-5 estimate damped by the order-3 one."""
    ny = y.size
    e5 = 0.0
    e3 = 0.0
    for j in range(ny):
        scale = atol + rtol * max(abs(y[j]), abs(ynew[j]))
        a5 = 0.0
        a3 = 0.0
        for q in range(_N853 + 1):
            a5 += E5[q] * K[q, j]
            a3 += E3[q] * K[q, j]
        e5 += (a5 / scale) ** 2
        e3 += (a3 / scale) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / np.sqrt((e5 + 0.01 * e3) * ny)


@njit(cache=True, error_model="numpy")
def _dop853_dense(form, p, t, h, y, ynew, K, A, C, D, F, ytmp, comps):
    """The seven coefficient rows ``F`` of DOP853's dense output over the step (after the three
    extra stages), for the components ``comps``."""
    _dop853_stages(form, p, t, y, h, K, A, C, _N853 + 1, _N853_DENSE, ytmp)
    for j in comps:
        dy = ynew[j] - y[j]
        F[0, j] = dy
        F[1, j] = h * K[0, j] - dy
        F[2, j] = 2.0 * dy - h * (K[_N853, j] + K[0, j])
        for r in range(4):
            acc = 0.0
            for q in range(_N853_DENSE):
                acc += D[r, q] * K[q, j]
            F[3 + r, j] = h * acc


@njit(cache=True, error_model="numpy")
def _dop853_eval(theta, y, F, out, comps):
    """DOP853's dense output at ``t + theta h``, components ``comps``: ``y + theta (F0 + theta'
    (F1 + theta (F2 + theta' (F3 + theta (F4 + theta' (F5 + theta F6))))))``, ``theta' =
    1 - theta``."""
    t1 = 1.0 - theta
    for j in comps:
        out[j] = y[j] + theta * (F[0, j] + t1 * (F[1, j] + theta * (F[2, j] + t1 * (
            F[3, j] + theta * (F[4, j] + t1 * (F[5, j] + theta * F[6, j]))))))


@njit(cache=True, error_model="numpy")
def integrate_dop853(form, p, y0, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                     max_steps, out, stop, A, B, C, E3, E5, D):
    """The engine's ``integrate`` with DOP853 (tableau from :func:`tableau`): the same
    samples, analysers, metrics and statuses; step control as in Hairer's code (safety 0.9,
    factors 0.2 to 10, no growth right after a rejection) and the same early stop."""
    ny = y0.size
    y = y0.copy()
    K = np.empty((_N853_DENSE, ny))
    F = np.empty((7, ny))
    ytmp, ynew, ys = np.empty(ny), np.empty(ny), np.empty(ny)
    comps = sampled_components(ny, out)
    rhs(form, t0, y, p, K[0])
    acc = new_analysers()
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(K[0]))):
        return metrics_row(acc, NON_FINITE, 0, t0, r_threshold)
    sample_into(form, p, acc, out, 0, t0, y, r_threshold, f_threshold)
    j_sample = 1
    t_sample = t0 + sample_dt
    t = t0
    h = initial_step(form, t0, y, K[0], p, rtol, atol, t_end - t0, 7)
    status = OK
    steps = 0
    rejected = False
    j_check = stop[CHECK_EVERY]
    while t < t_end:
        status = cannot_step(steps, max_steps, h, t)
        if status != OK:
            break
        h = min(h, t_end - t)
        _dop853_stages(form, p, t, y, h, K, A, C, 1, _N853, ytmp)
        for j in range(ny):
            acc_b = 0.0
            for q in range(_N853):
                acc_b += B[q] * K[q, j]
            ynew[j] = y[j] + h * acc_b
        rhs(form, t + h, ynew, p, K[_N853])
        e = _dop853_error(K, y, ynew, h, rtol, atol, E3, E5)
        if not np.isfinite(e) or e >= 1.0:
            h *= 0.2 if not np.isfinite(e) else max(0.2, 0.9 * e ** -0.125)
            rejected = True
            continue
        steps += 1
        if not all_finite(ynew):
            status = NON_FINITE
            break
        t_new = t + h
        if t_sample <= t_new + 1e-12 * sample_dt:
            _dop853_dense(form, p, t, h, y, ynew, K, A, C, D, F, ytmp, comps)
            while t_sample <= t_new + 1e-12 * sample_dt:
                _dop853_eval(min((t_sample - t) / h, 1.0), y, F, ys, comps)
                sample_into(form, p, acc, out, j_sample, t_sample, ys, r_threshold, f_threshold)
                j_sample += 1
                t_sample = t0 + j_sample * sample_dt
        t = t_new
        y[:] = ynew
        K[0, :] = K[_N853]
        factor = 10.0 if e == 0.0 else min(10.0, 0.9 * e ** -0.125)
        h *= min(1.0, factor) if rejected else factor
        rejected = False
        if j_sample >= j_check:
            j_check = j_sample + stop[CHECK_EVERY]
            if settled(stop, p, acc, t, y, r_threshold, f_threshold):
                break
    return metrics_row(acc, status, steps, t, r_threshold)
