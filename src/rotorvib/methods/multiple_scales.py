"""Multiple-scales solutions around an equilibrium of an autonomous system ``z' = f(z)``
(paper A, section 3, in the reading of digest A).

Write ``z = z* + x`` with ``f(z* + x) = J x + 1/2 H(x, x) + O(|x|^3)`` and expand
``x = eps x1 + eps^2 x2``:

* order eps (one-term solution, eqs 23-33): ``x1 = sum_j A_j phi_j exp(lambda_j tau)`` over the
  eigenpairs of ``J`` (for the balancer, the eight roots of the 4x4 lambda-matrix); the
  constants follow linearly from the initial state;
* order eps^2 (two-term solution, eqs 34-39): ``x2 = sum_jk A_j A_k c_jk exp((lambda_j +
  lambda_k) tau)`` with ``c_jk = ((lambda_j + lambda_k) I - J)^-1 1/2 H(phi_j, phi_k)``; the
  constants solve the eight nonlinear equations ``x(0) = sum_j A_j phi_j + sum_jk A_j A_k c_jk``;
* the same order with linear constants (beyond the paper): keep the one-term constants
  ``A = Phi^-1 x(0)`` in the second-order term and add a homogeneous part ``B`` that cancels it
  at ``tau = 0``, ``Phi B = -sum_jk A_j A_k c_jk``.  The nonlinear constants are ``A + B +
  O(|x0|^3)``, so both solutions err by ``O(|x0|^3)``.

The solver is generic in the vector field: it needs only ``J`` and the symmetric quadratic
tensor ``T`` with ``H(u, v)_i = sum_jk T_ijk u_j v_k``.  A near-resonance
``lambda_j + lambda_k ~ lambda_l`` makes ``c_jk`` large and is reported.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations_with_replacement

import numpy as np

from rotorvib.checks import finite_array, number


class ConstantsDiverged(ArithmeticError):
    """The two-term constants' nonlinear equations (eq. 39) have no solution near the one-term
    constants: the initial state is too far from the equilibrium for the expansion."""


@dataclass(frozen=True)
class Resonance:
    """``lambda_j + lambda_k`` within ``distance`` of ``lambda_l`` (relative to ``|lambda|``)."""

    j: int
    k: int
    l: int
    distance: float


@dataclass(frozen=True)
class MultipleScales:
    """Eigen-decomposition and second-order coefficients of a system at an equilibrium."""

    J: np.ndarray
    T: np.ndarray
    eigenvalues: np.ndarray
    modes: np.ndarray            # columns phi_j
    second_order: np.ndarray     # c[j, k, :]

    @classmethod
    def at(cls, J, T) -> "MultipleScales":
        """Decomposition at an equilibrium with Jacobian ``J`` (n x n) and quadratic tensor
        ``T`` (n x n x n); ``ValueError`` if either is not finite or not of these shapes."""
        n = np.shape(J)[0] if np.ndim(J) else 0
        J = finite_array("J", J, shape=(n, n))
        T = finite_array("T", T, shape=(n, n, n))
        lam, phi = np.linalg.eig(J)
        c = np.empty((n, n, n), dtype=complex)
        for j in range(n):
            for k in range(j, n):
                forcing = 0.5 * np.einsum("ijk,j,k->i", T, phi[:, j], phi[:, k])
                try:
                    c[j, k] = c[k, j] = np.linalg.solve((lam[j] + lam[k]) * np.eye(n) - J,
                                                        forcing)
                except np.linalg.LinAlgError:       # exact resonance: no bounded x2 term
                    c[j, k] = c[k, j] = np.nan
        return cls(J=J, T=T, eigenvalues=lam, modes=phi, second_order=c)

    def resonances(self, tolerance: float = 0.05) -> list[Resonance]:
        """Triads with ``|lambda_j + lambda_k - lambda_l| < tolerance * max|lambda|``
        (``tolerance`` finite and >= 0)."""
        tolerance = number("tolerance", tolerance, inclusive=True)
        lam = self.eigenvalues
        scale = np.max(np.abs(lam))
        found = []
        for j in range(len(lam)):
            for k in range(j, len(lam)):
                gaps = np.abs(lam[j] + lam[k] - lam) / scale
                l = int(np.argmin(gaps))
                if gaps[l] < tolerance:
                    found.append(Resonance(j, k, l, float(gaps[l])))
        return found

    def resonance_distance(self, terms: int) -> float:
        """The least ``|lambda_j + ... + lambda_m - lambda_l| / max|lambda|`` over every sum of
        ``terms`` exponents (repeats allowed): the distance to the nearest resonance of order
        ``terms``. The amplitudes are free of ``T1`` where no two exponents resonate (the
        solvability condition at order eps^2) and of ``T2`` where no three do (order eps^3)."""
        lam = self.eigenvalues
        sums = np.array([sum(c) for c in combinations_with_replacement(lam, int(terms))])
        return float(np.min(np.abs(sums[:, None] - lam[None, :])) / np.max(np.abs(lam)))

    def initial_state(self, x0) -> np.ndarray:
        """``x0`` checked: finite, one entry per state variable."""
        return finite_array("x0", x0, shape=(len(self.eigenvalues),))

    def one_term_constants(self, x0) -> np.ndarray:
        """``A`` with ``sum_j A_j phi_j = x0`` (eq. 33)."""
        return np.linalg.solve(self.modes, self.initial_state(x0).astype(complex))

    def two_term_constants(self, x0) -> np.ndarray:
        """``A`` solving the eight nonlinear initial-condition equations (eq. 39), by Newton's
        method from the one-term constants; :class:`ConstantsDiverged` if it does not
        converge."""
        from scipy.optimize import root  # here: the one-term solution needs no scipy.optimize

        x0 = self.initial_state(x0)
        n = len(x0)
        if np.isnan(self.second_order).any():
            triads = ", ".join(f"l{r.j}+l{r.k}=l{r.l}" for r in self.resonances(1e-9))
            raise ArithmeticError(f"exact internal resonance ({triads}): the two-term "
                                  "expansion needs secular terms")

        def residual(a_ri):
            a = a_ri[:n] + 1j * a_ri[n:]
            r = self.modes @ a + np.einsum("j,k,jki->i", a, a, self.second_order) - x0
            return np.concatenate((r.real, r.imag))

        start = self.one_term_constants(x0)
        sol = root(residual, np.concatenate((start.real, start.imag)), method="hybr",
                   options={"xtol": 1e-13})
        misfit = np.linalg.norm(residual(sol.x))
        if not misfit <= 1e-9 * max(np.linalg.norm(x0), 1e-300):
            raise ConstantsDiverged(f"two-term initial conditions did not converge (residual "
                                    f"{misfit:.2e}): {' '.join(sol.message.split())}")
        return sol.x[:n] + 1j * sol.x[n:]

    def linear_two_term_constants(self, x0) -> tuple[np.ndarray, np.ndarray]:
        """``(A + B, A)``: the first-order term's constants (one-term constants plus the
        homogeneous part with ``Phi B = -sum_jk A_j A_k c_jk``) and the second-order term's
        (the one-term constants), both from linear solves only."""
        a = self.one_term_constants(x0)
        if np.isnan(self.second_order).any():
            raise ArithmeticError("exact internal resonance: the two-term expansion needs "
                                  "secular terms")
        b = np.linalg.solve(self.modes, -np.einsum("j,k,jki->i", a, a, self.second_order))
        return a + b, a

    def one_term(self, x0, tau) -> np.ndarray:
        """``x(tau)`` of the one-term solution, shape ``(len(tau), n)`` (real)."""
        a = self.one_term_constants(x0)
        e = np.exp(np.outer(finite_array("tau", tau, shape=(None,)), self.eigenvalues))
        return np.real((e * a) @ self.modes.T)

    def two_term(self, x0, tau, constants: str = "nonlinear") -> np.ndarray:
        """``x(tau)`` of the two-term solution, shape ``(len(tau), n)`` (real), with the
        constants of the eight nonlinear equations (``constants="nonlinear"``, eq. 39) or the
        linear ones (``"linear"``, :meth:`linear_two_term_constants`)."""
        if constants == "nonlinear":
            first_a = second_a = self.two_term_constants(x0)
        elif constants == "linear":
            first_a, second_a = self.linear_two_term_constants(x0)
        else:
            raise ValueError(f"constants must be 'nonlinear' or 'linear', not {constants!r}")
        e = np.exp(np.outer(finite_array("tau", tau, shape=(None,)), self.eigenvalues))
        first = (e * first_a) @ self.modes.T
        second = np.einsum("tj,tk,j,k,jki->ti", e, e, second_a, second_a, self.second_order)
        return np.real(first + second)
