"""DOP853 (Hairer, Norsett & Wanner, Solving ODEs I, II.10) for the balancer engine: 12 stages
of order 8, error estimators of orders 5 and 3, FSAL, and a dense output of order 7 from three
more stages, feeding the same in-loop analysers as the engine's DOPRI5.

Its tableau is scipy's (``scipy/integrate/_ivp/dop853_coefficients.py``), loaded only when
asked for and passed to the compiled integrator as arrays.
"""

from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path

import numpy as np
from numba import njit

from rotorvib.models.balancer.analysers import metrics_row, new_analysers
from rotorvib.models.balancer.borrowed import borrowed
from rotorvib.models.balancer.engine import (all_finite, cannot_step, copy_into, initial_step, rhs,
                                             sample_into, sampled_components, stop_status)
from rotorvib.models.balancer.layout import NON_FINITE, OK, RUNNING
from rotorvib.models.balancer.settling import CHECK_EVERY

DOPRI5, DOP853 = 0, 1
METHODS = {"dopri5": DOPRI5, "dop853": DOP853}
_N853, _N853_DENSE = 12, 16


@lru_cache(maxsize=1)
def tableau() -> tuple:
    """``(A, B, C, E3, E5, D)`` of DOP853 as contiguous float arrays (DOPRI5's coefficients are
    compiled in), from scipy's file of them run on its own: importing it by name would first
    run ``scipy.integrate``'s ``__init__`` (every solver, quadrature rule and boundary-value
    method, about a third of a CPU-second of each job that runs the engine)."""
    scipy = Path(importlib.util.find_spec("scipy").origin).parent
    spec = importlib.util.spec_from_file_location(
        "rotorvib_dop853_coefficients", scipy / "integrate/_ivp/dop853_coefficients.py")
    c = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(c)
    return tuple(np.ascontiguousarray(x, dtype=float) for x in (c.A, c.B, c.C, c.E3, c.E5, c.D))


# The sums over the tableau are written out over its non-zero coefficients, term by term in
# the order of the full sums, so that they equal them to the bit (tested): the compiled step
# then holds no zero terms and no inner loops over the coefficients, at 0.86x the time of loops
# over all of them (skipping the zeros by loop bounds read at run time was slower than those
# loops), for about 5 s more compilation.


@njit(cache=True, error_model="numpy")
def _weighted(w, K, j):
    """``sum_q w[q] K[q, j]`` for a weight row of DOP853 (``B``, ``E3``, ``E5``): columns 0
    and 5-11 are its non-zero ones."""
    return (w[0] * K[0, j] + w[5] * K[5, j] + w[6] * K[6, j] + w[7] * K[7, j] + w[8] * K[8, j] +
            w[9] * K[9, j] + w[10] * K[10, j] + w[11] * K[11, j])


@njit(cache=True, error_model="numpy")
def _dense_weighted(d, K, j):
    """``sum_q d[q] K[q, j]`` for a row of DOP853's dense-output matrix ``D``: the columns of
    :func:`_weighted` and the dense stages 12-15."""
    return (_weighted(d, K, j) + d[12] * K[12, j] + d[13] * K[13, j] + d[14] * K[14, j] +
            d[15] * K[15, j])


@njit(cache=True, error_model="numpy", inline="always")
def _dop853_stages(form, p, t, y, h, K, A, C, first, last, ytmp):
    """Stages ``first .. last - 1`` of DOP853 into the rows of ``K`` (row 0: f(t, y)): stage
    ``s`` is ``K[s] = f(t + C[s] h, y + h sum_{q < s} A[s, q] K[q])``, for ``s`` in 1-11 (the
    step) and 13-15 (the dense output; row 12 is ``f(t + h, y_new)``, from the caller)."""
    n = y.size
    for s in range(first, last):
        if s == 1:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[1, 0] * K[0, j])
        elif s == 2:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[2, 0] * K[0, j] + A[2, 1] * K[1, j])
        elif s == 3:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[3, 0] * K[0, j] + A[3, 2] * K[2, j])
        elif s == 4:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[4, 0] * K[0, j] + A[4, 2] * K[2, j] + A[4, 3] * K[3, j])
        elif s == 5:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[5, 0] * K[0, j] + A[5, 3] * K[3, j] + A[5, 4] * K[4, j])
        elif s == 6:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[6, 0] * K[0, j] + A[6, 3] * K[3, j] + A[6, 4] * K[4, j] +
                                      A[6, 5] * K[5, j])
        elif s == 7:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[7, 0] * K[0, j] + A[7, 3] * K[3, j] + A[7, 4] * K[4, j] +
                                      A[7, 5] * K[5, j] + A[7, 6] * K[6, j])
        elif s == 8:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[8, 0] * K[0, j] + A[8, 3] * K[3, j] + A[8, 4] * K[4, j] +
                                      A[8, 5] * K[5, j] + A[8, 6] * K[6, j] + A[8, 7] * K[7, j])
        elif s == 9:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[9, 0] * K[0, j] + A[9, 3] * K[3, j] + A[9, 4] * K[4, j] +
                                      A[9, 5] * K[5, j] + A[9, 6] * K[6, j] + A[9, 7] * K[7, j] +
                                      A[9, 8] * K[8, j])
        elif s == 10:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[10, 0] * K[0, j] + A[10, 3] * K[3, j] +
                                      A[10, 4] * K[4, j] + A[10, 5] * K[5, j] +
                                      A[10, 6] * K[6, j] + A[10, 7] * K[7, j] +
                                      A[10, 8] * K[8, j] + A[10, 9] * K[9, j])
        elif s == 11:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[11, 0] * K[0, j] + A[11, 3] * K[3, j] +
                                      A[11, 4] * K[4, j] + A[11, 5] * K[5, j] +
                                      A[11, 6] * K[6, j] + A[11, 7] * K[7, j] +
                                      A[11, 8] * K[8, j] + A[11, 9] * K[9, j] +
                                      A[11, 10] * K[10, j])
        elif s == 13:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[13, 0] * K[0, j] + A[13, 6] * K[6, j] +
                                      A[13, 7] * K[7, j] + A[13, 8] * K[8, j] +
                                      A[13, 9] * K[9, j] + A[13, 10] * K[10, j] +
                                      A[13, 11] * K[11, j] + A[13, 12] * K[12, j])
        elif s == 14:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[14, 0] * K[0, j] + A[14, 5] * K[5, j] +
                                      A[14, 6] * K[6, j] + A[14, 7] * K[7, j] +
                                      A[14, 10] * K[10, j] + A[14, 11] * K[11, j] +
                                      A[14, 12] * K[12, j] + A[14, 13] * K[13, j])
        elif s == 15:
            for j in range(n):
                ytmp[j] = y[j] + h * (A[15, 0] * K[0, j] + A[15, 5] * K[5, j] +
                                      A[15, 6] * K[6, j] + A[15, 7] * K[7, j] +
                                      A[15, 8] * K[8, j] + A[15, 12] * K[12, j] +
                                      A[15, 13] * K[13, j] + A[15, 14] * K[14, j])
        rhs(form, t + C[s] * h, ytmp, p, K[s])


