"""Paper B's rotor without balls in ROSS (``ross-rotordynamics``), the open rotordynamics
code of Petrobras: the only module that imports it.

ROSS models a lateral rotor by finite elements: a shaft of Timoshenko beams, disks and
bearings.  Paper B's rigid disk on a spring support becomes a short, stiff, nearly massless
shaft of two elements with the disk (mass ``M``) at its middle node and a bearing of stiffness
``k/2`` and damping ``c/2`` at each end; the shaft's flexibility, bending and shear (ROSS's
beams are Timoshenko's), adds a compliance ``1/k_s`` in series with ``1/k`` (relative
``k/k_s``, stated with the shaft).  ROSS checks the rotor's lateral dynamics only: not the
balls, nor paper C's torsional model.

The steady response is solved from ROSS's assembled matrices, not through its modal route
(``run_unbalance_response``): that route inverts the matrix of the state-space eigenvectors,
whose condition number is about 1.5e10 for a nearly massless shaft (eigenvalues spread over ten
orders), so its amplitudes carry a round-off of ``cond * eps`` = 3e-6, amplified to 5e-5 at the
resonance, and move by that much with the BLAS kernel.  The dynamic stiffness solved here has a
condition number below 1e8: its round-off, 2e-8, is far below every difference tested.
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
    """Lateral stiffness at the middle of a simply supported Timoshenko shaft, bending and
    shear in series: ``1/k_s = L^3 / (48 E I) + L / (4 kappa G A)``, with Cowper's shear
    coefficient of a solid circle ``kappa = 6 (1 + nu) / (7 + 6 nu)``, ``nu = E / (2 G) - 1``
    (the default of ROSS's shaft element)."""
    d, length, E, G = shaft["diameter"], shaft["length"], shaft["E"], shaft["G"]
    nu = E / (2 * G) - 1
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    bending = length**3 / (48 * E * np.pi * d**4 / 64)
    shear = length / (4 * kappa * G * np.pi * d**2 / 4)
    return 1 / (bending + shear)


def dynamic_stiffness(model, speed: float) -> np.ndarray:
    """ROSS's dynamic stiffness of synchronous whirl at ``speed`` (its public ``K``, ``M``,
    ``C`` and ``G``): ``Z = K - W^2 M + i W (C + W G)``, from
    ``M q'' + (C + W G) q' + K q = F e^(i W t)``."""
    return (model.K(speed) - speed**2 * model.M(speed)
            + 1j * speed * (model.C(speed) + speed * model.G()))


def steady(model, unbalance: float, speeds) -> np.ndarray:
    """ROSS's complex steady response of the disk's x to an unbalance ``m e`` at the disk:
    ``Z(W) q = F`` with ``F_x = m e W^2``, ``F_y = -i m e W^2`` (the force of ROSS's
    ``run_unbalance_response`` at phase 0), solved directly (module docstring: why not ROSS's
    modal route)."""
    x = DOF_PER_NODE * DISK_NODE
    response = []
    for speed in np.asarray(speeds, dtype=float):
        force = np.zeros(model.ndof, dtype=complex)
        force[x], force[x + 1] = unbalance * speed**2, -1j * unbalance * speed**2
        response.append(np.linalg.solve(dynamic_stiffness(model, speed), force)[x])
    return np.array(response)


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
