"""The balancer's equations of motion in sympy (papers A and B): Lagrange's equations of the
dimensionless rotating-frame energies of digest A, their linearisation at the balanced state and
its characteristic polynomial, and the derivatives of the second-order Taylor expansion.

With lengths in ``R``, time ``tau = w_n t`` and energies in ``M_t R^2 w_n^2``::

    T = (1 - n mu)/2 |G'|^2 + mu/2 sum |B_i'|^2,   V = |C|^2 / 2,
    F = zeta |C'|^2 + mu beta / 2 sum a_i'^2,
    C = (u + i v) e^{i W tau},  G = C + mu/((1 - n mu) rho) e^{i W tau},  B_i = C + e^{i(W tau + a_i)}.

Lagrange's equations ``E(q, q', q'') = 0``, ``q = (u, v, a_1, a_2)``, linearised at the balanced
state ``u = v = 0``, ``a_1 = -a_2 = arccos(-1/(2 rho))``, give ``M dq'' + C dq' + K dq = 0``
(paper B eqs 27-32, paper A section 4).

Deriving them takes sympy seconds: the numeric modules (:mod:`stability`, :mod:`expansion`)
evaluate the expressions through :func:`rotorvib.methods.codegen.cached_lambdify`, and import
this module (and sympy) only when the cache does not hold them yet.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from rotorvib.models.balancer.parameters import N_BALLS

MU, RHO, ZETA, BETA, OMEGA = sp.symbols("mu rho zeta beta Omega", positive=True)
TAU = sp.Symbol("tau", real=True)
LAMBDA = sp.Symbol("lambda")
#: The groups every expression depends on, in the order of the generated functions' arguments.
PARAMETERS = (MU, RHO, ZETA, BETA, OMEGA)
#: The first-order state ``[u, v, a1, a2, u', v', a1', a2']`` of the Taylor expansion.
STATE = sp.symbols("u v a1 a2 up vp a1p a2p", real=True)


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
def characteristic_polynomial() -> sp.Poly:
    """``det(lambda^2 M + lambda C + K)`` as a polynomial in ``lambda`` (degree 8)."""
    M, C, K = pencil_matrices()
    return sp.Poly(sp.expand((LAMBDA**2 * M + LAMBDA * C + K).det(method="berkowitz")), LAMBDA)


@lru_cache(maxsize=1)
def taylor_derivatives():
    """Symbolic ``(M, G1, G2, dM)`` of :mod:`rotorvib.models.balancer.expansion` (its docstring) in
    the parameters and the state :data:`STATE`."""
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
