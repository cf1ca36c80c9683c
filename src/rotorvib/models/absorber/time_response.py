"""Forced time response of paper C's rotor with absorber sets.

State ``y = [theta, u_1..u_n, theta', u_1'..u_n']`` for ``n`` absorber sets, forcing
``Gamma(t) = Gamma0 cos(w t)`` (the real part of the paper's ``Gamma0 exp(i w t)``), start from rest.

* :func:`rhs_nonlinear` is eqs (8)-(10) generalised to ``n`` sets,
  ``(J + sum 2 m_j (u_j^2 + d_j^2)) theta'' + sum 2 m_j d_j u_j'' + sum 4 m_j u_j u_j' theta'
  + k_t theta = Gamma`` and ``m_j u_j'' + m_j d_j theta'' - m_j u_j theta'^2 + 2 c_j u_j'
  + 2 k_j u_j = 0``, solved for the accelerations by eliminating ``u_j''`` (the reduced disk
  inertia ``J + sum 2 m_j u_j^2`` is always positive);
* :func:`rhs_linear` is the matrix form (14), ``M q'' + C q' + K q = [Gamma, 0, ...]``;
* :func:`linear_response` solves (14) exactly: with ``y = [q, q']``, ``y' = A y + b cos(w t)``,
  ``y(t) = Re(Y e^{i w t}) + V e^{Lambda t} V^-1 (y(0) - Re Y)`` for ``(i w I - A) Y = b`` and
  ``A = V Lambda V^-1``.
"""

from __future__ import annotations

import numpy as np

from rotorvib.checks import integer, nonnegative_array, number
from rotorvib.methods.integrate import integrate
from rotorvib.models.absorber.linear import matrices
from rotorvib.models.absorber.parameters import Rotor


def _set_arrays(sets):
    return tuple(np.array([getattr(s, name) for s in sets], dtype=float) for name in "mkcd")


def rhs_nonlinear(t, y, J, k_t, gamma0, m, k, c, d, omega):
    """Eqs (8)-(10) for the disk (``J``, ``k_t``, forcing amplitude ``gamma0``) and the sets'
    arrays ``m, k, c, d`` (see the module docstring)."""
    n = len(m)
    theta, u = y[0], y[1:n + 1]
    dtheta, du = y[n + 1], y[n + 2:]
    gamma = gamma0 * np.cos(omega * t)
    f = m * u * dtheta**2 - 2 * c * du - 2 * k * u          # = m_j (u_j'' + d_j theta'')
    inertia = J + np.sum(2 * m * u**2)
    ddtheta = (gamma - k_t * theta - np.sum(4 * m * u * du) * dtheta
               - np.sum(2 * d * f)) / inertia
    ddu = f / m - d * ddtheta
    return np.concatenate(([dtheta], du, [ddtheta], ddu))


def rhs_linear(t, y, minv, C, K, gamma0, omega):
    """Right-hand side of eq. (14) as first-order system: ``q'' = M^-1 (f(t) - C q' - K q)``
    with ``f = (Gamma0 cos(omega t), 0, 0)``, ``y = (q, q')``, ``minv = M^-1``."""
    n = len(y) // 2
    force = np.zeros(n)
    force[0] = gamma0 * np.cos(omega * t)
    q, dq = y[:n], y[n:]
    return np.concatenate((dq, minv @ (force - C @ dq - K @ q)))


