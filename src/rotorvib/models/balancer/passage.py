"""The rotor's passage through its critical speed during a run-up with the balls held at
their initial angles: the peak whirl radius, its time and the bearing force there, without
integrating an equation of motion.

With the balls frozen at their angles ``phi_j`` in the disk's frame (they move on their own,
slow time scale; the passage is short), the complex whirl ``z = x + i y`` of the disk's centre
obeys the linear equation::

    M_t z'' + c z' + k z = U f(t),   f = (Phi'^2 - i Phi'') e^{i Phi},
    U = M eps + m R sum_j e^{i phi_j},   M_t = M + n m,

with the disk angle ``Phi`` and its derivatives as the engine has them under each kinematics
(:func:`~rotorvib.models.balancer.kinematics.disk_kinematics`: printed ``Phi = w t``,
consistent ``Phi = int w dt``).  Its solution from rest at ``z0`` is Duhamel's integral::

    z(t) = z_free(t) + U J(t),   J(t) = int_0^t h(t - tau) f(tau) dtau,
    h(s) = (e^{lam_1 s} - e^{lam_2 s}) / (M_t (lam_1 - lam_2)),   lam_1,2 = -zeta_t w +/- i w_d,

(underdamped, ``e^{-zeta_t w s} sin(w_d s) / (M_t w_d)``), ``w = sqrt(k / M_t)``,
``zeta_t = c / (2 sqrt(k M_t))``, ``w_d = w sqrt(1 - zeta_t^2)``: exact for balls that do not
move.  ``J`` does not depend on the ball angles, so one quadrature serves every set of them:
``J = (y_1 - y_2) / (M_t (lam_1 - lam_2))`` with ``y_j(t) = int_0^t e^{lam_j (t - tau)} f dtau``
by the trapezoidal rule (a recurrence, :func:`_decaying_integral`), :data:`STEPS_PER_TURN` steps
per turn of the fastest phase (``Phi' + w``; relative error about
``(2 pi / STEPS_PER_TURN)^2 / 12`` = 1e-5).  The peak is the greatest ``|z|`` in a window
around the crossing time ``t_c`` (``Phi'(t_c) = w``), of :data:`WINDOW` in units of
``1 / sqrt(a)``, ``a = d Phi' / dt`` at ``t_c`` the sweep rate of the excitation's frequency
(under the printed kinematics ``2 w' + w'' t``, not the printed ``Phi'' = 2 w'``).

Two limits check it (tests/test_passage.py): a slow, linear, undamped sweep
(``eta = a / w^2 -> 0``) peaks at ``sqrt(pi)`` times the Cornu spiral's greatest distance from
its start, ``r_pk = 1.467 eps_u / sqrt(eta)`` (``eps_u = |U| / M_t``), within ``O(sqrt eta)``;
a slow, damped one at the steady response's greatest value over speed,
``r_pk = eps_u / (2 zeta_t sqrt(1 - zeta_t^2))`` (``zeta_t < 1 / sqrt 2``).  At the peak
``r' = 0``, so the bearing force ``k r + c r'`` (eq. 40) is ``k r_pk``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from rotorvib.models.balancer.kinematics import disk_kinematics_on, speed
from rotorvib.models.balancer.layout import PRINTED
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters

#: Trapezoidal steps per turn of the quadrature's fastest phase (module docstring).
STEPS_PER_TURN = 400
#: The window in which the peak is sought, before and after the crossing, in units of
#: ``1 / sqrt(a)``: an undamped slow sweep peaks 2.16 after it, a damped one nearer it.
WINDOW = (6.0, 12.0)
#: Ball-angle sets whose whirl is evaluated at once (bounds the memory of a large batch).
CHUNK = 64


def disk_rate(params: np.ndarray, t: float) -> tuple[float, float]:
    """The excitation's frequency and its sweep rate ``(Phi', d Phi' / dt)`` at ``t`` for the
    engine's FIXED parameters ``params``
    (:func:`~rotorvib.models.balancer.parameters.fixed_parameters`): ``(w, w')`` under the
    consistent kinematics (``Phi = int w dt``), ``(w + w' t, 2 w' + w'' t)`` under the printed
    ones (``Phi = w t``).  The sweep rate is the derivative of the rate, not the printed
    ``Phi'' = 2 w'`` that paper B's equations carry
    (:func:`~rotorvib.models.balancer.kinematics.disk_kinematics`): the phase ``w t`` sweeps
    through the critical speed the faster, by ``w'' t`` (about 1.7 times ``2 w'`` at paper B's
    crossing)."""
    w, wd, wdd, _ = speed(float(t), params[8], params[9], int(params[10]))
    if int(params[11]) == PRINTED:
        return float(w + wd * t), float(2 * wd + wdd * t)
    return float(w), float(wd)


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
    bearing force there (N; the three are arrays for an array of ball angles), and the
    crossing's time (s) and the excitation's sweep rate there (rad/s^2)."""

    radius: float
    time: float
    force: float
    crossing: float
    acceleration: float


def _roots(zeta_t: float, omega: float) -> tuple[complex, complex]:
    """The rotor's characteristic roots ``-zeta_t w +/- i w_d``, ``w_d = w sqrt(1 - zeta_t^2)``
    (imaginary above critical damping); ``ValueError`` at critical damping, where they merge."""
    if abs(1 - zeta_t**2) < 1e-12:
        raise ValueError(f"the rotor's damping ratio zeta_t = {zeta_t} is critical (1): the "
                         "passage's quadrature needs distinct roots")
    damped = omega * np.sqrt(complex(1 - zeta_t**2))
    return -zeta_t * omega + 1j * damped, -zeta_t * omega - 1j * damped


def free_whirl(z0: complex, zeta_t: float, omega: float, t) -> np.ndarray:
    """The rotor's free vibration from rest at ``z0`` (eq. 36's ``r0 e^{i theta0}``):
    ``z0 (lam_2 e^{lam_1 t} - lam_1 e^{lam_2 t}) / (lam_2 - lam_1)`` with the roots
    ``lam_1,2 = -zeta_t w +/- i w_d`` (:func:`_roots`); underdamped,
    ``e^{-zeta_t w t} z0 (cos w_d t + zeta_t w / w_d sin w_d t)``."""
    one, two = _roots(zeta_t, omega)
    t = np.asarray(t, dtype=float)
    return z0 * (two * np.exp(one * t) - one * np.exp(two * t)) / (two - one)


def unit_response(b: Balancer, params: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``J(t)`` of the module docstring on the uniform grid ``t`` (from 0): the whirl of the
    frozen rotor per unit of unbalance ``U`` (m per kg m), with the impulse response
    ``h(s) = (e^{lam_1 s} - e^{lam_2 s}) / (M_t (lam_1 - lam_2))`` (:func:`_roots`)."""
    total = b.total_mass
    one, two = _roots(b.c / (2 * np.sqrt(b.k * total)), np.sqrt(b.k / total))
    phi, rate, acceleration = disk_kinematics_on(np.asarray(t, dtype=float), params)
    force = (rate**2 - 1j * acceleration) * np.exp(1j * phi)
    dt = t[1] - t[0]
    return ((_decaying_integral(np.exp(one * dt), force, dt)
             - _decaying_integral(np.exp(two * dt), force, dt)) / (total * (one - two)))


@njit(cache=True)
def _decaying_integral(decay, f, dt):
    """``y(t_n) = int_0^{t_n} e^{lam (t_n - tau)} f(tau) dtau`` on a uniform grid of step ``dt``
    (``decay = e^{lam dt}``), by the trapezoidal rule as a recurrence:
    ``y_n = decay y_{n-1} + dt (decay f_{n-1} + f_n) / 2``; no ``e^{-lam t}`` grows."""
    y = np.empty_like(f)
    y[0] = 0.0
    for n in range(1, f.size):
        y[n] = decay * y[n - 1] + 0.5 * dt * (decay * f[n - 1] + f[n])
    return y


def _refined_peak(values: np.ndarray, grid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The greatest of ``values`` along the last axis (sampled on the uniform ``grid``) and
    where it is: the best sample, refined by the parabola through it and its neighbours."""
    i = np.clip(values.argmax(axis=-1), 1, grid.size - 2)
    left, mid, right = (np.take_along_axis(values, (i + j)[..., None], -1)[..., 0]
                        for j in (-1, 0, 1))
    curvature = left - 2 * mid + right
    shift = np.where(curvature < 0, 0.5 * (left - right) / np.where(curvature < 0,
                                                                    curvature, -1.0), 0.0)
    return mid - 0.25 * (left - right) * shift, grid[i] + shift * (grid[1] - grid[0])


def passage_peak(b: Balancer, profile: SpeedProfile, phi0, z0: complex = 0.0) -> Passage:
    """The peak of the critical-speed passage of balancer ``b`` under ``profile``, the balls at
    the angles ``phi0`` (radians, in the disk's frame; shape ``(..., balls)``: the radius,
    time and force take its leading shape) and the rotor starting from rest at ``z0`` (module
    docstring); NaN throughout where the run-up never reaches the critical speed."""
    total = b.total_mass
    omega = np.sqrt(b.k / total)
    params = fixed_parameters(b, profile)
    t_c = crossing(profile, params, omega)
    if not np.isfinite(t_c):
        return Passage(*(float("nan"),) * 5)
    sweep = disk_rate(params, t_c)[1]
    fastest = 3 * profile.omega + omega            # Phi' <= 3 Omega under either kinematics
    dt = 2 * np.pi / (STEPS_PER_TURN * fastest)
    t = np.arange(0.0, t_c + WINDOW[1] / np.sqrt(sweep) + dt, dt)
    window = t >= t_c - WINDOW[0] / np.sqrt(sweep)
    response = unit_response(b, params, t)[window]
    free = free_whirl(z0, b.c / (2 * np.sqrt(b.k * total)), omega, t[window])
    unbalance = (b.M * b.eps + b.m * b.R * np.exp(1j * np.asarray(phi0, float)).sum(axis=-1))
    flat = np.atleast_1d(unbalance).ravel()
    radius, t_peak = np.concatenate([
        np.stack(_refined_peak(np.abs(free + u[:, None] * response), t[window]))
        for u in np.array_split(flat, max(1, -(-flat.size // CHUNK)))], axis=1)
    radius, t_peak = radius.reshape(np.shape(unbalance)), t_peak.reshape(np.shape(unbalance))
    if not radius.ndim:
        radius, t_peak = float(radius), float(t_peak)
    return Passage(radius, t_peak, b.k * radius, float(t_c), float(sweep))
