"""Second-order Taylor expansion of the balancer's rotating-frame vector field at an equilibrium
(paper A): the ``J`` and quadratic tensor ``T`` that :mod:`rotorvib.methods.multiple_scales` needs.

The derivatives are exact: taken symbolically (sympy) of Lagrange's equations
``E = M(q) q'' - G(q, q')`` of
:func:`rotorvib.models.balancer.equations.rotating_lagrange_equations`
(:func:`~rotorvib.models.balancer.equations.taylor_derivatives`), evaluated through generated
code (:func:`rotorvib.models.balancer.stability.generated`: a process finds it cached and
imports no sympy).  With ``a = M^-1 G`` the accelerations and ``delta`` the deviation of
``z = (q, q')``::

    a ~ M0^-1 [G1 delta + 1/2 G2(delta, delta)] - M0^-1 M1(delta q) M0^-1 G1 delta,

so ``T_a = M0^-1 G2 + B + B^T`` with ``B_imn = -(M0^-1)_ir (dM_rs/dz_m) (M0^-1 G1)_sn``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from rotorvib.models.balancer.stability import generated


@lru_cache(maxsize=1)
def _derivative_functions():
    return tuple(generated(f"taylor_{name}", lambda eq, i=i: (eq.PARAMETERS + eq.STATE,
                                                             eq.taylor_derivatives()[i]),
                           beside=__file__)
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
