"""Stopping a run once its answer is known: a bound on the whirl radius and the bearing force
for the rest of a run at constant speed.

After the run-up the balancer is autonomous in the frame turning with the disk.  Near a rest
point ``q_e = (u_e, v_e, a_1e, a_2e, 0, 0, 0, 0)`` of that frame (or its mirror image, the balls
swapped) the deviation ``dq`` of the rotating-frame state ``[u, v, a1, a2, u', v', a1', a2']``
(paper A's units: lengths in ``R``, time ``tau = w_n t``) obeys ``dq' = J dq``, ``J`` the
linearisation (:mod:`certificates`).  With ``J = V diag(lambda) V^-1`` and modal amplitudes
``c = V^-1 dq(tau)``, every later state is ``dq(tau') = sum_k c_k e^{lambda_k (tau' - tau)} v_k``;
when no ``Re lambda_k`` is positive, ``|e^{lambda_k s}| <= 1`` for ``s >= 0`` and the triangle
inequality bounds, for all later times,

::

    r = R |u + i v|          <=  sum_k |c_k| R |v_k,u + i v_k,v|                     =: B_r,
    F = k r + c r' <= k r + c |z'|
                             <=  sum_k |c_k| (k R |v_k,u + i v_k,v|
                                  + c R w_n |v_k,u' + i v_k,v' + i W (v_k,u + i v_k,v)|) =: B_F,

``z = x + i y`` the centre in the fixed frame, ``W = Omega / w_n``.  The rest point is the
balanced state ``q* = (0, 0, a*, -a*, ...)`` (eq. 33) where the balls can balance the disk
(bound 34).  A run may stop once the balance time, the envelope time and the force decay time
are settled (the analysers' flags) and ``B_r <= margin r_threshold``, ``B_F <= margin
f_threshold`` and ``B_F`` is below the force maximum: no later sample could move any metric.
``margin < 1`` leaves room for the nonlinear terms the linearisation drops (second order in
``dq``).

At the existence bound (34) the balls meet at ``a* = pi`` and ``J`` has a neutral mode
(``|Re lambda| <= neutral``): the balls' symmetric separation, which moves ``r`` only at second
order (its ``u, v`` components vanish).  It is left out of the sums; instead the steady whirl of
the residual unbalance of the current ball angles, ``z_s = W_d^2 U / (k - M_t W_d^2 + i c W_d)``
with ``U = M eps + m R sum_i e^{i a_i}`` (rotating frame, ``W_d`` the disk speed), is taken out
of ``(u, v)`` before the projection and added on its own: ``r_s = |z_s|``, ``F_s = (k + c W_d)
r_s``.  This assumes the separation does not grow, which holds on the centre manifold above the
critical speed and is checked by computation (identical metrics with and without stopping: the
tests and ``python -m benchmarks.balancer --stop``).

Beyond the bound (``2 m R < M eps``) there is no balanced state: the balls gather at one angle
``a_e`` and the residual unbalance whirls the centre at ``z_s`` of that angle
(:func:`~rotorvib.models.balancer.certificates.residual_whirl`).  The rest point is then
``(z_s / R, a_e, a_e, 0, ...)``, and the bounds take the quasi-static whirl out in the same way:
the balls' separation decays slowly as ``2 m R`` nears ``M eps`` and moves ``r`` at second
order only, through ``z_s``.  The rest point itself whirls at ``r_e = |z_s(a_e)|`` (``F_e =
(k + c W_d) r_e`` in the bound's terms), which the linearisation does not approximate: the margin
leaves its room below the thresholds to the departure from the rest point only, and a run that
balances stops once ``B_r - r_e <= margin (r_threshold - r_e)`` and ``B_F - F_e <= margin
(f_threshold - F_e)`` (``r_e < r_threshold``, ``F_e < f_threshold``; at the balanced state ``r_e
= 0`` and these are the conditions above).  One whose residual whirl stays above the thresholds
never balances, and stops once that is known: the balls' unbalance
is at least ``U_min = M eps - n m R`` at any angles, so that for all later times

::

    r >= r_min - sum_k |c_k| R |v_k,u + i v_k,v|                                      =: L_r,
    F = k r + c r' >= k L_r - c R w_n sum_k |c_k| |v_k,u' + i v_k,v'|                   =: L_F,

``r_min = |z_s(U_min)|`` (``r' = R d|u + i v|/dt`` is at most the rotating-frame speed), and the
run may stop once the balance, envelope and force flags all say "not yet" (the last sample is
above both thresholds), ``margin L_r >= r_threshold``, ``margin L_F >= f_threshold`` and ``B_F``
is below the force maximum: every metric stays NaN, or at its value.

A mode that is neutral and moves ``r`` at first order, a rest point that does not decay, a
ball count other than two or a non-constant speed (the rotating-frame form, the run-up
itself): no certificate, the run goes on to ``t_end`` as before.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorvib.models.balancer.analysers import answers_settled, answers_undefined, force_maximum
from rotorvib.models.balancer.kinematics import disk_kinematics

# layout of a certificate row (one per run): scalars (A1, A2: the ball angles of the rest point),
# then the modal weights of B_r, B_F and L_F and the real and imaginary parts of V^-1 (row-major),
# then the run's balance-time bound (the engine's ABOVE_BOUND stop; infinite: none)
(ENABLED, T_FROM, W_N, A1, A2, QUASI_STATIC, GAIN_RE, GAIN_IM, FORCE_FACTOR, UNBALANCE,
 BALL_MOMENT, MARGIN, CHECK_EVERY, RADIUS, STIFFNESS) = range(15)
WEIGHT_R, WEIGHT_F, WEIGHT_V, VINV_RE, VINV_IM, BALANCE_BOUND = 15, 23, 31, 39, 103, 167
SIZE = 168

@njit(cache=True, error_model="numpy")
def _wrap(a):
    return (a + np.pi) % (2.0 * np.pi) - np.pi


@njit(cache=True, error_model="numpy")
def _quasi_static_whirl(S, a1, a2):
    """The steady whirl ``z_s = g U`` (m, rotating frame; real and imaginary parts) of the
    unbalance ``U = M eps + m R (e^{i a1} + e^{i a2})`` the balls leave at the angles ``a1, a2``,
    ``g`` the quasi-static gain of ``S``."""
    ur = S[UNBALANCE] + S[BALL_MOMENT] * (np.cos(a1) + np.cos(a2))
    ui = S[BALL_MOMENT] * (np.sin(a1) + np.sin(a2))
    return S[GAIN_RE] * ur - S[GAIN_IM] * ui, S[GAIN_RE] * ui + S[GAIN_IM] * ur


@njit(cache=True, error_model="numpy")
def _amplitudes(S, y, phi, phid):
    """The modal amplitudes ``|c_k|`` of the fixed-frame state ``y`` (two balls) at disk angle
    ``phi`` and rate ``phid``, measured from the rest point of ``S`` or its mirror image (the
    balls swapped), whichever is nearer, and the quasi-static whirl radius ``r_s`` (0 unless
    ``S`` takes it out)."""
    R, wn, a1, a2 = S[RADIUS], S[W_N], S[A1], S[A2]
    co, si = np.cos(phi), np.sin(phi)
    dq = np.empty(8)
    dq[0] = (y[0] * co + y[1] * si) / R                  # (x + i y) e^{-i Phi} / R
    dq[1] = (y[1] * co - y[0] * si) / R
    a = y[4] + phid * y[1]                               # z' - i Phi' z, turned the same way
    b = y[5] - phid * y[0]
    dq[4] = (a * co + b * si) / (R * wn)
    dq[5] = (b * co - a * si) / (R * wn)
    d1, d2 = _wrap(y[2] - a1), _wrap(y[3] - a2)
    m1, m2 = _wrap(y[3] - a1), _wrap(y[2] - a2)          # mirror image: the balls swapped
    if d1 * d1 + d2 * d2 <= m1 * m1 + m2 * m2:
        dq[2], dq[3], dq[6], dq[7] = d1, d2, y[6] / wn, y[7] / wn
    else:
        dq[2], dq[3], dq[6], dq[7] = m1, m2, y[7] / wn, y[6] / wn
    r_s = 0.0
    if S[QUASI_STATIC] > 0.0:
        # steady whirl of the residual unbalance U of the current ball angles, taken out of the
        # deviation and bounded on its own
        zr, zi = _quasi_static_whirl(S, y[2], y[3])
        zr /= R
        zi /= R
        dq[0] -= zr
        dq[1] -= zi
        r_s = R * np.sqrt(zr * zr + zi * zi)
    amplitudes = np.empty(8)
    for k in range(8):
        cr = 0.0
        ci = 0.0
        for j in range(8):
            cr += S[VINV_RE + 8 * k + j] * dq[j]
            ci += S[VINV_IM + 8 * k + j] * dq[j]
        amplitudes[k] = np.sqrt(cr * cr + ci * ci)
    return amplitudes, r_s


@njit(cache=True, error_model="numpy")
def _upper(S, amplitudes, r_s):
    """``(B_r, B_F)`` from the modal amplitudes and the quasi-static whirl radius."""
    b_r = r_s
    b_f = S[FORCE_FACTOR] * r_s
    for k in range(8):
        b_r += amplitudes[k] * S[WEIGHT_R + k]
        b_f += amplitudes[k] * S[WEIGHT_F + k]
    return b_r, b_f


@njit(cache=True, error_model="numpy")
def _lower(S, amplitudes):
    """``(L_r, L_F)`` from the modal amplitudes."""
    # r_min: the quasi-static whirl of the least unbalance the two balls can leave
    l_r = (np.sqrt(S[GAIN_RE] * S[GAIN_RE] + S[GAIN_IM] * S[GAIN_IM])
           * (S[UNBALANCE] - 2.0 * S[BALL_MOMENT]))
    rate = 0.0
    for k in range(8):
        l_r -= amplitudes[k] * S[WEIGHT_R + k]
        rate += amplitudes[k] * S[WEIGHT_V + k]
    return l_r, S[STIFFNESS] * l_r - rate


@njit(cache=True, error_model="numpy")
def rest_whirl(S):
    """The whirl radius ``r_e = |z_s|`` of the rest point of ``S`` (its ball angles
    ``a_1e, a_2e``, :func:`_quasi_static_whirl`) and its force in the bound's terms, ``F_e =
    (k + c W_d) r_e``: 0 at the balanced state, the residual whirl beyond the existence
    bound."""
    zr, zi = _quasi_static_whirl(S, S[A1], S[A2])
    r_e = np.sqrt(zr * zr + zi * zi)
    return r_e, S[FORCE_FACTOR] * r_e


@njit(cache=True, error_model="numpy")
def bounds(S, y, phi, phid):
    """``(B_r, B_F)`` of the module docstring for the fixed-frame state ``y`` (two balls) at disk
    angle ``phi`` and rate ``phid`` (:func:`_amplitudes`)."""
    amplitudes, r_s = _amplitudes(S, y, phi, phid)
    return _upper(S, amplitudes, r_s)


@njit(cache=True, error_model="numpy")
def lower_bounds(S, y, phi, phid):
    """``(L_r, L_F)`` of the module docstring for the state ``y`` (as :func:`bounds`)."""
    return _lower(S, _amplitudes(S, y, phi, phid)[0])


@njit(cache=True, error_model="numpy")
def settled(S, p, acc, t, y, r_threshold, f_threshold):
    """True when the run at ``(t, y)`` (FIXED form, parameters ``p``, analyser state ``acc``)
    may stop: its metrics are settled and the bounds of the module docstring hold, or it is
    above both thresholds and the lower bounds keep it there."""
    if S[ENABLED] == 0.0 or t < S[T_FROM]:
        return False
    balanced = answers_settled(acc)
    beyond = S[UNBALANCE] > 2.0 * S[BALL_MOMENT]          # the existence bound (34)
    if not (balanced or (beyond and answers_undefined(acc))):
        return False
    phi, phid, _ = disk_kinematics(t, p)
    amplitudes, r_s = _amplitudes(S, y, phi, phid)
    b_r, b_f = _upper(S, amplitudes, r_s)
    if b_f >= force_maximum(acc):
        return False
    if balanced:
        r_e, f_e = rest_whirl(S)
        return (r_e < r_threshold and f_e < f_threshold
                and b_r - r_e <= S[MARGIN] * (r_threshold - r_e)
                and b_f - f_e <= S[MARGIN] * (f_threshold - f_e))
    l_r, l_f = _lower(S, amplitudes)
    return S[MARGIN] * l_r >= r_threshold and S[MARGIN] * l_f >= f_threshold


def disabled() -> np.ndarray:
    """A certificate row that never lets a run stop (stored runs, the rotating form)."""
    row = np.zeros(SIZE)
    row[CHECK_EVERY] = row[BALANCE_BOUND] = np.inf
    return row
