"""Parameters of paper C's torsional rotor and its absorber sets.

An *absorber set* is a pair of equal masses ``m`` sliding on a line at distance ``d`` from the
disk centre, each held by two springs ``k`` and two dampers ``c`` (paper C, Figs 1-2).  The
paper's dual absorber is two such sets at right angles; a classical single absorber is one set;
the bare rotor has none.  All equations of the package are written for any number of sets.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotorvib.checks import SMALLEST_NORMAL, require

#: Order of the eight design variables of the dual absorber (paper C, section 4).
DUAL_NAMES = ("m1", "m2", "k1", "k2", "c1", "c2", "d1", "d2")


@dataclass(frozen=True)
class Rotor:
    """Disk on a torsional shaft (paper C, Table 1): mass ``M`` (kg), radius ``R`` (m), shaft
    stiffness ``k_t`` (N m/rad), torque amplitude ``Gamma0`` (N m); polar inertia
    ``J = J_factor * M R^2`` (J_factor = 1/2 for a solid disk).  Each a finite number > 0;
    ``J`` and ``omega_n = sqrt(k_t / J)`` normal and finite (``ValueError`` otherwise)."""

    M: float
    R: float
    k_t: float
    Gamma0: float
    J_factor: float = 0.5

    def __post_init__(self):
        require(self, ("M", "R", "k_t", "Gamma0", "J_factor"), ())
        if not (self.J >= SMALLEST_NORMAL and np.isfinite(self.omega_n) and self.omega_n > 0):
            raise ValueError(f"Rotor.R = {self.R!r} with M = {self.M!r} and J_factor = "
                             f"{self.J_factor!r}: the inertia J_factor M R^2 = {self.J!r} and "
                             f"omega_n = sqrt(k_t / J) must be normal, finite numbers")

    @property
    def J(self) -> float:
        return self.J_factor * self.M * self.R**2

    @property
    def omega_n(self) -> float:
        """Natural frequency of the rotor without absorbers, sqrt(k_t/J) (rad/s)."""
        return float(np.sqrt(self.k_t / self.J))


@dataclass(frozen=True)
class AbsorberSet:
    """One absorber set: mass of each of its two bodies ``m`` (kg), stiffness ``k`` (N/m) and
    damping ``c`` (N s/m) of each of the two springs/dampers per body, radius ``d`` (m)."""

    m: float
    k: float
    c: float
    d: float

    def __post_init__(self):
        require(self, ("m", "d"), ("k", "c"))

    @property
    def omega_a(self) -> float:
        """Natural frequency of the set on a locked disk, sqrt(2k/m) (eq. 12 with theta = 0)."""
        return float(np.sqrt(2 * self.k / self.m))


def dual_absorber(m1, m2, k1, k2, c1, c2, d1, d2) -> tuple[AbsorberSet, AbsorberSet]:
    """The paper's dual absorber from its eight design variables (Table 2 order)."""
    return AbsorberSet(m1, k1, c1, d1), AbsorberSet(m2, k2, c2, d2)


def dual_from_vector(x) -> tuple[AbsorberSet, AbsorberSet]:
    """The two absorber sets of a design vector ``x = (m1, m2, k1, k2, c1, c2, d1, d2)``
    (:func:`dual_absorber`)."""
    return dual_absorber(*(float(v) for v in x))


def dual_to_vector(sets) -> np.ndarray:
    """The design vector ``(m1, m2, k1, k2, c1, c2, d1, d2)`` of two absorber sets (inverse of
    :func:`dual_from_vector`)."""
    a, b = sets
    return np.array([a.m, b.m, a.k, b.k, a.c, b.c, a.d, b.d])


def design_bounds(bounds: dict) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds in DUAL_NAMES order from ``{"m": [lo, hi], "k": ..., "c": ...,
    "d": ...}`` (the paper gives one interval per kind, shared by both sets)."""
    pairs = [bounds[name[0]] for name in DUAL_NAMES]
    return np.array([p[0] for p in pairs], float), np.array([p[1] for p in pairs], float)


def undamped(sets) -> tuple[AbsorberSet, ...]:
    """The same absorber sets with zero damping (paper C, Fig 5)."""
    return tuple(replace(s, c=0.0) for s in sets)


def effective_mass_ratio(rotor: Rotor, sets) -> float:
    """Inertia added by the sets relative to the disk, sum 2 m d^2 / J: the classical mass ratio."""
    return float(sum(2 * s.m * s.d**2 for s in sets) / rotor.J)
