"""Second-order Taylor expansion of the balancer's rotating-frame vector field at an equilibrium
(paper A): the ``J`` and quadratic tensor ``T`` that :mod:`rotorvib.methods.multiple_scales` needs.

The derivatives are exact: taken symbolically (sympy) of Lagrange's equations
``E = M(q) q'' - G(q, q')`` of :func:`rotorvib.models.balancer.stability.rotating_lagrange_equations`.  With
``a = M^-1 G`` the accelerations and ``delta`` the deviation of ``z = (q, q')``::

    a ~ M0^-1 [G1 delta + 1/2 G2(delta, delta)] - M0^-1 M1(delta q) M0^-1 G1 delta,

so ``T_a = M0^-1 G2 + B + B^T`` with ``B_imn = -(M0^-1)_ir (dM_rs/dz_m) (M0^-1 G1)_sn``.
"""

from __future__ import annotations

import sys
from functools import lru_cache

import numpy as np
import sympy as sp

from rotorvib.methods.codegen import cached_lambdify
from rotorvib.models.balancer import stability
from rotorvib.models.balancer.stability import PARAMETERS, TAU, rotating_lagrange_equations

STATE = sp.symbols("u v a1 a2 up vp a1p a2p", real=True)


@lru_cache(maxsize=1)
def _derivatives():
    """Symbolic ``(M, G1, G2, dM)`` (module docstring) in the parameters and the state."""
    q, eqs = rotating_lagrange_equations()
    z = STATE
    acc = sp.symbols("udd vdd a1dd a2dd", real=True)
    subs = {}
    for qj, zq, zp, zd in zip(q, z[:4], z[4:], acc):
        subs[sp.diff(qj, TAU, 2)] = zd
        subs[sp.diff(qj, TAU)] = zp
    plain = [e.subs(subs).subs(dict(zip(q, z[:4]))) for e in eqs]
    M = sp.Matrix([[sp.diff(e, a) for a in acc] for e in plain])
    G = sp.Matrix([-e.subs({a: 0 for a in acc}) for e in plain])
    G1 = G.jacobian(z)
    G2 = [[[sp.diff(G[i], z[m], z[k]) for k in range(8)] for m in range(8)] for i in range(4)]
    dM = [[[sp.diff(M[r, s], z[m]) for m in range(8)] for s in range(4)] for r in range(4)]
    return M, G1, G2, dM


@lru_cache(maxsize=1)
def _derivative_functions():
    return tuple(cached_lambdify(f"taylor_{name}", PARAMETERS + STATE,
                                 lambda i=i: _derivatives()[i],
                                 modules=(sys.modules[__name__], stability))
                 for i, name in enumerate(("M", "G1", "G2", "dM")))


def taylor_at(mu, rho, zeta, beta, omega, state) -> tuple[np.ndarray, np.ndarray]:
    """``(J, T)`` of the 8-dimensional first-order system at ``state`` (an equilibrium
    ``[u, v, a1, a2, 0, 0, 0, 0]``), in the time ``tau = w_n t``."""
    fM, fG1, fG2, fdM = _derivative_functions()
    args = (mu, rho, zeta, beta, omega, *np.asarray(state, float))
    M0inv = np.linalg.inv(np.array(fM(*args), dtype=float))
    G1 = np.array(fG1(*args), dtype=float)
    G2 = np.array(fG2(*args), dtype=float)
    dM = np.array(fdM(*args), dtype=float)
    A1 = M0inv @ G1
    B = -np.einsum("ir,rsm,sn->imn", M0inv, dM, A1)
    Ta = np.einsum("ir,rmn->imn", M0inv, G2) + B + B.transpose(0, 2, 1)
    J = np.zeros((8, 8))
    J[:4, 4:] = np.eye(4)
    J[4:] = A1
    T = np.zeros((8, 8, 8))
    T[4:] = Ta
    return J, T


def balanced_state(rho: float) -> np.ndarray:
    """The balanced equilibrium ``u = v = 0``, ``a1 = -a2 = arccos(-1/(2 rho))``."""
    a = np.arccos(-1.0 / (2.0 * rho))
    return np.array([0.0, 0.0, a, -a, 0.0, 0.0, 0.0, 0.0])
