"""Compiled core of the automatic ball balancer: its right-hand sides and an adaptive
Dormand-Prince 5(4) integrator (DOPRI5) that feeds samples to the in-loop analysers
(``analysers``) and stops when ``settling`` says the answer is known; ``dop853`` holds the
8th-order integrator; ``simulate`` runs either, one run or a batch on threads.

Everything here is numba-compiled with ``cache=True``; model parameters travel as arrays (never as
globals, which a cache would freeze), and the integrators' step loops work on borrowed views of
them (``borrowed``), which numba keeps no reference count of.  All compiled code of the package uses numba's
``error_model="numpy"``: a division by zero gives an infinity or NaN (which the integrators report
as a non-finite state, never as a number) instead of a check and a Python exception at every
division, which made the integrators about 10 % slower.  Two forms of the same physics:

``FIXED`` (paper B, dimensional)
    state ``[x, y, phi_1..phi_n, x', y', phi_1'..phi_n']``: the geometric centre C in the fixed
    frame (regular at r = 0, unlike the polar ``r, theta`` of eqs 7-9) and the ball angles on the
    disk measured from the line C->G.  The disk angle ``Phi(t)`` follows either paper B's printed
    kinematics (``Phi = w t``, ``Phi' = w + w' t``, ``Phi'' = 2 w'`` as in eqs 7-9) or the
    consistent kinematics (``Phi = int w dt``, ``Phi' = w``, ``Phi'' = w'``).
    Parameters ``P_FIXED``: M (disk mass), m (ball mass), R, eps, k, c, D, n, Omega, T_ramp,
    profile, kinematics.

``ROTATING`` (paper A, dimensionless, frame turning with the disk)
    state ``[u, v, a_1..a_n, u', v', a_1'..a_n']`` with ``u + i v = (x + i y) e^{-i Phi} / R``,
    time ``tau = w_n t``, ``w_n = sqrt(k / M_t)``, ``M_t = M + n m``; digest A's equations
    divided by ``M_t R w_n^2`` and ``m R^2 w_n^2``.  Parameters ``P_ROT``: mu, rho, zeta, beta, n,
    Omega, T_ramp (in tau), profile.  Consistent kinematics only.

Speed profiles and disk kinematics: ``kinematics``; the forms' codes, the parameter layouts and
the status codes: ``layout`` (without numba).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorvib.models.balancer.analysers import (balance_time_above, forget, metrics_row,
                                                new_analysers, observe)
from rotorvib.models.balancer.borrowed import borrowed
from rotorvib.models.balancer.kinematics import disk_kinematics, speed
from rotorvib.models.balancer.layout import (ABOVE_BOUND, FIXED, MAX_STEPS, NON_FINITE, OK,
                                             RUNNING, STEP_UNDERFLOW)
from rotorvib.models.balancer.settling import BALANCE_BOUND, CHECK_EVERY, settled


@njit(cache=True, error_model="numpy")
def _solve_rotor(a11, a12, a22, b1, b2):
    """The symmetric positive-definite 2x2 system left after eliminating the ball accelerations."""
    det = a11 * a22 - a12 * a12
    return (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det


@njit(cache=True, error_model="numpy")
def rhs_fixed(t, y, p, dy):
    """Paper B's balancer in fixed-frame Cartesian coordinates (see module docstring).

    The ball equations ``m R^2 (phi_i'' + Phi'') + D phi_i' = m R (x'' sin a_i - y'' cos a_i)``,
    ``a_i = Phi + phi_i``, are used to eliminate ``phi_i''`` from the two rotor equations, which
    leaves a 2x2 positive-definite system for ``x'', y''``.
    """
    M, m, R, eps, k, c, D = p[0], p[1], p[2], p[3], p[4], p[5], p[6]
    n = int(p[7])
    phi, phid, phidd = disk_kinematics(t, p)
    mt = M + n * m
    ss = 0.0
    cc = 0.0
    sc = 0.0
    fx = -c * y[n + 2] - k * y[0] + M * eps * (phidd * np.sin(phi) + phid * phid * np.cos(phi))
    fy = -c * y[n + 3] - k * y[1] - M * eps * (phidd * np.cos(phi) - phid * phid * np.sin(phi))
    for i in range(n):
        a = phi + y[2 + i]
        s = np.sin(a)
        co = np.cos(a)
        dy[2 + i] = s            # sin and cos parked in dy until the accelerations are known
        dy[n + 4 + i] = co
        rate = phid + y[n + 4 + i]
        ss += s * s
        cc += co * co
        sc += s * co
        fx += m * R * rate * rate * co - D / R * s * y[n + 4 + i]
        fy += m * R * rate * rate * s + D / R * co * y[n + 4 + i]
    xdd, ydd = _solve_rotor(mt - m * ss, m * sc, mt - m * cc, fx, fy)
    for i in range(n):
        s, co = dy[2 + i], dy[n + 4 + i]
        dy[n + 4 + i] = -phidd - D / (m * R * R) * y[n + 4 + i] + (xdd * s - ydd * co) / R
        dy[2 + i] = y[n + 4 + i]
    dy[0], dy[1] = y[n + 2], y[n + 3]
    dy[n + 2] = xdd
    dy[n + 3] = ydd


@njit(cache=True, error_model="numpy")
def rhs_rotating(t, y, p, dy):
    """Paper A's dimensionless rotating-frame balancer (digest A, divided as in the module
    docstring): with ``a_u = u'' - 2 W v' - W^2 u - W' v`` and ``a_v = v'' + 2 W u' - W^2 v + W' u``,
    ``a_u + 2 zeta (u' - W v) + u = (mu/rho) W^2 + mu sum[(W + a_i')^2 cos a_i + (W' + a_i'') sin a_i]``,
    ``a_v + 2 zeta (v' + W u) + v = -(mu/rho) W' + mu sum[(W + a_i')^2 sin a_i - (W' + a_i'') cos a_i]``,
    ``a_i'' + W' + beta a_i' = a_u sin a_i - a_v cos a_i``.
    """
    mu, rho, zeta, beta = p[0], p[1], p[2], p[3]
    n = int(p[4])
    w, wd, wdd, integral = speed(t, p[5], p[6], int(p[7]))
    u, v, up, vp = y[0], y[1], y[n + 2], y[n + 3]
    gu = 2.0 * w * vp + w * w * u + wd * v
    gv = -2.0 * w * up + w * w * v - wd * u
    ss = 0.0
    cc = 0.0
    sc = 0.0
    bu = mu / rho * w * w - 2.0 * zeta * (up - w * v) - u
    bv = -mu / rho * wd - 2.0 * zeta * (vp + w * u) - v
    for i in range(n):
        s = np.sin(y[2 + i])
        co = np.cos(y[2 + i])
        dy[2 + i] = s            # sin and cos parked in dy until the accelerations are known
        dy[n + 4 + i] = co
        rate = w + y[n + 4 + i]
        ss += s * s
        cc += co * co
        sc += s * co
        bu += mu * (rate * rate * co - beta * y[n + 4 + i] * s)
        bv += mu * (rate * rate * s + beta * y[n + 4 + i] * co)
    au, av = _solve_rotor(1.0 - mu * ss, mu * sc, 1.0 - mu * cc, bu, bv)
    for i in range(n):
        s, co = dy[2 + i], dy[n + 4 + i]
        dy[n + 4 + i] = -wd - beta * y[n + 4 + i] + au * s - av * co
        dy[2 + i] = y[n + 4 + i]
    dy[0], dy[1] = up, vp
    dy[n + 2] = au + gu
    dy[n + 3] = av + gv


@njit(cache=True, error_model="numpy", inline="always")
def rhs(form, t, y, p, dy):
    if form == FIXED:
        rhs_fixed(t, y, p, dy)
    else:
        rhs_rotating(t, y, p, dy)


@njit(cache=True, error_model="numpy")
def radius_and_force(form, y, p):
    """Whirl radius ``r`` and bearing force ``F = k r + c r'`` (eq. 40) of a state.

    FIXED: metres and newtons.  ROTATING: ``r/R`` and ``F/(k R) = r/R + 2 zeta (r/R)'``."""
    n = int(p[7]) if form == FIXED else int(p[4])
    x, yy, xd, yd = y[0], y[1], y[n + 2], y[n + 3]
    r = np.sqrt(x * x + yy * yy)
    rdot = (x * xd + yy * yd) / r if r > 0.0 else 0.0
    if form == FIXED:
        return r, p[4] * r + p[5] * rdot
    return r, r + 2.0 * p[2] * rdot


# Dormand-Prince 5(4) tableau (Hairer, Norsett & Wanner, Solving ODEs I, table 5.2)
C2, C3, C4, C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
A21 = 1.0 / 5.0
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = (9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0,
                           -5103.0 / 18656.0)
B1, B3, B4, B5, B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                          22.0 / 525.0, -1.0 / 40.0)


@njit(cache=True, error_model="numpy")
def _norm(err, y0, y1, rtol, atol):
    total = 0.0
    for j in range(err.size):
        scale = atol + rtol * max(abs(y0[j]), abs(y1[j]))
        total += (err[j] / scale) ** 2
    return np.sqrt(total / err.size)


@njit(cache=True, error_model="numpy")
def initial_step(form, t0, y0, f0, p, rtol, atol, t_span, order=4):
    """Hairer's starting step (Solving ODEs I, II.4) for an error estimator of ``order``."""
    d0 = 0.0
    d1 = 0.0
    for j in range(y0.size):
        scale = atol + rtol * abs(y0[j])
        d0 += (y0[j] / scale) ** 2
        d1 += (f0[j] / scale) ** 2
    d0 = np.sqrt(d0 / y0.size)
    d1 = np.sqrt(d1 / y0.size)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_span)
    y1 = y0 + h0 * f0
    f1 = np.empty_like(y0)
    rhs(form, t0 + h0, y1, p, f1)
    d2 = 0.0
    for j in range(y0.size):
        scale = atol + rtol * abs(y0[j])
        d2 += ((f1[j] - f0[j]) / scale) ** 2
    d2 = np.sqrt(d2 / y0.size) / h0
    if max(d1, d2) <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100.0 * h0, h1, t_span)


