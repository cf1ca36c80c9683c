"""Linear stability of the balanced state at constant speed (papers A and B).

The linearisation is generated symbolically (sympy) from the dimensionless rotating-frame
energies of digest A, independently of the compiled right-hand side (the tests compare the two
through a finite-difference Jacobian).  With lengths in ``R``, time ``tau = w_n t`` and energies
in ``M_t R^2 w_n^2``::

    T = (1 - n mu)/2 |G'|^2 + mu/2 sum |B_i'|^2,   V = |C|^2 / 2,
    F = zeta |C'|^2 + mu beta / 2 sum a_i'^2,
    C = (u + i v) e^{i W tau},  G = C + mu/((1 - n mu) rho) e^{i W tau},  B_i = C + e^{i(W tau + a_i)}.

Lagrange's equations ``E(q, q', q'') = 0``, ``q = (u, v, a_1, a_2)``, linearised at the balanced
state ``u = v = 0``, ``a_1 = -a_2 = arccos(-1/(2 rho))``, give ``M dq'' + C dq' + K dq = 0``;
eigenvalues of ``[[0, I], [-M^-1 K, -M^-1 C]]`` decide stability (paper B eqs 27-32, paper A
section 4).  Everything is vectorised over parameter grids (stacked ``eigvals``).
"""

from __future__ import annotations

import sys
from functools import lru_cache

import numpy as np
import sympy as sp

from rotorvib.checks import finite_array, in_domain
from rotorvib.methods.codegen import cached_lambdify

MU, RHO, ZETA, BETA, OMEGA = sp.symbols("mu rho zeta beta Omega", positive=True)
TAU = sp.Symbol("tau", real=True)
LAMBDA = sp.Symbol("lambda")
PARAMETERS = (MU, RHO, ZETA, BETA, OMEGA)
N_BALLS = 2


def _coordinates():
    return [sp.Function(name, real=True)(TAU) for name in ("u", "v", "a1", "a2")]


def lagrange_expressions():
    """``E_j = d/dtau dT/dq_j' - dT/dq_j + dV/dq_j + dF/dq_j'`` for ``q = (u, v, a1, a2)``
    straight from the energies of the module docstring, which carry the disk's phase
    ``W tau``."""
    u, v, a1, a2 = q = _coordinates()
    phase = OMEGA * TAU

    def at(angle):
        return sp.Matrix([sp.cos(angle), sp.sin(angle)])

    centre = sp.Matrix([[sp.cos(phase), -sp.sin(phase)], [sp.sin(phase), sp.cos(phase)]]) * \
        sp.Matrix([u, v])
    ecc = MU / ((1 - N_BALLS * MU) * RHO)
    bodies = [centre + ecc * at(phase)] + [centre + at(phase + a) for a in (a1, a2)]

    def speed2(z):
        dz = sp.diff(z, TAU)
        return dz.dot(dz)

    T = (1 - N_BALLS * MU) / 2 * speed2(bodies[0]) + MU / 2 * (speed2(bodies[1]) + speed2(bodies[2]))
    V = centre.dot(centre) / 2
    F = ZETA * speed2(centre) + MU * BETA / 2 * (sp.diff(a1, TAU) ** 2 + sp.diff(a2, TAU) ** 2)
    return q, [sp.diff(sp.diff(T, sp.diff(qj, TAU)), TAU) - sp.diff(T, qj) + sp.diff(V, qj)
               + sp.diff(F, sp.diff(qj, TAU)) for qj in q]


@lru_cache(maxsize=1)
def rotating_lagrange_equations():
    """``E_j(q, q', q'')`` for ``q = (u, v, a1, a2)`` (two balls), as sympy expressions.

    The phase ``W tau`` of :func:`lagrange_expressions` cancels exactly: expanding the
    trigonometric functions and then ``sin(W tau)^2 = 1 - cos(W tau)^2`` removes it (the tests
    compare both forms at random points), in a fraction of the time of ``simplify``."""
    phase = OMEGA * TAU
    q, expressions = lagrange_expressions()
    return q, [sp.expand(sp.expand(sp.expand_trig(e)).subs(sp.sin(phase) ** 2,
                                                            1 - sp.cos(phase) ** 2))
               for e in expressions]


@lru_cache(maxsize=1)
def pencil_matrices():
    """Symbolic ``(M, C, K)`` at the balanced state, in ``mu, rho, zeta, beta, Omega``."""
    q, eqs = rotating_lagrange_equations()
    sym_q = sp.symbols("u v a1 a2")
    sym_d = sp.symbols("ud vd a1d a2d")
    sym_dd = sp.symbols("udd vdd a1dd a2dd")
    subs = {}
    for qj, s0, s1, s2 in zip(q, sym_q, sym_d, sym_dd):
        subs[sp.diff(qj, TAU, 2)] = s2
        subs[sp.diff(qj, TAU)] = s1
    plain = [e.subs(subs).subs(dict(zip(q, sym_q))) for e in eqs]
    cos_a = -1 / (2 * RHO)
    sin_a = sp.sqrt(1 - cos_a**2)
    alpha = sp.Symbol("alpha_star")
    at_eq = {sym_q[0]: 0, sym_q[1]: 0, sym_q[2]: alpha, sym_q[3]: -alpha,
             **{s: 0 for s in sym_d + sym_dd}}

    def jac(wrt):
        J = sp.Matrix([[sp.diff(e, w) for w in wrt] for e in plain]).subs(at_eq)
        J = J.subs({sp.cos(alpha): cos_a, sp.sin(alpha): sin_a})
        return sp.simplify(J)

    return jac(sym_dd), jac(sym_d), jac(sym_q)


@lru_cache(maxsize=1)
def _numeric_pencil():
    return tuple(cached_lambdify(f"pencil_{name}", PARAMETERS,
                                 lambda i=i: list(pencil_matrices()[i]),
                                 modules=(sys.modules[__name__],))
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
        out[..., i] = np.broadcast_to(np.asarray(entry, dtype=float), shape)
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
def characteristic_polynomial() -> sp.Poly:
    """``det(lambda^2 M + lambda C + K)`` as a polynomial in ``lambda`` (degree 8)."""
    M, C, K = pencil_matrices()
    return sp.Poly(sp.expand((LAMBDA**2 * M + LAMBDA * C + K).det(method="berkowitz")), LAMBDA)


@lru_cache(maxsize=1)
def _coefficient_function():
    return cached_lambdify("characteristic_coefficients", PARAMETERS,
                           lambda: characteristic_polynomial().all_coeffs(),
                           modules=(sys.modules[__name__],))


def characteristic_coefficients(mu, rho, zeta, beta, omega) -> np.ndarray:
    """The coefficients of ``det(lambda^2 M + lambda C + K)``, highest power first, shape
    ``(..., 9)`` (the groups' domain is that of :func:`groups`)."""
    values = groups(mu, rho, zeta, beta, omega)
    shape = values[0].shape
    return np.stack([np.broadcast_to(np.asarray(c, dtype=float), shape)
                     for c in _coefficient_function()(*values)], axis=-1)


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