@njit(cache=True, error_model="numpy")
def _dop853_error(K, y, ynew, h, rtol, atol, E3, E5):
    """Hairer's error norm of DOP853: the order-5 estimate damped by the order-3 one."""
    ny = y.size
    e5 = 0.0
    e3 = 0.0
    for j in range(ny):
        scale = atol + rtol * max(abs(y[j]), abs(ynew[j]))
        e5 += (_weighted(E5, K, j) / scale) ** 2
        e3 += (_weighted(E3, K, j) / scale) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / np.sqrt((e5 + 0.01 * e3) * ny)


@njit(cache=True, error_model="numpy", inline="always")
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
            F[3 + r, j] = h * _dense_weighted(D[r], K, j)


@njit(cache=True, error_model="numpy", inline="always")
def _dop853_eval(theta, y, F, out, comps):
    """DOP853's dense output at ``t + theta h``, components ``comps``: ``y + theta (F0 + theta'
    (F1 + theta (F2 + theta' (F3 + theta (F4 + theta' (F5 + theta F6))))))``, ``theta' =
    1 - theta``."""
    t1 = 1.0 - theta
    for j in comps:
        out[j] = y[j] + theta * (F[0, j] + t1 * (F[1, j] + theta * (F[2, j] + t1 * (
            F[3, j] + theta * (F[4, j] + t1 * (F[5, j] + theta * F[6, j]))))))


@njit(cache=True, nogil=True, error_model="numpy")
def integrate_dop853(form, p, y0, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                     max_steps, out, stop, A, B, C, E3, E5, D):
    """The engine's ``integrate`` with DOP853 (tableau from :func:`tableau`): the same
    samples, analysers, metrics and statuses; step control as in Hairer's code (safety 0.9,
    factors 0.2 to 10, no growth right after a rejection) and the same early stops."""
    ny = y0.size
    return _integrate_dop853(form, p, t0, t_end, rtol, atol, sample_dt, r_threshold,
                             f_threshold, max_steps, out, stop, A, B, C, E3, E5, D, y0.copy(),
                             np.empty((_N853_DENSE, ny)), np.empty((7, ny)),
                             np.empty((3, ny)), sampled_components(ny, out), new_analysers())


@njit(cache=True, nogil=True, error_model="numpy")
def _integrate_dop853(form, p, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                      max_steps, out, stop, A, B, C, E3, E5, D, y, K, F, work, comps, acc):
    """:func:`integrate_dop853` from the state ``y`` (overwritten) with the stages ``K``, the
    dense-output rows ``F`` and the rows of ``work`` as its vectors, on borrowed views of its
    arrays (:mod:`borrowed`)."""
    p, out, stop, A, B, C, E3, E5, D = (borrowed(p), borrowed(out), borrowed(stop), borrowed(A),
                                        borrowed(B), borrowed(C), borrowed(E3), borrowed(E5),
                                        borrowed(D))
    y, K, F, work, comps, acc = (borrowed(y), borrowed(K), borrowed(F), borrowed(work),
                                 borrowed(comps), borrowed(acc))
    ny = y.size
    ytmp, ynew, ys = work[0], work[1], work[2]
    rhs(form, t0, y, p, K[0])
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
            ynew[j] = y[j] + h * _weighted(B, K, j)
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
        copy_into(y, ynew)
        copy_into(K[0], K[_N853])
        factor = 10.0 if e == 0.0 else min(10.0, 0.9 * e ** -0.125)
        h *= min(1.0, factor) if rejected else factor
        rejected = False
        if j_sample >= j_check:
            j_check = j_sample + stop[CHECK_EVERY]
            ending = stop_status(stop, p, acc, t, y, r_threshold, f_threshold)
            if ending != RUNNING:
                status = ending
                break
    return metrics_row(acc, status, steps, t, r_threshold)
