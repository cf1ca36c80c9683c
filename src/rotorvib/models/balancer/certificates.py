"""Stop certificates of balancer runs (:mod:`settling`): the modes of the linearised rest point
of each run's machine at its operating speed -- its balanced state, or beyond the existence
bound (34) its residual whirl (:func:`residual_whirl`).

The linearisation ``J`` is taken from the compiled rotating-frame right-hand side itself
(``engine.rhs_rotating``, paper A's dimensionless form) by fourth-order central differences at
the rest point, e.g. the balanced state ``[0, 0, a*, -a*, 0, 0, 0, 0]``: ``J e_j = (-f(+2h) +
8 f(+h) - 8 f(-h) + f(-2h)) / (12 h)`` with ``h = 1e-3``, truncation ``O(h^4)``, about 1e-12 --
far below the growth rate (``StopRule.neutral``) that tells a neutral mode.  The tests compare
it with the symbolic linearisation of :mod:`stability`; this module avoids sympy so that a batch
job does not load it.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorvib.models.balancer.criteria import StopRule
from rotorvib.models.balancer.engine import copy_into, rhs_rotating
from rotorvib.models.balancer.layout import CONSTANT
from rotorvib.models.balancer.parameters import (SpeedProfile, rotating_parameter_rows,
                                                 total_mass_groups)
from rotorvib.models.balancer.settling import (
    A1, A2, BALANCE_BOUND, BALL_MOMENT, CHECK_EVERY, ENABLED, FORCE_FACTOR, GAIN_IM, GAIN_RE,
    MARGIN, QUASI_STATIC, RADIUS, SIZE, STIFFNESS, T_FROM, UNBALANCE, VINV_IM, VINV_RE, W_N,
    WEIGHT_F, WEIGHT_R, WEIGHT_V)

STEP = 1e-3


@njit(cache=True, error_model="numpy")
def linearisation(p_rot, y0):
    """``J`` of the rotating form (parameters ``p_rot``, layout ``layout.P_ROT``, two balls) at
    the state ``y0``, by the differences of the module docstring."""
    J = np.zeros((8, 8))
    y = np.empty(8)
    f = np.empty(8)
    for j in range(8):
        for step, weight in ((2.0, -1.0), (1.0, 8.0), (-1.0, -8.0), (-2.0, 1.0)):
            copy_into(y, y0)
            y[j] += step * STEP
            rhs_rotating(0.0, y, p_rot, f)
            for i in range(8):
                J[i, j] += weight * f[i] / (12.0 * STEP)
    return J


@njit(cache=True, error_model="numpy")
def _jacobians(groups, states):
    out = np.empty((groups.shape[0], 8, 8))
    for i in range(groups.shape[0]):
        J = linearisation(groups[i], states[i])
        for row in range(8):
            copy_into(out[i, row], J[row])
    return out


def residual_whirl(mu, rho, zeta, W, n=2) -> np.ndarray:
    """The rest point of the rotating form where a residual unbalance whirls the centre beyond
    the existence bound (``n rho < 1``), one state row per entry of paper A's groups ``mu, rho,
    zeta`` and the constant speed ``W`` (broadcast together; ``n`` balls, state rows of two).
    At rest the rotor equations give the whirl ``w = u + i v = g (1/rho + n e^{i a})``, ``g =
    mu W^2 / (1 - W^2 + 2 i zeta W)``, for all balls at ``a``, and a ball rests where the whirl
    pulls it along the race no more, ``Im(w e^{-i a}) = 0``: ``sin(a - arg g) = n rho
    sin(arg g)``.  Of its two roots this is ``a = arg g + arcsin(n rho sin(arg g))``, the balls
    on the side the centre whirls to, where the field pushes them outwards (opposite the
    unbalance above the critical speed, beside it below); at the other root they would sit on
    the inner side, a rest point no ball returns to."""
    mu, rho, zeta, W = np.broadcast_arrays(*(np.asarray(v, float).ravel() for v in
                                             (mu, rho, zeta, W)))
    g = mu * W**2 / (1 - W**2 + 2j * zeta * W)
    a = np.angle(g) + np.arcsin(n * rho * np.sin(np.angle(g)))
    w = g * (1 / rho + n * np.exp(1j * a))
    return np.column_stack([w.real, w.imag, a, a, np.zeros((len(a), 4))])


def certificates(params: np.ndarray, rule: StopRule, sample_dt: float) -> np.ndarray:
    """One certificate row per row of ``params`` (the engine's ``P_FIXED`` layout): the rest
    point and the modal matrices and weights of :mod:`settling`'s bounds, or a row with
    ``ENABLED = 0``.  Where the balls can balance the disk the rest point is the balanced state;
    beyond the existence bound it is the residual whirl (:func:`residual_whirl`), with the
    quasi-static whirl of :mod:`settling` taken out."""
    params = np.atleast_2d(np.asarray(params, dtype=float))
    unique, inverse = np.unique(params, axis=0, return_inverse=True)
    M, m, R, eps, k, c, _, n, omega, t_ramp, profile, _ = unique.T
    mt = M + n * m
    wn = np.sqrt(k / mt)
    W = omega / wn
    two = (n == 2) & (eps > 0)
    ok = two & (2 * m * R >= M * eps)
    rows = np.zeros((len(unique), SIZE))
    i = np.flatnonzero(ok)
    if i.size:
        alpha = np.arccos(-M[i] * eps[i] / (2 * m[i] * R[i]))
        rest = np.zeros((i.size, 8))
        rest[:, 2], rest[:, 3] = alpha, -alpha
        rows[i] = _rest_rows(unique[i], _rotating_rows(unique[i], W[i]), W[i], rest, rule,
                             quasi_static=False)
    j = np.flatnonzero(two & ~ok)
    if j.size:
        groups = _rotating_rows(unique[j], W[j])
        rest = residual_whirl(*groups[:, :3].T, W[j])
        rows[j] = _rest_rows(unique[j], groups, W[j], rest, rule, quasi_static=True)
    rows[:, T_FROM] = np.where(profile == CONSTANT, 0.0, t_ramp)   # constant speed from there
    rows[:, W_N] = wn
    gain = omega**2 / (k - mt * omega**2 + 1j * c * omega)
    rows[:, GAIN_RE], rows[:, GAIN_IM], rows[:, FORCE_FACTOR] = gain.real, gain.imag, k + c * omega
    rows[:, UNBALANCE], rows[:, BALL_MOMENT] = M * eps, m * R
    rows[:, MARGIN], rows[:, RADIUS], rows[:, STIFFNESS] = rule.margin, R, k
    rows[:, CHECK_EVERY] = np.where(rows[:, ENABLED] > 0, rule.check_every(sample_dt), np.inf)
    rows[:, BALANCE_BOUND] = np.inf
    return rows[inverse.ravel()]


def _rest_rows(fixed, groups, W, rest, rule: StopRule, *, quasi_static: bool) -> np.ndarray:
    """The certificate rows of the machines ``fixed`` (``P_FIXED`` rows; ``groups``, their
    rotating-form rows at the constant dimensionless speeds ``W``) about the rest points
    ``rest`` (rotating-form states): their ball angles and modal part (:func:`_modal_rows`)."""
    M, m, R, eps, k, c, _, n = fixed[:, :8].T
    rows = _modal_rows(_jacobians(groups, rest), R, k, c, np.sqrt(k / (M + n * m)), W, rule,
                       quasi_static=quasi_static)
    rows[:, A1], rows[:, A2] = rest[:, 2], rest[:, 3]
    return rows


def _rotating_rows(fixed: np.ndarray, W: np.ndarray) -> np.ndarray:
    """The rotating form's parameter rows (``layout.P_ROT``) of the machines of ``fixed``
    (``layout.P_FIXED`` rows) at the constant dimensionless speeds ``W``: paper A's groups
    (:func:`~rotorvib.models.balancer.parameters.total_mass_groups`), as
    :func:`~rotorvib.models.balancer.parameters.rotating_parameters` lays them out for
    ``SpeedProfile(W)``."""
    M, m, R, eps, k, c, D, n = fixed[:, :8].T
    mu, rho, zeta, beta = total_mass_groups(M, m, R, eps, k, c, D, n)
    constant = SpeedProfile(1.0)
    return rotating_parameter_rows(mu=mu, rho=rho, zeta=zeta, beta=beta, n=n, omega=W,
                                   t_ramp=constant.t_ramp, profile_code=constant.profile_code)


def _modal_rows(J, R, k, c, wn, W, rule: StopRule, *, quasi_static: bool) -> np.ndarray:
    """The modal part of the certificate rows of the stacked linearisations ``J``, enabled where
    :mod:`settling`'s bounds apply: no growing mode, eigenvectors well conditioned, and no
    neutral mode that moves ``r`` at first order; the quasi-static whirl of :mod:`settling` taken
    out where a mode is neutral, or everywhere with ``quasi_static``."""
    lam, V = np.linalg.eig(J)                       # V[:, :, k]: mode k
    whirl = V[:, 0] + 1j * V[:, 1]
    rate = V[:, 4] + 1j * V[:, 5] + 1j * W[:, None] * whirl
    neutral = np.abs(lam.real) <= rule.neutral
    usable = ((lam.real.max(axis=1) <= rule.neutral) & (np.linalg.cond(V) <= 1e8)
              & ~np.any(neutral & (np.abs(whirl) > 1e-9 * np.linalg.norm(V, axis=1)), axis=1))
    rows = np.zeros((len(J), SIZE))
    u = np.flatnonzero(usable)
    Vinv = np.linalg.inv(V[u])
    rows[u, WEIGHT_R:WEIGHT_R + 8] = np.where(neutral[u], 0.0, R[u, None] * np.abs(whirl[u]))
    rows[u, WEIGHT_F:WEIGHT_F + 8] = np.where(
        neutral[u], 0.0, R[u, None] * (k[u, None] * np.abs(whirl[u])
                                       + c[u, None] * wn[u, None] * np.abs(rate[u])))
    rows[u, WEIGHT_V:WEIGHT_V + 8] = np.where(
        neutral[u], 0.0, R[u, None] * c[u, None] * wn[u, None] * np.abs(V[u, 4] + 1j * V[u, 5]))
    rows[u, VINV_RE:VINV_RE + 64] = Vinv.real.reshape(u.size, 64)
    rows[u, VINV_IM:VINV_IM + 64] = Vinv.imag.reshape(u.size, 64)
    rows[u, QUASI_STATIC] = quasi_static | neutral[u].any(axis=1)
    rows[u, ENABLED] = 1.0
    return rows
