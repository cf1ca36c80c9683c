"""Steady-state torsional response of paper C's rotor with absorber sets (eqs 14-20).

Three routes to the same amplitude, used to check one another:

* :func:`steady_state` solves ``A q = [Gamma0, 0, ...]`` with ``A = -M w^2 + i w C + K``
  (eqs 16-18) for any number of absorber sets;
* :func:`theta_eq20` is the paper's closed form ``Theta = a22 a33 Gamma0 / det(A)`` (eq. 20) for the
  dual absorber, vectorised over design vectors (the genetic algorithm's objective), with either
  the correct determinant or the printed one (which has the wrong sign on ``a13 a22 a31``);
* with no absorber both reduce to ``Gamma0 / (k_t - J w^2)``, i.e. ``D = 1/|1 - w^2|``.
"""

from __future__ import annotations

import numpy as np

from rotorvib.checks import finite_array, integer, nonnegative_array
from rotorvib.models.absorber.linear import matrices
from rotorvib.models.absorber.parameters import DUAL_NAMES, Rotor


def dynamic_stiffness(rotor: Rotor, sets, omega, spin: float = 0.0) -> np.ndarray:
    """``A(w) = -M w^2 + i w C + K`` (eq. 18), shape ``omega.shape + (n, n)``; ``spin`` as in
    :func:`~rotorvib.models.absorber.linear.matrices`; ``omega`` (rad/s) finite and >= 0
    (:func:`rotorvib.checks.nonnegative_array`)."""
    M, C, K = matrices(rotor, sets, spin)
    w = nonnegative_array("omega", omega, "a frequency (rad/s)")[..., None, None]
    return -M * w**2 + 1j * w * C + K


def steady_state(rotor: Rotor, sets, omega, spin: float = 0.0) -> np.ndarray:
    """Complex amplitudes ``[Theta, S1, S2, ...]`` (rad, m, m) of eq. (17) by a linear solve;
    ``spin`` as in :func:`~rotorvib.models.absorber.linear.matrices`."""
    A = dynamic_stiffness(rotor, sets, omega, spin)
    rhs = np.zeros(A.shape[:-1], dtype=complex)
    rhs[..., 0] = rotor.Gamma0
    return np.linalg.solve(A, rhs[..., None])[..., 0]


def theta_eq20(rotor: Rotor, x, omega, *, printed_determinant: bool = False) -> np.ndarray:
    """Complex ``Theta`` of eq. (20) for dual-absorber design vectors ``x[..., 8]`` (DUAL_NAMES).

    ``printed_determinant=True`` uses the determinant as printed,
    ``a11 a22 a33 + a13 a22 a31 - a12 a21 a33``; the default uses the true cofactor expansion
    ``a11 a22 a33 - a13 a22 a31 - a12 a21 a33``.
    """
    x = finite_array("x", x)
    if x.shape[-1:] != (len(DUAL_NAMES),):
        raise ValueError(f"x: shape {x.shape}, expected (..., {len(DUAL_NAMES)}) in the order "
                         f"{DUAL_NAMES}")
    m1, m2, k1, k2, c1, c2, d1, d2 = np.moveaxis(x, -1, 0)
    w2 = nonnegative_array("omega", omega, "a frequency (rad/s)") ** 2
    w = np.sqrt(w2)
    a11 = -(rotor.J + 2 * m1 * d1**2 + 2 * m2 * d2**2) * w2 + rotor.k_t
    a12, a13 = -2 * m1 * d1 * w2, -2 * m2 * d2 * w2
    a21, a31 = -m1 * d1 * w2, -m2 * d2 * w2
    a22 = -m1 * w2 + 2j * c1 * w + 2 * k1
    a33 = -m2 * w2 + 2j * c2 * w + 2 * k2
    sign = 1.0 if printed_determinant else -1.0
    det = a11 * a22 * a33 + sign * a13 * a22 * a31 - a12 * a21 * a33
    return a22 * a33 * rotor.Gamma0 / det


def dimensionless_amplitude(rotor: Rotor, theta) -> np.ndarray:
    """``D = |Theta| k_t / Gamma0`` (paper C, after eq. 20)."""
    return np.abs(theta) * rotor.k_t / rotor.Gamma0


def amplitude(rotor: Rotor, sets, w, spin: float = 0.0) -> np.ndarray:
    """``D(w)`` of the rotor with ``sets`` at frequency ratios ``w = omega / omega_n``;
    ``spin`` as in :func:`~rotorvib.models.absorber.linear.matrices`; ``w`` finite and >= 0."""
    omega = nonnegative_array("w", w, "a frequency ratio") * rotor.omega_n
    return dimensionless_amplitude(rotor, steady_state(rotor, sets, omega, spin)[..., 0])


def bare_rotor_amplitude(w) -> np.ndarray:
    """``D = 1/|1 - w^2|`` of the rotor without absorber (infinite at ``w = 1``, the one
    infinity it returns); ``w`` finite and >= 0."""
    w = nonnegative_array("w", w, "a frequency ratio")
    with np.errstate(divide="ignore"):
        return 1.0 / np.abs(1.0 - w**2)


def natural_frequencies(rotor: Rotor, sets) -> np.ndarray:
    """Undamped natural frequencies ``w_i / omega_n``, ascending: ``sqrt`` of the eigenvalues of
    ``K q = w^2 M q`` (the poles of the response without damping, where D is unbounded)."""
    from scipy.linalg import eigvals  # here: the jobs that only evaluate eq. (20) need no scipy

    M, _, K = matrices(rotor, sets)
    lam = np.sort(eigvals(K, M).real)
    return np.sqrt(lam) / rotor.omega_n


def rotor_peak(rotor: Rotor, sets, *, samples: int = 4001) -> tuple[float, float]:
    """``(w, D)`` of the largest ``D(w) = |Theta| k_t / Gamma0`` over all frequencies of a damped
    design: sampled on ``[w_1 / 2, 2 w_n]`` around its undamped natural frequencies ``w_i``
    (log-spaced), then refined by a bounded scalar search between the neighbours of the best
    sample."""
    from scipy.optimize import minimize_scalar  # here, as eigvals above

    samples = integer("samples", samples, 3, 1_000_000)
    w_nat = natural_frequencies(rotor, sets)
    w = np.geomspace(w_nat[0] / 2, 2 * w_nat[-1], samples)

    def D(x):
        return amplitude(rotor, sets, x)

    i = int(np.argmax(D(w)))
    lo, hi = w[max(i - 1, 0)], w[min(i + 1, samples - 1)]
    best = minimize_scalar(lambda x: -float(D(x)), bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-10})
    return float(best.x), float(-best.fun)
