"""Paper B's rotor without balls in ROSS (``ross-rotordynamics``), the open rotordynamics
code of Petrobras: the only module that imports it.

ROSS models a lateral rotor by finite elements: a shaft of Timoshenko beams, disks and
bearings.  Paper B's rigid disk on a spring support becomes a short, stiff, nearly massless
shaft of two elements with the disk (mass ``M``) at its middle node and a bearing of stiffness
``k/2`` and damping ``c/2`` at each end; the shaft's flexibility adds a compliance ``1/k_s`` in
series with ``1/k`` (relative ``k/k_s``, stated with the shaft).  ROSS checks the rotor's
lateral dynamics only: not the balls, nor paper C's torsional model.
"""

from __future__ import annotations

import contextlib
import io

import numpy as np

#: Degrees of freedom per node in ROSS (x, y and two tilts); the disk is node 1.
DOF_PER_NODE, DISK_NODE = 4, 1


def rotor(M: float, k: float, c: float, shaft: dict):
    """The ROSS rotor: two shaft elements of ``shaft["length"]/2``, solid of
    ``shaft["diameter"]``, material ``E``, ``G``, ``density``; the disk's inertias are those of
    a thin disk of the shaft's own radius scale (they do not enter the lateral response at the
    middle node of a symmetric rotor)."""
    import ross as rs

    material = rs.Material(name="shaft", rho=shaft["density"], E=shaft["E"], G_s=shaft["G"])
    elements = [rs.ShaftElement(L=shaft["length"] / 2, idl=0.0, odl=shaft["diameter"],
                                material=material) for _ in range(2)]
    radius = shaft["diameter"]
    disk = rs.DiskElement(n=DISK_NODE, m=M, Id=M * radius**2 / 4, Ip=M * radius**2 / 2)
    bearings = [rs.BearingElement(n=n, kxx=k / 2, cxx=c / 2) for n in (0, 2)]
    return rs.Rotor(elements, [disk], bearings)


def shaft_stiffness(shaft: dict) -> float:
    """Lateral stiffness at the middle of a simply supported shaft, ``48 E I / L^3``."""
    inertia = np.pi * shaft["diameter"] ** 4 / 64
    return 48 * shaft["E"] * inertia / shaft["length"] ** 3


def steady(model, unbalance: float, speeds) -> np.ndarray:
    """ROSS's complex steady response of the disk's x (``run_unbalance_response``)."""
    result = model.run_unbalance_response(node=DISK_NODE, unbalance_magnitude=unbalance,
                                          unbalance_phase=0.0, frequency=np.asarray(speeds))
    return result.forced_resp[DOF_PER_NODE * DISK_NODE]


def runup(model, unbalance: float, t, kinematics) -> np.ndarray:
    """ROSS's whirl radius of the disk under the unbalance force of a prescribed speed
    (``M eps (phi'^2 cos phi + phi'' sin phi, phi'^2 sin phi - phi'' cos phi)``), integrated by
    ROSS's Newmark scheme with speed-dependent matrices (``run_time_response`` with a speed
    array); ``kinematics = (w, w', w'', int w dt)`` at the times ``t``."""
    speed, acceleration, _, angle = kinematics
    force = np.zeros((len(t), model.ndof))
    x = DOF_PER_NODE * DISK_NODE
    force[:, x] = unbalance * (speed**2 * np.cos(angle) + acceleration * np.sin(angle))
    force[:, x + 1] = unbalance * (speed**2 * np.sin(angle) - acceleration * np.cos(angle))
    with contextlib.redirect_stdout(io.StringIO()):       # ROSS prints its method's name
        y = model.run_time_response(np.asarray(speed), force, np.asarray(t)).yout
    return np.hypot(y[:, x], y[:, x + 1])