@njit(cache=True, error_model="numpy")
def cannot_step(steps, max_steps, h, t):
    """Why no further step can be taken (``OK``: it can): too many steps, or a step too small
    to advance ``t`` (or NaN)."""
    if steps >= max_steps:
        return MAX_STEPS
    if not h >= 1e-14 * max(1.0, abs(t)):      # also catches a NaN step
        return STEP_UNDERFLOW if np.isfinite(h) else NON_FINITE
    return OK


@njit(cache=True, error_model="numpy")
def all_finite(x):
    """``np.all(np.isfinite(x))`` without a temporary array (once per step)."""
    for j in range(x.size):
        if not np.isfinite(x[j]):
            return False
    return True


@njit(cache=True, error_model="numpy")
def copy_into(dst, src):
    """``dst[:] = src`` for two vectors of one length, element by element: a slice assignment
    makes numba compile its shape check's error message (string formatting), seconds of a
    cold compile."""
    for j in range(dst.size):
        dst[j] = src[j]


@njit(cache=True, error_model="numpy")
def _hermite(theta, h, y0, f0, y1, f1, out, comps):
    """Cubic Hermite interpolation at ``t0 + theta h`` from values and slopes at both ends, of
    the components ``comps``."""
    h00 = (1.0 + 2.0 * theta) * (1.0 - theta) ** 2
    h10 = theta * (1.0 - theta) ** 2
    h01 = theta * theta * (3.0 - 2.0 * theta)
    h11 = theta * theta * (theta - 1.0)
    for j in comps:
        out[j] = h00 * y0[j] + h10 * h * f0[j] + h01 * y1[j] + h11 * h * f1[j]


