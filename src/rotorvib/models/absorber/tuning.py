"""Absorber designs built from rules: Den Hartog's classical single absorber and the paper's
mass-ratio family (Fig 6)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorvib.models.absorber.parameters import AbsorberSet, Rotor


def den_hartog_single(rotor: Rotor, m: float, d: float) -> AbsorberSet:
    """Classical single absorber set of body mass ``m`` at radius ``d`` tuned by Den Hartog.

    Eliminating the relative coordinate shows the set is exactly a classical absorber of mass
    ``2m``, spring ``4k`` and damper ``4c`` on a main mass ``J/d^2``, so with
    ``mu = 2 m d^2 / J``: ``omega_a = omega_n / (1 + mu)`` (``omega_a^2 = 2k/m``) and
    ``zeta = sqrt(3 mu / (8 (1 + mu)^3))`` (``zeta = c / (m omega_a)``)
    [Den Hartog, Mechanical Vibrations, 1956, section 3.3].
    """
    mu = 2 * m * d**2 / rotor.J
    omega_a = rotor.omega_n / (1 + mu)
    zeta = np.sqrt(3 * mu / (8 * (1 + mu) ** 3))
    return AbsorberSet(m=m, k=m * omega_a**2 / 2, c=zeta * m * omega_a, d=d)


def mass_ratio_family(reference, mu: float):
    """Dual absorber with ``m2 = mu m1`` and ``k2 = mu k1`` (set 2 keeps the tuning
    ``2 k2 / m2 = 2 k1 / m1`` of the reference); ``c1, c2, d1, d2`` as in the reference.
    For the paper's Table 2 (``m2/m1 = k2/k1 = 0.85``) ``mu = 0.85`` returns Table 2 itself."""
    first, second = reference
    return first, replace(second, m=mu * first.m, k=mu * first.k)
