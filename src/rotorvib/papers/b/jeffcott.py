"""Beyond paper B: its rotor without balls, a Jeffcott rotor, as a case shared with ROSS.

Without balls paper B's equations (with the consistent kinematics, disk angle ``phi = int w
dt``) reduce to the Jeffcott rotor: the geometric centre ``z = x + i y`` of a disk of mass ``M``
whose mass centre lies ``eps`` from it obeys

    M z'' + c z' + k z = M eps (phi'^2 - i phi'') e^{i phi},

so at a constant speed ``w`` (``Omega = w / omega_n``, ``omega_n = sqrt(k / M)``) the steady
response is ``z = H e^{i w t}`` with

    H = eps Omega^2 / (1 - Omega^2 + 2 i zeta Omega):

amplitude ``|H|`` and phase ``arg H`` (the lag of the whirl behind the unbalance, from 0 through
-pi/2 at ``omega_n`` towards -pi).  The package's engine needs balls: they are given a
negligible mass.  :mod:`rotorvib.papers.b.ross_model` computes the same rotor with ROSS.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.models.balancer.kinematics import profile_speed
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile
from rotorvib.models.balancer.simulate import simulate
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import Setup

#: The balls' initial angles (rad): any, their mass is negligible.
BALLS = (0.0, np.pi)
#: The balance criterion's radius (m): never reached (the whirl grows from 0 to the unbalance's
#: scale at once), so every run goes on to its end; the least radius an argument may have.
NEVER = 1e-100


def steady_response(eps: float, zeta: float, omega_bar) -> np.ndarray:
    """``H = eps Omega^2 / (1 - Omega^2 + 2 i zeta Omega)`` (m), vectorised over the speed
    ratio."""
    w = np.asarray(omega_bar, dtype=float)
    return eps * w**2 / (1 - w**2 + 2j * zeta * w)


def ballless(setup: Setup, eps_bar: float, m_bar: float) -> Balancer:
    """Paper B's machine with balls of mass ratio ``m_bar`` (negligible) and damping 1."""
    return Balancer.from_paper_b(M=setup.M, k=setup.k, R=setup.R, m_bar=m_bar, eps_bar=eps_bar,
                                 zeta=setup.zeta, beta=1.0, n=setup.n)


def engine_steady(setup: Setup, eps_bar: float, m_bar: float, speeds, settle: float,
                  sample_dt: float) -> np.ndarray:
    """The engine's steady response ``H`` at each constant speed (rad/s): the complex whirl
    ``z e^{-i w t}`` averaged over the last five revolutions of a run of ``settle`` s (the free
    vibration decays as ``exp(-zeta omega_n t)``)."""
    b = ballless(setup, eps_bar, m_bar)
    out = np.empty(len(speeds), dtype=complex)
    for i, w in enumerate(speeds):
        tr = simulate(b, SpeedProfile(omega=float(w), kind="constant", kinematics="consistent"),
                      BALLS, settle, r0=0.0, sample_dt=sample_dt, r_threshold=NEVER,
                      store=True, **setup.tolerances)
        last = tr.t > tr.t[-1] - 5 * 2 * np.pi / w
        z = tr.y[last, 0] + 1j * tr.y[last, 1]
        out[i] = np.mean(z * np.exp(-1j * w * tr.t[last]))
    return out


def engine_runup(setup: Setup, eps_bar: float, m_bar: float, t_end: float, dt: float):
    """The engine's whirl radius ``r(t)`` (m) at times ``0, dt, ...`` through paper B's run-up
    (eq. 37, consistent kinematics), from rest."""
    b = ballless(setup, eps_bar, m_bar)
    profile = SpeedProfile(omega=setup.omega, kind="runup", t_ramp=setup.t_ramp,
                           kinematics="consistent")
    tr = simulate(b, profile, BALLS, t_end, r0=0.0, sample_dt=dt, r_threshold=NEVER,
                  store=True, **setup.tolerances)
    return tr.t, tr.r, profile


def jeffcott_dataset(setup: Setup, *, eps_bar: float, m_bar: float, speeds, settle: float,
                     t_end: float, dt: float, ross_steady, ross_runup) -> xr.Dataset:
    """Steady response over ``speeds`` and the run-up, by the closed form, the engine and
    ROSS (``ross_steady(speeds) -> H``, ``ross_runup(t, (w, w', w'', int w dt)) -> r``)."""
    speeds = np.asarray(speeds, dtype=float)
    omega_n = np.sqrt(setup.k / setup.M)
    eps = eps_bar * setup.R
    by = {"closed_form": steady_response(eps, setup.zeta, speeds / omega_n),
          "engine": engine_steady(setup, eps_bar, m_bar, speeds, settle, dt),
          "ross": ross_steady(speeds)}
    t, r_engine, profile = engine_runup(setup, eps_bar, m_bar, t_end, dt)
    speed = profile_speed(profile, t)                    # (w, w', w'', int w dt) at the samples
    r_ross = ross_runup(t, speed)
    names = {"closed_form": "closed form", "engine": "the package's engine (balls of "
             f"mass ratio {m_bar:g})", "ross": "ROSS"}
    m = {"units": "m"}
    return xr.Dataset(
        {**{f"amplitude_{k}": ("speed", np.abs(v), {"long_name": f"steady whirl amplitude, "
                                                                 f"{names[k]}", **m})
            for k, v in by.items()},
         **{f"phase_{k}": ("speed", np.angle(v), {"long_name": f"phase of the whirl behind the "
                                                              f"unbalance, {names[k]}",
                                                  "units": "rad"})
            for k, v in by.items()},
         "r_engine": ("t", r_engine, {"long_name": f"whirl radius in the run-up, "
                                                      f"{names['engine']}", **m}),
         "r_ross": ("t", r_ross, {"long_name": "whirl radius in the run-up, ROSS", **m}),
         "speed_runup": ("t", speed[0], {"long_name": "disk speed in the run-up",
                                                       "units": "rad s-1"}),
         "omega_n": ((), omega_n, {"long_name": "natural frequency sqrt(k/M)",
                                   "units": "rad s-1"}),
         "eps": ((), eps, {"long_name": "eccentricity of the disk's mass centre", **m}),
         "zeta": ((), setup.zeta, {"long_name": "support damping ratio", "units": "1"})},
        coords={"speed": ("speed", speeds, {"long_name": "constant disk speed",
                                            "units": "rad s-1"}),
                "t": ("t", t, {"long_name": "time", "units": "s"})},
        attrs=dataset_attrs("the rotor without balls against ROSS",
                            "Beyond the paper: paper B's rotor without balls (a Jeffcott rotor): "
                            "steady unbalance response over the speed and a run-up through the "
                            "critical speed, by the closed form, the package's engine and ROSS",
                            "eqs 2-3 without balls, eq. 37"),
    )
