"""Prescribed disk speed and disk angle of the balancer (compiled, used inside the right-hand
sides).

Speed profiles: ``CONSTANT`` (``w = Omega``) and ``RUNUP``, paper B's eq. (37) scaled to any
operating speed and ramp time T: ``w = Omega (t/T - sin(2 pi t/T) / (2 pi))`` for ``t < T``
(T = 0.5 s, Omega = 200 rad/s gives ``400 t - (100/pi) sin(4 pi t)``), then ``w = Omega``.

Disk angle ``Phi(t)`` of the FIXED form: paper B's printed kinematics (``Phi = w t``,
``Phi' = w + w' t``, ``Phi'' = 2 w'``, as in eqs 7-9) or the consistent kinematics
(``Phi = int w dt``, ``Phi' = w``, ``Phi'' = w'``).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rotorvib.models.balancer.layout import CONSTANT, PRINTED


@njit(cache=True, error_model="numpy")
def speed(t, omega, t_ramp, profile):
    """Return ``(w, w', w'', int_0^t w)`` of the speed profile at time ``t``."""
    if profile == CONSTANT or t >= t_ramp:
        if profile == CONSTANT:
            return omega, 0.0, 0.0, omega * t
        return omega, 0.0, 0.0, omega * (0.5 * t_ramp + (t - t_ramp))
    a = 2.0 * np.pi / t_ramp
    w = omega * (t / t_ramp - np.sin(a * t) / (2.0 * np.pi))
    wd = omega / t_ramp * (1.0 - np.cos(a * t))
    wdd = omega / t_ramp * a * np.sin(a * t)
    integral = omega * (t * t / (2.0 * t_ramp) + (np.cos(a * t) - 1.0) / (a * 2.0 * np.pi))
    return w, wd, wdd, integral


@njit(cache=True, error_model="numpy")
def disk_kinematics(t, p):
    """Disk angle, rate and acceleration ``(Phi, Phi', Phi'')`` for the FIXED form."""
    w, wd, wdd, integral = speed(t, p[8], p[9], int(p[10]))
    if int(p[11]) == PRINTED:
        return w * t, w + wd * t, 2.0 * wd
    return integral, w, wd


@njit(cache=True, error_model="numpy")
def disk_kinematics_on(t, p):
    """:func:`disk_kinematics` at each time of the array ``t``: shape ``(3, t.size)``."""
    out = np.empty((3, t.size))
    for i in range(t.size):
        out[0, i], out[1, i], out[2, i] = disk_kinematics(t[i], p)
    return out


def profile_speed(profile, t):
    """``(w, w', w'', int w dt)`` of ``profile`` (a
    :class:`~rotorvib.models.balancer.parameters.SpeedProfile`) at times ``t`` (vectorised)."""
    out = np.array([speed(float(ti), profile.omega, profile.t_ramp, profile.profile_code)
                    for ti in np.atleast_1d(t)])
    return tuple(out.T)
