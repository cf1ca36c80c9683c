"""Symbolic re-derivation of paper C's equations (1)-(20) and comparison with the printed ones.

The printed equations are transcribed below exactly as they appear in the paper; the derived
ones come from the velocities (2), the energies (1), (4) and the generalised forces (7) by
Lagrange's equations (6).  :func:`checks` returns one PASS/FAIL row per printed equation.
"""

from __future__ import annotations

import sympy as sp

from rotorvib.methods.symbolic import Check, compare, compare_matrices, lagrange_equations

PAPER = "C"

t = sp.Symbol("t", real=True)
J, kt, m1, m2, d1, d2, k1, k2, c1, c2, w, Gamma0 = sp.symbols(
    "J k_t m1 m2 d1 d2 k1 k2 c1 c2 omega Gamma0", positive=True)
theta, u, v = (sp.Function(name, real=True)(t) for name in ("theta", "u", "v"))
Gamma = sp.Function("Gamma", real=True)(t)
Q = (theta, u, v)
a = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}"))


def _d(f, n=1):
    return sp.diff(f, t, n)


def velocities():
    """Eq. (2): absolute velocities of one body of each absorber set."""
    i, j, k = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
    v1 = -_d(u) * i + (_d(theta) * k).cross(d1 * j - u * i)
    v2 = _d(v) * j + (_d(theta) * k).cross(d2 * i + v * j)
    return v1, v2


def kinetic_energy():
    """Eq. (1) evaluated with the velocities (2)."""
    v1, v2 = velocities()
    return (sp.Rational(1, 2) * J * _d(theta) ** 2 + sp.Rational(1, 2) * 2 * m1 * v1.dot(v1)
            + sp.Rational(1, 2) * 2 * m2 * v2.dot(v2))


def potential_energy():
    """Eq. (4)."""
    return 4 * (k1 * u**2 / 2) + 4 * (k2 * v**2 / 2) + kt * theta**2 / 2


def generalised_forces():
    """Eq. (7)."""
    return Gamma, -4 * c1 * _d(u), -4 * c2 * _d(v)


def equations_of_motion():
    """Eqs. (8)-(10) derived by Lagrange's equations (6), as ``lhs - rhs`` expressions."""
    return lagrange_equations(kinetic_energy(), potential_energy(), Q, t, generalised_forces())


def linearise(expr):
    """First-order part in the amplitudes of theta, u, v and the torque (eqs 11-13)."""
    eps = sp.Symbol("epsilon")
    scaled = expr.subs({theta: eps * theta, u: eps * u, v: eps * v, Gamma: eps * Gamma}).doit()
    return sp.expand(sp.diff(scaled, eps).subs(eps, 0))


# --- the equations as printed in the paper ------------------------------------------------
def printed_kinetic_energy():
    """Eq. (3) as printed."""
    return (sp.Rational(1, 2) * J * _d(theta) ** 2
            + m1 * ((-u * _d(theta)) ** 2 + (-_d(u) - d1 * _d(theta)) ** 2)
            + m2 * ((-v * _d(theta)) ** 2 + (_d(v) + d2 * _d(theta)) ** 2))


def printed_equations_of_motion():
    """Eqs. (8)-(10) as printed."""
    eq8 = ((J + 2 * m1 * u**2 + 2 * m1 * d1**2 + 2 * m2 * v**2 + 2 * m2 * d2**2) * _d(theta, 2)
           + 2 * m1 * d1 * _d(u, 2) + 4 * m1 * u * _d(u) * _d(theta) + 2 * m2 * d2 * _d(v, 2)
           + 4 * m2 * v * _d(v) * _d(theta) + kt * theta - Gamma)
    eq9 = m1 * _d(u, 2) + m1 * d1 * _d(theta, 2) - m1 * u * _d(theta) ** 2 + 2 * c1 * _d(u) + 2 * k1 * u
    eq10 = m2 * _d(v, 2) + m2 * d2 * _d(theta, 2) - m2 * v * _d(theta) ** 2 + 2 * c2 * _d(v) + 2 * k2 * v
    return eq8, eq9, eq10


def printed_linear_equations():
    """Eqs. (11)-(13) as printed."""
    return ((J + 2 * m1 * d1**2 + 2 * m2 * d2**2) * _d(theta, 2) + 2 * m1 * d1 * _d(u, 2)
            + 2 * m2 * d2 * _d(v, 2) + kt * theta - Gamma,
            m1 * _d(u, 2) + m1 * d1 * _d(theta, 2) + 2 * c1 * _d(u) + 2 * k1 * u,
            m2 * _d(v, 2) + m2 * d2 * _d(theta, 2) + 2 * c2 * _d(v) + 2 * k2 * v)


