"""The rotor's passage through its critical speed during a run-up, in closed form: the peak
whirl radius, its time and the bearing force there, with the balls held at their initial
angles.

Near the time ``t_c`` at which the disk's angular rate ``Phi'`` equals the rotor's natural
frequency ``w = sqrt(k / M_t)`` (``M_t = M + n m``: the balls move with the disk), the
complex whirl ``z = x + i y`` obeys::

    M_t z'' + c z' + k z = U (Phi'^2 - i Phi'') e^{i Phi},   U = M eps + m R sum_j e^{i phi_j},

the balls frozen at their angles ``phi_j`` in the disk's frame (they move on the balls' slow
time scale; the passage is short).  With ``z = A e^{i Phi}``, ``A`` slowly varying, the sweep
taken as linear through the crossing (``Phi' = w + a s``, ``s = t - t_c``, ``a = Phi''(t_c)``)
and ``Phi'' A`` and ``Phi''`` against ``Phi'^2`` dropped::

    A' = -i eps_u (w + a s) / 2 - (zeta_t w + i a s) A,
    eps_u = U / M_t,  zeta_t = c / (2 sqrt(k M_t)),

whose solution from rest is, with ``sigma = s sqrt(a)``, ``d = zeta_t w / sqrt(a)`` and
``g = sqrt(eta) = sqrt(a) / w`` (the forcing's growth through the passage)::

    |A| = eps_u w / (2 sqrt a) E(sigma, d, g),
    E = |int_{-inf}^{sigma} e^{-d (sigma - v)} (1 + g v) e^{i v^2 / 2} dv|
      = |sqrt(pi / 2) e^{i pi / 4} W(-i e^{-i pi / 4} (sigma - i d) / sqrt 2) (1 + i d g) - i g|

(``W`` the Faddeeva function; the term in ``g`` integrates ``v e^{d v + i v^2 / 2}`` by
parts).  With ``g = 0`` its greatest value over ``sigma`` is ``sqrt(pi)`` times the Cornu
spiral's greatest distance from its start, 2.934 at ``sigma = 2.157``
(``r_pk = 1.467 eps_u / sqrt(eta)``); heavily damped, the quasi-static ``1/d``
(``r_pk = eps_u / (2 zeta_t)``).  What is dropped (the sweep's curvature in the phase) is of
relative order ``sqrt(eta)``: against an integration of the same rotor the peak is low by 6 %
at ``eta = 0.08`` (paper B's run-up) and the error halves as ``eta`` falls fourfold
(tests/test_passage.py).  The rotor's initial whirl ``r0`` (eq. 36 of paper B), decayed to
the peak at ``zeta_t w``, is added in the worst phase.  At the peak ``r' = 0``, so the bearing
force ``k r + c r'`` (eq. 40) is ``k r_pk``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import wofz

from rotorvib.models.balancer.kinematics import disk_kinematics
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters

#: The sweep variable ``sigma`` over which the envelope's peak is sought: the undamped peak is
#: at 2.157 and a damped one nearer 0; grid step, then a parabola through the best three.
SIGMA_GRID = np.linspace(-6.0, 12.0, 361)


def envelope(sigma, d, g=0.0):
    """``E(sigma, d, g)`` of the module docstring (broadcast): the passage's whirl amplitude in
    units of ``eps_u w / (2 sqrt a)``."""
    d, g = np.asarray(d), np.asarray(g)
    z = np.exp(-0.25j * np.pi) * (np.asarray(sigma) - 1j * d) / np.sqrt(2.0)
    return np.abs(np.sqrt(np.pi / 2) * np.exp(0.25j * np.pi) * wofz(-1j * z) * (1 + 1j * d * g)
                  - 1j * g)


def peak_factor(d, g=0.0) -> tuple[np.ndarray, np.ndarray]:
    """The greatest ``E(sigma, d, g)`` over ``sigma`` and the ``sigma`` where it is, for each
    ``d >= 0`` and ``g >= 0`` (broadcast): the best point of :data:`SIGMA_GRID`, refined by the
    parabola through it and its neighbours."""
    d, g = np.broadcast_arrays(np.asarray(d, dtype=float), np.asarray(g, dtype=float))
    if np.any(~(d >= 0)) or np.any(~(g >= 0)):
        raise ValueError(f"the passage's damping measure d = zeta_t w / sqrt(a) and growth "
                         f"g = sqrt(a) / w must be >= 0, not d = {d}, g = {g}")
    values = envelope(SIGMA_GRID, d[..., None], g[..., None])
    i = np.clip(values.argmax(axis=-1), 1, SIGMA_GRID.size - 2)
    left, mid, right = (np.take_along_axis(values, (i + j)[..., None], -1)[..., 0]
                        for j in (-1, 0, 1))
    curvature = left - 2 * mid + right
    shift = np.where(curvature < 0, 0.5 * (left - right) / np.where(curvature < 0,
                                                                    curvature, -1.0), 0.0)
    h = SIGMA_GRID[1] - SIGMA_GRID[0]
    sigma = SIGMA_GRID[i] + shift * h
    return envelope(sigma, d, g), sigma


def disk_rate(params: np.ndarray, t: float) -> tuple[float, float]:
    """The disk's angular rate and acceleration ``(Phi', Phi'')`` at ``t`` for the engine's
    FIXED parameters ``params`` (:func:`~rotorvib.models.balancer.parameters.fixed_parameters`;
    the engine's own disk angle: ``w t`` printed, ``int w dt`` consistent)."""
    _, rate, acceleration = disk_kinematics(float(t), params)
    return float(rate), float(acceleration)


def crossing(profile: SpeedProfile, params: np.ndarray, omega: float) -> float:
    """The time at which the disk's rate (:func:`disk_rate`, ``params`` built with
    ``profile``) first reaches ``omega`` during the run-up; NaN where it never does (an
    operating speed at or below it: no passage)."""
    from scipy.optimize import brentq  # here: the jobs that read the passage's rows find none

    if profile.kind != "runup" or disk_rate(params, profile.t_ramp)[0] <= omega:
        return float("nan")
    return brentq(lambda t: disk_rate(params, t)[0] - omega, 0.0, profile.t_ramp, xtol=1e-12)


@dataclass(frozen=True)
class Passage:
    """The critical-speed passage of one run-up: the peak whirl radius (m), its time (s), the
    bearing force there (N; the radius and force are arrays for an array of ball angles), and
    the crossing's time (s) and angular acceleration (rad/s^2)."""

    radius: float
    time: float
    force: float
    crossing: float
    acceleration: float


def passage_peak(b: Balancer, profile: SpeedProfile, phi0, r0: float = 0.0) -> Passage:
    """The peak of the critical-speed passage of balancer ``b`` under ``profile``, the balls at
    the angles ``phi0`` (radians, in the disk's frame; shape ``(..., balls)``: the radius and
    force take its leading shape) and the rotor's initial whirl ``r0`` (module docstring); NaN
    throughout where the run-up never reaches the critical speed."""
    total = b.total_mass
    omega = np.sqrt(b.k / total)
    params = fixed_parameters(b, profile)
    t_c = crossing(profile, params, omega)
    if not np.isfinite(t_c):
        return Passage(*(float("nan"),) * 5)
    acceleration = disk_rate(params, t_c)[1]
    zeta_t = b.c / (2 * np.sqrt(b.k * total))
    unbalance = np.abs(b.M * b.eps
                       + b.m * b.R * np.exp(1j * np.asarray(phi0, float)).sum(axis=-1))
    peak, sigma = peak_factor(zeta_t * omega / np.sqrt(acceleration),
                              np.sqrt(acceleration) / omega)
    t_peak = float(t_c + sigma / np.sqrt(acceleration))
    radius = (unbalance / total * omega / (2 * np.sqrt(acceleration)) * float(peak)
              + r0 * np.exp(-zeta_t * omega * t_peak))
    radius = radius if np.ndim(radius) else float(radius)
    return Passage(radius, t_peak, b.k * radius, float(t_c), float(acceleration))
