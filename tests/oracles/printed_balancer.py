"""Paper B's equations (7)-(9) exactly as printed, in polar coordinates (numpy, not compiled).

Used to show that the engine's regular Cartesian form with the printed kinematics is the same
model: the two agree wherever the polar form is defined (``r > 0``).  State
``[r, theta, phi_1..phi_n, r', theta', phi_1'..phi_n']``.
"""

from __future__ import annotations

import numpy as np

from rotorvib.models.balancer.kinematics import profile_speed
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile


def rhs_polar_printed(t, y, b: Balancer, profile: SpeedProfile):
    """Right-hand side of (7)-(9) as printed: disk angle ``w t``, its rate ``w + w' t`` and the
    second derivative written ``2 w'``; the mass matrix solved numerically."""
    n = b.n
    r, th, phi = y[0], y[1], y[2:n + 2]
    rd, thd, phid = y[n + 2], y[n + 3], y[n + 4:]
    w, wd, _, _ = (float(v[0]) for v in profile_speed(profile, t))
    mt = b.M + n * b.m
    a = phi + w * t - th
    S, C = np.sin(a), np.cos(a)
    rate = phid + w + wd * t
    psi = w * t - th
    mass = np.zeros((n + 2, n + 2))
    force = np.zeros(n + 2)
    mR = b.m * b.R
    # (7)
    mass[0, 0] = mt
    mass[0, 2:] = -mR * S
    force[0] = -(mt * (-r * thd**2) + b.c * rd + b.k * r - mR * np.sum(2 * wd * S + rate**2 * C)
                 - b.M * b.eps * ((w + wd * t) ** 2 * np.cos(psi) + 2 * wd * np.sin(psi)))
    # (8)
    mass[1, 1] = mt * r
    mass[1, 2:] = mR * C
    force[1] = -(mt * 2 * rd * thd + b.c * r * thd + mR * np.sum(2 * wd * C - rate**2 * S)
                 - b.M * b.eps * ((w + wd * t) ** 2 * np.sin(psi) - 2 * wd * np.cos(psi)))
    # (9)
    for i in range(n):
        mass[2 + i, 0] = -mR * S[i]
        mass[2 + i, 1] = mR * r * C[i]
        mass[2 + i, 2 + i] = mR * b.R
        force[2 + i] = -(mR * b.R * 2 * wd + b.D * phid[i]
                         - mR * (-r * thd**2 * S[i] - 2 * rd * thd * C[i]))
    acc = np.linalg.solve(mass, force)
    return np.concatenate((y[n + 2:], acc))


def polar_to_fixed(yp: np.ndarray, n: int) -> np.ndarray:
    """Map polar states (rows) to the engine's FIXED-form states."""
    r, th, rd, thd = yp[:, 0], yp[:, 1], yp[:, n + 2], yp[:, n + 3]
    out = np.empty_like(yp)
    out[:, 0], out[:, 1] = r * np.cos(th), r * np.sin(th)
    out[:, 2:n + 2] = yp[:, 2:n + 2]
    out[:, n + 2] = rd * np.cos(th) - r * thd * np.sin(th)
    out[:, n + 3] = rd * np.sin(th) + r * thd * np.cos(th)
    out[:, n + 4:] = yp[:, n + 4:]
    return out