def printed_matrices():
    """M, C, K of eq. (14) as printed."""
    M11 = J + 2 * m1 * d1**2 + 2 * m2 * d2**2
    M = sp.Matrix([[M11, 2 * m1 * d1, 2 * m2 * d2], [m1 * d1, m1, 0], [m2 * d2, 0, m2]])
    return M, sp.diag(0, 2 * c1, 2 * c2), sp.diag(kt, 2 * k1, 2 * k2)


def printed_A_entries():
    """Entries a_ij of eq. (19) as printed."""
    M11 = J + 2 * m1 * d1**2 + 2 * m2 * d2**2
    return sp.Matrix([[-M11 * w**2 + kt, -2 * m1 * d1 * w**2, -2 * m2 * d2 * w**2],
                      [-m1 * d1 * w**2, -m1 * w**2 + 2 * sp.I * c1 * w + 2 * k1, 0],
                      [-m2 * d2 * w**2, 0, -m2 * w**2 + 2 * sp.I * c2 * w + 2 * k2]])


def printed_determinant():
    """det(A) as printed after eq. (19)."""
    return a[0, 0] * a[1, 1] * a[2, 2] + a[0, 2] * a[1, 1] * a[2, 0] - a[0, 1] * a[1, 0] * a[2, 2]


# --- checks ------------------------------------------------------------------------------
def _matrices_of(equations):
    accelerations = [_d(q, 2) for q in Q]
    rates = [_d(q) for q in Q]
    return tuple(sp.Matrix([[sp.diff(e, x) for x in xs] for e in equations])
                 for xs in (accelerations, rates, list(Q)))


def checks() -> list[Check]:
    """Every printed equation of paper C, checked against the derivation."""
    rows = [compare(PAPER, "(3)", "kinetic energy from the velocities (2) in (1)",
                    kinetic_energy(), printed_kinetic_energy())]
    derived = equations_of_motion()
    printed = printed_equations_of_motion()
    for name, der, pri, lead in zip(("(8)", "(9)", "(10)"), derived, printed,
                                    (_d(theta, 2), _d(u, 2), _d(v, 2))):
        rows.append(compare(PAPER, name, "Lagrange's equation (6) from (1), (2), (4), (7)",
                            der, pri, proportional_to=lead))
    # the printed linear set keeps (9)-(10) halved: scale the derived rows the same way
    scales = [sp.Integer(1)] + [sp.simplify(der.coeff(lead) / pri.coeff(lead))
                                for der, pri, lead in zip(derived[1:], printed[1:],
                                                          (_d(u, 2), _d(v, 2)))]
    linear = [linearise(e) / s for e, s in zip(derived, scales)]
    for name, lin, pri in zip(("(11)", "(12)", "(13)"), linear, printed_linear_equations()):
        rows.append(compare(PAPER, name, "first-order part of (8)-(10) in the amplitudes", lin, pri))
    M, C, K = _matrices_of(linear)
    for label, der, pri in zip("MCK", (M, C, K), printed_matrices()):
        rows.append(compare_matrices(PAPER, "(14)", f"matrix {label} of the linear set", der, pri))
    A = -M * w**2 + sp.I * w * C + K
    rows.append(compare_matrices(PAPER, "(19)", "entries a_ij of A = -M w^2 + i w C + K (18)",
                                 A, printed_A_entries()))
    a_sparse = a.subs({a[1, 2]: 0, a[2, 1]: 0})
    true_det = a_sparse.det()
    rows.append(compare(PAPER, "det(A)", "determinant of A with a23 = a32 = 0 (after 19)",
                        true_det, printed_determinant()))
    theta_cramer = sp.simplify(a_sparse.inv()[0, 0] * Gamma0)
    rows.append(compare(PAPER, "(20)", "Theta = a22 a33 Gamma0 / det(A), true determinant",
                        theta_cramer, a[1, 1] * a[2, 2] * Gamma0 / true_det))
    rows.append(compare(PAPER, "(20)", "Theta = a22 a33 Gamma0 / det(A), printed determinant",
                        theta_cramer, a[1, 1] * a[2, 2] * Gamma0 / printed_determinant()))
    return rows
