"""Absorber designs built from rules: Den Hartog's classical single absorber and the paper's
mass-ratio family (Fig 6)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorvib.checks import instance, number
from rotorvib.models.absorber.parameters import AbsorberSet, Rotor


def den_hartog_single(rotor: Rotor, m: float, d: float) -> AbsorberSet:
    """Classical single absorber set of body mass ``m`` at radius ``d`` tuned by Den Hartog.

    Eliminating the relative coordinate shows the set is exactly a classical absorber of mass
    ``2m``, spring ``4k`` and damper ``4c`` on a main mass ``J/d^2``, so with
    ``mu = 2 m d^2 / J``: ``omega_a = omega_n / (1 + mu)`` (``omega_a^2 = 2k/m``) and
    ``zeta = sqrt(3 mu / (8 (1 + mu)^3))`` (``zeta = c / (m omega_a)``)
    [Den Hartog, Mechanical Vibrations, 1956, section 3.3].  ``m`` and ``d`` are finite and
    > 0 (kg and m), and so is ``mu``, each within :data:`rotorvib.checks.MAGNITUDES`.
    """
    rotor = instance("rotor", rotor, Rotor)
    m, d = number("m", m, what=" (kg)"), number("d", d, what=" (m)")
    mu = number("the mass ratio 2 m d^2 / J of m and d", 2 * m * d * d / rotor.J)
    omega_a = rotor.omega_n / (1 + mu)
    zeta = np.sqrt(3 * mu / (8 * (1 + mu) ** 3))
    return AbsorberSet(m=m, k=m * omega_a**2 / 2, c=zeta * m * omega_a, d=d)


#: Ways to build a dual absorber of mass ratio ``mu = m2/m1`` from a reference one (Fig 6; the
#: paper does not say which it used, nor what it holds fixed): ``tuned`` scales the spring with
#: the mass, ``mass_only`` keeps the reference spring (both add absorber mass as mu grows),
#: ``fixed_total`` keeps the total absorber mass m1 + m2 and both sets' tuning.
CONSTRUCTIONS = {
    "tuned": "m2 = mu m1, k2 = mu k1",
    "mass_only": "m2 = mu m1, k2 as the reference",
    "fixed_total": "m1 + m2 as the reference, m2 = mu m1, both sets tuned as the reference's set 1",
}


def mass_ratio_family(reference, mu: float, construction: str = "tuned"):
    """Dual absorber with ``m2 = mu m1``; ``tuned`` also sets ``k2 = mu k1`` (set 2 keeps the
    tuning ``2 k2 / m2 = 2 k1 / m1`` of the reference), ``mass_only`` keeps the reference's
    ``k2``; ``fixed_total`` keeps ``m1 + m2`` of the reference, so ``m1 = (m1_ref + m2_ref) /
    (1 + mu)``, and tunes both sets as the reference's set 1 (``k_i = m_i k1_ref / m1_ref``);
    ``c1, c2, d1, d2`` as in the reference.  For the paper's Table 2 (``m2/m1 = k2/k1 = 0.85``)
    ``mu = 0.85`` returns Table 2 itself under all three.  ``mu`` is
    finite and > 0; ``reference`` two :class:`AbsorberSet`."""
    mu = number("mu", mu, what=" (m2 / m1)")
    if len(reference) != 2 or not all(isinstance(s, AbsorberSet) for s in reference):
        raise ValueError(f"reference = {reference!r}: must be two AbsorberSet")
    first, second = reference
    if construction == "tuned":
        return first, replace(second, m=mu * first.m, k=mu * first.k)
    if construction == "mass_only":
        return first, replace(second, m=mu * first.m)
    if construction == "fixed_total":
        m1 = (first.m + second.m) / (1 + mu)
        stiffness = first.k / first.m                 # the reference's set 1 tuning, k / m
        return (replace(first, m=m1, k=stiffness * m1),
                replace(second, m=mu * m1, k=stiffness * mu * m1))
    raise ValueError(f"unknown construction {construction!r}; one of {list(CONSTRUCTIONS)}")
