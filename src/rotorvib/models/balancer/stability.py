"""Linear stability of the balanced state at constant speed (papers A and B).

The linearisation ``M dq'' + C dq' + K dq = 0`` at the balanced state ``u = v = 0``,
``a_1 = -a_2 = arccos(-1/(2 rho))`` is generated symbolically (:mod:`equations`, sympy) from the
dimensionless rotating-frame energies of digest A, independently of the compiled right-hand
side (the tests compare the two through a finite-difference Jacobian), and evaluated through
generated code (:func:`rotorvib.methods.codegen.cached_lambdify`: a process finds it cached
and imports no sympy).  Eigenvalues of ``[[0, I], [-M^-1 K, -M^-1 C]]`` decide stability
(paper B eqs 27-32, paper A section 4).  Everything is vectorised over parameter grids (stacked
``eigvals``).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from rotorvib.checks import finite_array, in_domain
from rotorvib.methods.codegen import cached_lambdify
from rotorvib.models.balancer.parameters import N_BALLS

#: The files whose code defines the symbolic expressions evaluated here and in :mod:`expansion`:
#: their derivation (:mod:`equations`, imported only to derive), the module of the ball count
#: it is derived for (:data:`~rotorvib.models.balancer.parameters.N_BALLS`) and this module,
#: read for the generated code's cache key.
DERIVATION = (Path(__file__).with_name("equations.py"), Path(__file__).with_name("parameters.py"),
              Path(__file__))


def generated(name: str, derive, *, beside: str | Path = __file__):
    """The numeric function ``name`` of ``(args, expressions) = derive(equations)``, generated
    once and cached beside the module file ``beside`` (:func:`cached_lambdify`, keyed on it and
    :data:`DERIVATION`): :mod:`equations` and sympy are imported only to derive it."""
    def build():
        from rotorvib.models.balancer import equations

        return derive(equations)
    return cached_lambdify(name, build, sources=tuple(dict.fromkeys((Path(beside), *DERIVATION))))


@lru_cache(maxsize=1)
def _numeric_pencil():
    return tuple(generated(f"pencil_{name}",
                           lambda eq, i=i: (eq.PARAMETERS, list(eq.pencil_matrices()[i])))
                 for i, name in enumerate("MCK"))


def groups(mu, rho, zeta, beta, omega) -> list[np.ndarray]:
    """The five groups, checked and broadcast together: ``0 < mu <= 1/n`` (at ``1/n`` the disk
    has no mass left and the mass matrix is singular: ``numpy.linalg.LinAlgError``),
    ``rho >= 1/2`` (the balanced state exists, ``cos a = -1/(2 rho)``; at ``1/2`` the balls lie
    together), ``zeta, beta >= 0``, ``omega`` of either sign; each finite, not bool or text, and
    0 or within :data:`rotorvib.checks.MAGNITUDES`. ``ValueError`` naming the first group
    outside."""
    named = {name: finite_array(name, value) for name, value in
             zip(("mu", "rho", "zeta", "beta", "omega"), (mu, rho, zeta, beta, omega))}
    domain = {"mu": (lambda v: (v > 0) & (v <= 1 / N_BALLS), f"in (0, 1/{N_BALLS}]"),
              "rho": (lambda v: v >= 0.5, ">= 1/2"), "zeta": (lambda v: v >= 0, ">= 0"),
              "beta": (lambda v: v >= 0, ">= 0"), "omega": (lambda v: np.isfinite(v), "real")}
    for name, (holds, allowed) in domain.items():
        in_domain(name, named[name], holds(named[name]), allowed)
    return np.broadcast_arrays(*named.values())


def _stack(f, shape, *values):
    entries = f(*values)          # the 16 entries, row by row, scalars or arrays
    out = np.empty(shape + (16,))
    for i, entry in enumerate(entries):
        out[..., i] = entry       # broadcast by the assignment
    return out.reshape(shape + (4, 4))


def jacobian(mu, rho, zeta, beta, omega) -> np.ndarray:
    """First-order system matrix at the balanced state, shape ``broadcast(...) + (8, 8)``
    (state ``[u, v, a1, a2, u', v', a1', a2']``, time unit ``1/w_n``); the groups' domain is
    that of :func:`groups`."""
    values = groups(mu, rho, zeta, beta, omega)
    shape = values[0].shape
    fM, fC, fK = _numeric_pencil()
    M, C, K = (_stack(f, shape, *values) for f in (fM, fC, fK))
    A = np.zeros(shape + (8, 8))
    A[..., :4, 4:] = np.eye(4)
    A[..., 4:, :4] = -np.linalg.solve(M, K)
    A[..., 4:, 4:] = -np.linalg.solve(M, C)
    return A


def eigenvalues(mu, rho, zeta, beta, omega) -> np.ndarray:
    """The eight eigenvalues at every parameter point (stacked ``np.linalg.eigvals``)."""
    return np.linalg.eigvals(jacobian(mu, rho, zeta, beta, omega))


def max_real_part(mu, rho, zeta, beta, omega) -> np.ndarray:
    """Largest real part of the eigenvalues: negative where the balanced state is stable."""
    return eigenvalues(mu, rho, zeta, beta, omega).real.max(axis=-1)


@lru_cache(maxsize=1)
def _coefficient_function():
    return generated("characteristic_coefficients",
                     lambda eq: (eq.PARAMETERS, eq.characteristic_polynomial().all_coeffs()))


def characteristic_coefficients(mu, rho, zeta, beta, omega) -> np.ndarray:
    """The coefficients of ``det(lambda^2 M + lambda C + K)``, highest power first, shape
    ``(..., 9)`` (the groups' domain is that of :func:`groups`)."""
    values = groups(mu, rho, zeta, beta, omega)
    shape = values[0].shape
    return np.stack([np.broadcast_to(np.asarray(c, dtype=float), shape)
                     for c in _coefficient_function()(*values)], axis=-1)


def exact_characteristic_coefficients(mu, rho, zeta, beta, omega) -> list:
    """The coefficients of :func:`characteristic_coefficients` at one point, computed in the
    arithmetic of the numbers given (``mpmath.mpf``: in their precision; the generated code is
    the polynomial's own sums and products).  The groups must lie in :func:`groups`' domain:
    the caller checks them."""
    return list(_coefficient_function()(mu, rho, zeta, beta, omega))


def polynomial_roots(mu, rho, zeta, beta, omega) -> np.ndarray:
    """The eight roots of ``det(lambda^2 M + lambda C + K) = 0`` (the multiple-scales
    eigenvalue problem of the 4x4 lambda-matrix, paper A eqs 23-33), through the symbolic
    characteristic polynomial and stacked companion matrices: a code path separate from
    :func:`eigenvalues` (Lyapunov's 8x8 Jacobian); the groups' domain is that of
    :func:`groups`."""
    coeffs = characteristic_coefficients(mu, rho, zeta, beta, omega)
    shape = coeffs.shape[:-1]
    monic = coeffs[..., 1:] / coeffs[..., :1]
    companion = np.zeros(shape + (8, 8))
    companion[..., 0, :] = -monic
    companion[..., np.arange(1, 8), np.arange(7)] = 1.0
    return np.linalg.eigvals(companion)


def stability_onsets(growth_of, omega_bar, growth, *, xtol: float = 1e-8) -> np.ndarray:
    """Speeds at which each row of ``growth`` (rows x ``omega_bar``) turns from unstable to
    stable with rising speed, located exactly: the root of ``growth_of(row, omega)`` between the
    two grid speeds that bracket the first sign change (Brent's method, to ``xtol``).  NaN for a
    row that never turns stable on the grid or is stable from its first speed on."""
    from scipy.optimize import brentq  # here: the numeric jobs need no scipy.optimize

    onsets = np.full(growth.shape[0], np.nan)
    for i, row in enumerate(growth):
        turns = np.flatnonzero((row[:-1] >= 0) & (row[1:] < 0))
        if turns.size:
            j = turns[0]
            onsets[i] = brentq(lambda w: float(growth_of(i, w)), omega_bar[j], omega_bar[j + 1],
                               xtol=xtol)
    return onsets
