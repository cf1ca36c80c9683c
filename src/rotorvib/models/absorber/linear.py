"""The linearised equations of paper C's rotor with absorber sets (eq. 14), ``M q'' + C q' + K q
= [Gamma, 0, ...]``: the matrices that the frequency response (:mod:`.frequency_response`, eqs
16-20) and the exact linear time response (:mod:`.time_response`) both solve."""

from __future__ import annotations

import numpy as np

from rotorvib.checks import number
from rotorvib.models.absorber.parameters import Rotor


def matrices(rotor: Rotor, sets, spin: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass, damping and stiffness matrices of the linearised equations (eq. 14), any set count.

    Row 0 is the disk equation (11); row ``j`` the equation (12)/(13) of set ``j`` as printed
    (divided by 2, so M is not symmetric).  ``spin`` is the rotor's mean speed Omega (rad/s),
    which the paper's kinetic energy leaves out: with it the term ``-m u (Omega + theta')^2`` of
    eq. (9), linearised, softens each set's stiffness to ``2 k - m Omega^2`` (beyond the paper;
    0 gives eq. 14 as printed; a finite number >= 0 within
    :data:`rotorvib.checks.MAGNITUDES`, its square entering the stiffness).
    """
    spin = number("spin", spin, inclusive=True, what=" (rotor speed, rad/s)")
    n = 1 + len(sets)
    M, C, K = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))
    M[0, 0] = rotor.J + sum(2 * s.m * s.d**2 for s in sets)
    K[0, 0] = rotor.k_t
    for j, s in enumerate(sets, start=1):
        M[0, j] = 2 * s.m * s.d
        M[j, 0] = s.m * s.d
        M[j, j] = s.m
        C[j, j] = 2 * s.c
        K[j, j] = 2 * s.k - s.m * spin**2
    return M, C, K