def simulate(rotor: Rotor, sets, omega: float, t, *, model: str = "nonlinear",
             rtol: float = 1e-10, atol: float = 1e-13) -> np.ndarray:
    """Response from rest at times ``t``; returns ``q(t)``, shape ``(len(t), 1 + n_sets)``
    (``theta`` in rad, then each set's displacement in m).  ``model`` is ``"nonlinear"``
    (eqs 8-10) or ``"linear"`` (eq. 14).  ``t`` (s) increasing from a time >= 0, spanning at
    most :data:`MAX_PERIODS` periods of the forcing and of the bare rotor (the integrator's
    work grows with them: a span of 1e300 s would never end)."""
    omega = number("omega", omega, what=" (forcing frequency, rad/s)")
    t = _times(t)
    periods = (t[-1] - t[0]) * max(omega, rotor.omega_n) / (2 * np.pi)
    if periods > MAX_PERIODS:
        raise ValueError(f"t: spans {t[-1] - t[0]:.6g} s, {periods:.3g} periods of "
                         f"max(omega, omega_n) = {max(omega, rotor.omega_n):.6g} rad/s; at most "
                         f"{MAX_PERIODS:.0e}")
    n = 1 + len(sets)
    y0 = np.zeros(2 * n)
    if model == "nonlinear":
        y = integrate(rhs_nonlinear, y0, t, rtol=rtol, atol=atol,
                      args=(rotor.J, rotor.k_t, rotor.Gamma0, *_set_arrays(sets), omega))
    elif model == "linear":
        M, C, K = matrices(rotor, sets)
        y = integrate(rhs_linear, y0, t, rtol=rtol, atol=atol,
                      args=(np.linalg.inv(M), C, K, rotor.Gamma0, omega))
    else:
        raise ValueError(f"model must be 'nonlinear' or 'linear', not {model!r}")
    return y[:, :n]


def linear_response(rotor: Rotor, sets, omega: float, t) -> np.ndarray:
    """Exact response of eq. (14) from rest at times ``t`` (module docstring), shape
    ``(len(t), 1 + n_sets)`` like :func:`simulate`; needs a damped design (``i w`` not an
    eigenvalue of ``A``)."""
    number("omega", omega, what=" (forcing frequency, rad/s)")
    t = _times(t)
    M, C, K = matrices(rotor, sets)
    n = len(M)
    minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ K, -minv @ C]])
    b = np.concatenate((np.zeros(n), minv[:, 0] * rotor.Gamma0))
    forced = np.linalg.solve(1j * omega * np.eye(2 * n) - A, b)
    lam, V = np.linalg.eig(A)
    free = np.linalg.solve(V, -forced.real.astype(complex))
    t = t[:, None]
    y = np.real(forced * np.exp(1j * omega * t)) + np.real((V @ (free * np.exp(lam * t)).T).T)
    return y[:, :n]


#: Samples of one response at most (8 bytes each per state variable).
MAX_SAMPLES = 10_000_000
#: Periods of the forcing or of the bare rotor that one integrated response may span at most
#: (paper C's responses span a few hundred).
MAX_PERIODS = 1_000_000


def _times(t) -> np.ndarray:
    """``t`` as the times of a response: one dimension, at most :data:`MAX_SAMPLES`, each
    finite and >= 0 (:func:`rotorvib.checks.nonnegative_array`), increasing; ``ValueError``
    naming ``t`` otherwise."""
    t = nonnegative_array("t", t, "a time (s)")
    if t.ndim != 1 or not 1 <= len(t) <= MAX_SAMPLES or np.any(np.diff(t) <= 0):
        raise ValueError(f"t: shape {t.shape}; must be 1 to {MAX_SAMPLES} increasing times")
    return t


def response_times(omega: float, t_end: float, samples_per_period: int) -> np.ndarray:
    """Times ``0 .. t_end`` at ``samples_per_period`` samples per forcing period ``2 pi/omega``;
    ``ValueError`` naming the argument when one is out of its domain or the times would be more
    than :data:`MAX_SAMPLES`."""
    period = 2 * np.pi / number("omega", omega, what=" (forcing frequency, rad/s)")
    t_end = number("t_end", t_end, what=" (s)")
    per_period = integer("samples_per_period", samples_per_period, 2)
    samples = t_end / period * per_period
    if samples > MAX_SAMPLES:
        raise ValueError(f"t_end = {t_end!r}: {samples:.3g} samples at omega = {omega!r} and "
                         f"{per_period} per period; at most {MAX_SAMPLES}")
    return np.linspace(0.0, t_end, int(round(samples)) + 1)


def undamped_resonance_envelope(rotor: Rotor, t):
    """Exact envelope ``Gamma0 t / (2 J w_n)`` of the bare rotor driven at ``w_n`` from rest;
    ``t`` (s) finite and >= 0."""
    return rotor.Gamma0 * nonnegative_array("t", t, "a time (s)") / (2 * rotor.J * rotor.omega_n)
