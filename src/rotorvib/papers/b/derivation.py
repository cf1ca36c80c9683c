"""Paper B's equations re-derived with sympy from its energies (2)-(6), for two balls, and checked
against the printed (7)-(9), (14), (16)-(17), (23)-(24), (33)-(34).

The disk angle enters only through ``Phi(t)``.  Three kinematic conventions are compared:
exactly ``Phi = w(t) t`` (what (2)-(3) write), the printed one (``Phi = w t`` with the
``w'' t`` term of ``Phi''`` dropped, i.e. ``Phi'' = 2 w'``), and the consistent ``Phi' = w``.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from rotorvib.methods.symbolic import Check, compare, compare_matrices, lagrange_equations

PAPER = "B"
N = 2

t = sp.Symbol("t", real=True)
M, m, R, eps, k, c, D, IG = sp.symbols("M m R epsilon k c D I_G", positive=True)
r, theta = sp.Function("r", real=True)(t), sp.Function("theta", real=True)(t)
phis = [sp.Function(f"phi{i + 1}", real=True)(t) for i in range(N)]
w = sp.Function("omega", real=True)(t)
Phi = sp.Function("Phi", real=True)(t)
Q = [r, theta] + phis


def _d(f, n=1):
    return sp.diff(f, t, n)


def _vec(angle):
    return sp.Matrix([sp.cos(angle), sp.sin(angle)])


def positions(disk_angle):
    """Fixed-frame positions of C, G and the balls for a given disk angle (eqs 2-3)."""
    C = r * _vec(theta)
    return C, C + eps * _vec(disk_angle), [C + R * _vec(disk_angle + p) for p in phis]


@lru_cache(maxsize=4)
def equations(disk_angle):
    """Lagrange's equations (1) from T (4), V (5) and F (6), expanded with the trigonometric
    functions of sums expanded (a canonical form in which the comparisons below reach zero; full
    ``simplify`` gave the same PASS/FAIL on every row at about five times the cost)."""
    _, G, balls = positions(disk_angle)
    T = (IG * _d(disk_angle) ** 2 / 2 + M * _d(G).dot(_d(G)) / 2
         + m * sum(_d(b).dot(_d(b)) for b in balls) / 2)
    V = k * r**2 / 2
    F = c * (_d(r) ** 2 + r**2 * _d(theta) ** 2) / 2 + D * sum(_d(p) ** 2 for p in phis) / 2
    forces = [-sp.diff(F, _d(q)) for q in Q]
    return [sp.expand(sp.expand_trig(e)) for e in lagrange_equations(T, V, Q, t, forces)]


def printed_equations(angle=None, spin=None, spin_rate=None):
    """(7), (8) and (9) for each ball, as printed: disk ``angle`` w t, its rate ``spin``
    w + w' t and its acceleration ``spin_rate`` 2 w' (other kinematics may be substituted)."""
    angle = w * t if angle is None else angle
    spin = w + _d(w) * t if spin is None else spin
    spin_rate = 2 * _d(w) if spin_rate is None else spin_rate
    a = [p + angle - theta for p in phis]
    rate = [_d(p) + spin for p in phis]
    psi = angle - theta
    mt = M + N * m
    ar, at = _d(r, 2) - r * _d(theta) ** 2, r * _d(theta, 2) + 2 * _d(r) * _d(theta)
    eq7 = (mt * ar + c * _d(r) + k * r
           - m * R * sum((_d(p, 2) + spin_rate) * sp.sin(ai) + ri**2 * sp.cos(ai)
                         for p, ai, ri in zip(phis, a, rate))
           - M * eps * (spin**2 * sp.cos(psi) + spin_rate * sp.sin(psi)))
    eq8 = (mt * at + c * r * _d(theta)
           + m * R * sum((_d(p, 2) + spin_rate) * sp.cos(ai) - ri**2 * sp.sin(ai)
                         for p, ai, ri in zip(phis, a, rate))
           - M * eps * (spin**2 * sp.sin(psi) - spin_rate * sp.cos(psi)))
    eq9 = [m * R**2 * (_d(p, 2) + spin_rate) + D * _d(p)
           - m * R * (ar * sp.sin(ai) - at * sp.cos(ai)) for p, ai in zip(phis, a)]
    return [eq7, eq8] + eq9


def printed_mass_matrix():
    """Matrix M of (14) as printed (two balls), coefficients of r'', theta'', phi_i''."""
    S = [sp.sin(p + w * t - theta) for p in phis]
    C = [sp.cos(p + w * t - theta) for p in phis]
    mt = M + N * m
    return sp.Matrix([[mt, 0, -m * R * S[0], -m * R * S[1]],
                      [0, mt * r, -m * R * C[0], -m * R * C[1]],
                      [-m * R * S[0], -m * R * r * C[0], m * R**2, 0],
                      [-m * R * S[1], -m * R * r * C[1], 0, m * R**2]])


def _consistent(expr):
    """Disk angle with Phi' = w (so Phi'' = w')."""
    return expr.subs({_d(Phi, 2): _d(w), _d(Phi): w}).doit()


def _drop_wddot(expr):
    return sp.expand(expr.subs(_d(w, 2), 0))


def _constant_speed(expr):
    return sp.expand(expr.subs({_d(w, 2): 0}).subs({_d(w): 0}))


def checks() -> list[Check]:
    """Every symbolic check of paper B: eqs. (2)-(9) from the energies (2)-(6) by Lagrange
    under the paper's kinematics, the equilibrium (16)-(17) and (33)-(34), and the linearised
    matrices against the printed ones."""
    rows = []
    _, G, balls = positions(w * t)
    e_r, e_th = _vec(theta), sp.Matrix([-sp.sin(theta), sp.cos(theta)])
    printed_G = (r + eps * sp.cos(w * t - theta), eps * sp.sin(w * t - theta))
    rows.append(compare(PAPER, "(2)", "radial component of r_G", sp.expand_trig(G.dot(e_r)),
                        sp.expand_trig(printed_G[0])))
    rows.append(compare(PAPER, "(2)", "tangential component of r_G",
                        sp.expand_trig(G.dot(e_th)), sp.expand_trig(printed_G[1])))
    exact = equations(w * t)
    consistent = [_consistent(e) for e in equations(Phi)]
    printed = printed_equations()
    # the printed equations read with the disk angle Phi, keeping their rate terms ...
    printed_phi = printed_equations(Phi)
    # ... and with the consistent rates Phi' = w, Phi'' = w'
    printed_consistent = printed_equations(Phi, w, _d(w))
    names = ["(7)", "(8)"] + [f"(9), ball {i + 1}" for i in range(N)]
    leads = [_d(r, 2), _d(theta, 2)] + [_d(p, 2) for p in phis]
    for name, ex, co, pr, pp, pc, lead in zip(names, exact, consistent, printed, printed_phi,
                                              printed_consistent, leads):
        rows.append(compare(PAPER, name, "as printed vs Lagrange with Phi = w t exactly "
                            "(difference: the dropped w'' t terms)", ex, pr, proportional_to=lead))
        rows.append(compare(PAPER, name, "as printed vs Lagrange with Phi = w t, w'' t dropped "
                            "(the paper's convention Phi'' = 2 w')", _drop_wddot(ex), pr,
                            proportional_to=lead))
        rows.append(compare(PAPER, name, "as printed (rates w + w' t, 2 w') vs Lagrange with the "
                            "consistent Phi' = w", co, pp, proportional_to=lead))
        rows.append(compare(PAPER, name, "printed form with Phi' = w, Phi'' = w' vs Lagrange "
                            "with the consistent kinematics", co, pc, proportional_to=lead))
        rows.append(compare(PAPER, name, "as printed vs consistent kinematics at constant "
                            "speed (w' = 0)", _constant_speed(co), _constant_speed(pp),
                            proportional_to=lead))
    accelerations = [_d(q, 2) for q in Q]
    mass = sp.Matrix([[sp.expand(e).coeff(a) for a in accelerations] for e in printed])
    rows.append(compare_matrices(PAPER, "(14)", "mass matrix M against the coefficients of "
                                 "r'', theta'', phi_i'' in the printed (7)-(9)",
                                 mass, printed_mass_matrix()))
    rows += _equilibrium_checks(printed)
    rows += _linearisation_checks()
    return rows


def _equilibrium_checks(printed):
    """(16)-(17) from the printed equations at r = 0, constant speed; (33)-(34)."""
    psi, W = sp.symbols("psi Omega", real=True)
    p_star = sp.symbols("phi1s phi2s", real=True)
    rest = {**{_d(q, 2): 0 for q in Q}, **{_d(q): 0 for q in Q}, _d(w): 0}
    at_rest = [sp.expand(e.subs(rest).subs(r, 0)) for e in printed[:2]]
    at_rest = [sp.expand_trig(e.subs(theta, w * t - psi).subs(w, W)) for e in at_rest]
    at_rest = [e.subs(dict(zip(phis, p_star))) for e in at_rest]
    radial = sp.simplify(at_rest[0] * sp.cos(psi) + at_rest[1] * sp.sin(psi))
    tangential = sp.simplify(-at_rest[0] * sp.sin(psi) + at_rest[1] * sp.cos(psi))
    eq16 = m / M * sum(sp.cos(p) for p in p_star) + eps / R
    eq17 = sum(sp.sin(p) for p in p_star)
    rows = [compare(PAPER, "(16)", "balanced state r* = 0 of (7)-(8): component along C->G",
                    radial, -W**2 * M * R * eq16),
            compare(PAPER, "(17)", "balanced state r* = 0 of (7)-(8): component across C->G",
                    tangential, -W**2 * m * R * eq17)]
    angle = sp.acos(-eps * M / (2 * m * R))
    at33 = {p_star[0]: angle, p_star[1]: -angle}
    rows.append(Check(PAPER, "(33)", "phi1* = -phi2* = arccos(-eps M/(2 m R)) solves (16)-(17)",
                      sp.simplify(eq16.subs(at33)) == 0 and sp.simplify(eq17.subs(at33)) == 0,
                      sp.sstr(sp.simplify(eq16.subs(at33)))))
    boundary = sp.solve(sp.Eq(eps * M / (2 * m * R), 1), m)
    rows.append(Check(PAPER, "(34)", "arccos argument in [-1, 1] <=> m/M >= eps/(2R) "
                      "(boundary m = eps M/(2R))", boundary == [eps * M / (2 * R)],
                      "0" if boundary == [eps * M / (2 * R)] else sp.sstr(boundary)))
    return rows


def _linearisation_checks():
    """Columns 1-2 of (23)-(24), the only ones legible in the source, against the linearisation
    of the derived equations in (r, psi = w t - theta, phi_i) at constant speed, r* = 0."""
    W = sp.Symbol("Omega", positive=True)
    psi = sp.Function("psi", real=True)(t)
    eqs = [e.subs(theta, W * t - psi).subs(w, W).doit() for e in equations(w * t)]
    eqs = [sp.expand(e.subs(_d(W), 0)) for e in eqs]
    eqs[1] = sp.expand(-eqs[1] / r)          # theta-equation in the printed scale of (8)
    coords = [r, psi] + phis
    sym = sp.symbols("r_s psi_s phi1_s phi2_s", real=True)
    dsym = sp.symbols("rd psid phi1d phi2d", real=True)
    ddsym = sp.symbols("rdd psidd phi1dd phi2dd", real=True)
    repl = {}
    for q, s0, s1, s2 in zip(coords, sym, dsym, ddsym):
        repl[_d(q, 2)] = s2
        repl[_d(q)] = s1
    plain = [sp.expand(e.subs(repl).subs(dict(zip(coords, sym)))) for e in eqs]
    rest = {**{s: 0 for s in dsym + ddsym}}
    Cd = sp.Matrix([[sp.diff(e, v).subs(rest) for v in dsym[:2]] for e in plain])
    Kd = sp.Matrix([[sp.diff(e, v).subs(rest) for v in sym[:2]] for e in plain])
    rstar = sp.Symbol("r_star")
    Si = [sp.sin(sym[2 + i] + sym[1]) for i in range(N)]
    Ci = [sp.cos(sym[2 + i] + sym[1]) for i in range(N)]
    mt = M + N * m
    C_print = sp.Matrix([[c, 2 * mt * W * rstar], [-2 * mt * W, c * rstar],
                         [2 * m * R * W * Ci[0], 0], [2 * m * R * W * Ci[1], 0]])
    K_print = sp.Matrix([[k - mt * W**2, W**2 * (M * eps * sp.sin(sym[1]) + m * R * sum(Si))],
                         [-c * W, W**2 * (M * eps * sp.cos(sym[1]) + m * R * sum(Ci))],
                         [m * R * W**2 * Si[0], m * R * W**2 * rstar * Ci[0]],
                         [m * R * W**2 * Si[1], m * R * W**2 * rstar * Ci[1]]])
    at, balanced = {sym[0]: rstar}, {rstar: 0}
    Cd, Kd = Cd.subs(at), Kd.subs(at)
    return [compare_matrices(PAPER, "(23)", "C*, columns r' and psi' (the legible ones), any r*",
                             Cd, C_print),
            compare_matrices(PAPER, "(23)", "C*, columns r' and psi', balanced state r* = 0",
                             Cd.subs(balanced), C_print.subs(balanced)),
            compare_matrices(PAPER, "(24)", "K*, columns r and psi (the legible ones), any r*",
                             Kd, K_print)]