@njit(cache=True, error_model="numpy")
def sampled_components(ny, out):
    """The state components a sample needs: all when the samples are stored in ``out``, else
    only the centre's position and velocity (for ``r`` and ``F``)."""
    if out.shape[0] > 0:
        return np.arange(ny)
    return np.array([0, 1, ny // 2, ny // 2 + 1])


@njit(cache=True, error_model="numpy", inline="always")
def sample_into(form, p, acc, out, j, t, ys, r_threshold, f_threshold):
    r, force = radius_and_force(form, ys, p)
    if j < out.shape[0]:
        copy_into(out[j], ys)
    observe(acc, t, r, force, r_threshold, f_threshold)


@njit(cache=True, error_model="numpy")
def stop_status(stop, p, acc, t, y, r_threshold, f_threshold):
    """At a check of the stop row ``stop``: ``ABOVE_BOUND`` once the balance time is known to
    exceed the row's ``BALANCE_BOUND`` (its metrics are then left unknown), ``OK`` once the
    metrics are settled (:func:`settling.settled`), else ``RUNNING``."""
    if balance_time_above(acc, stop[BALANCE_BOUND]):
        forget(acc)
        return ABOVE_BOUND
    if settled(stop, p, acc, t, y, r_threshold, f_threshold):
        return OK
    return RUNNING


@njit(cache=True, nogil=True, error_model="numpy")
def integrate(form, p, y0, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
              max_steps, out, stop):
    """Integrate from ``(t0, y0)`` to ``t_end``; return the metrics row (``METRICS``).

    The solution is sampled every ``sample_dt`` (cubic Hermite interpolation inside each step).
    On the samples: the balance time (after the last sample with ``r >= r_threshold``, the
    crossing time interpolated linearly; ``balanced = 0`` if ``r`` is above the threshold at the
    end: censored), the paper's envelope variant (crossing of the piecewise-linear envelope
    through the local maxima of ``r``), the bearing-force maximum and its decay time (same rule as
    the balance time with ``f_threshold``).  Samples are stored in ``out`` (rows) while it has
    room (pass an empty ``(0, len(y0))`` array for none).  A failed integration sets ``status``.
    Every ``stop[CHECK_EVERY]`` samples the run ends early if the certificate row ``stop``
    (:mod:`settling`) shows that no later sample can change a metric, or that the balance time
    exceeds the row's bound (:func:`stop_status`).
    """
    ny = y0.size
    return _integrate(form, p, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold,
                      max_steps, out, stop, y0.copy(), np.empty((11, ny)),
                      sampled_components(ny, out), new_analysers())


@njit(cache=True, nogil=True, error_model="numpy")
def _integrate(form, p, t0, t_end, rtol, atol, sample_dt, r_threshold, f_threshold, max_steps,
               out, stop, y, work, comps, acc):
    """:func:`integrate` from the state ``y`` (overwritten), with the rows of ``work`` as its
    vectors, on borrowed views of its arrays (:mod:`borrowed`)."""
    p, out, stop, y, work, comps, acc = (borrowed(p), borrowed(out), borrowed(stop), borrowed(y),
                                         borrowed(work), borrowed(comps), borrowed(acc))
    f0, k2, k3, k4, k5, k6, k7, ytmp, ynew, err, ys = (work[0], work[1], work[2], work[3],
                                                       work[4], work[5], work[6], work[7],
                                                       work[8], work[9], work[10])
    ny = y.size
    rhs(form, t0, y, p, f0)
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(f0))):
        return metrics_row(acc, NON_FINITE, 0, t0, r_threshold)
    sample_into(form, p, acc, out, 0, t0, y, r_threshold, f_threshold)
    j_sample = 1
    t_sample = t0 + sample_dt
    t = t0
    h = initial_step(form, t0, y, f0, p, rtol, atol, t_end - t0)
    status = OK
    steps = 0
    j_check = stop[CHECK_EVERY]
    while t < t_end:
        status = cannot_step(steps, max_steps, h, t)
        if status != OK:
            break
        h = min(h, t_end - t)
        for j in range(ny):
            ytmp[j] = y[j] + h * A21 * f0[j]
        rhs(form, t + C2 * h, ytmp, p, k2)
        for j in range(ny):
            ytmp[j] = y[j] + h * (A31 * f0[j] + A32 * k2[j])
        rhs(form, t + C3 * h, ytmp, p, k3)
        for j in range(ny):
            ytmp[j] = y[j] + h * (A41 * f0[j] + A42 * k2[j] + A43 * k3[j])
        rhs(form, t + C4 * h, ytmp, p, k4)
        for j in range(ny):
            ytmp[j] = y[j] + h * (A51 * f0[j] + A52 * k2[j] + A53 * k3[j] + A54 * k4[j])
        rhs(form, t + C5 * h, ytmp, p, k5)
        for j in range(ny):
            ytmp[j] = y[j] + h * (A61 * f0[j] + A62 * k2[j] + A63 * k3[j] + A64 * k4[j]
                                  + A65 * k5[j])
        rhs(form, t + h, ytmp, p, k6)
        for j in range(ny):
            ynew[j] = y[j] + h * (B1 * f0[j] + B3 * k3[j] + B4 * k4[j] + B5 * k5[j] + B6 * k6[j])
        rhs(form, t + h, ynew, p, k7)
        for j in range(ny):
            err[j] = h * (E1 * f0[j] + E3 * k3[j] + E4 * k4[j] + E5 * k5[j] + E6 * k6[j]
                          + E7 * k7[j])
        e = _norm(err, y, ynew, rtol, atol)
        if not np.isfinite(e) or e > 1.0:
            h *= 0.2 if not np.isfinite(e) else max(0.2, 0.9 * e ** -0.2)
            continue
        steps += 1
        if not all_finite(ynew):
            status = NON_FINITE
            break
        t_new = t + h
        while t_sample <= t_new + 1e-12 * sample_dt:
            _hermite(min((t_sample - t) / h, 1.0), h, y, f0, ynew, k7, ys, comps)
            sample_into(form, p, acc, out, j_sample, t_sample, ys, r_threshold, f_threshold)
            j_sample += 1
            t_sample = t0 + j_sample * sample_dt
        t = t_new
        copy_into(y, ynew)
        copy_into(f0, k7)
        h *= min(5.0, max(0.2, 0.9 * e ** -0.2)) if e > 0.0 else 5.0
        if j_sample >= j_check:
            j_check = j_sample + stop[CHECK_EVERY]
            ending = stop_status(stop, p, acc, t, y, r_threshold, f_threshold)
            if ending != RUNNING:
                status = ending
                break
    return metrics_row(acc, status, steps, t, r_threshold)
