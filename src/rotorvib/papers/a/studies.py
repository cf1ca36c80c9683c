"""Paper A's studies as labelled datasets: responses by Runge-Kutta and by the one- and two-term
multiple-scales solutions (Figs 2-6), stability regions by the multiple-scales eigenvalue
problem and by Lyapunov's Jacobian (Fig 7), the error against the initial distance, and the
classical small-mu slow flow (beyond the paper)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.methods import routh
from rotorvib.methods.multiple_scales import MultipleScales
from rotorvib.models.balancer import engine, stability
from rotorvib.models.balancer.expansion import balanced_state, taylor_at
from rotorvib.models.balancer.parameters import Dimensionless, SpeedProfile, rotating_parameters
from rotorvib.models.balancer.simulate import BalanceCriterion, run

REFERENCE = ("Paper A: Dynamics and stability of a rotor equipped with an automatic ball balancer "
             "by the multiple scales method (Persian; data/papers.yaml); model and parameters "
             "reconstructed in digest A")
METHODS = ("runge_kutta", "one_term", "two_term")
_STATE = (("u", "x of the geometric centre in the rotating frame / R", "1"),
          ("v", "y of the geometric centre in the rotating frame / R", "1"),
          ("alpha1", "angle of ball 1 from the mass-centre direction", "degree"),
          ("alpha2", "angle of ball 2 from the mass-centre direction", "degree"))


def _attrs(title, summary, where):
    return {"title": f"Paper A: {title}", "summary": summary,
            "references": f"{REFERENCE}; {where}",
            "comment": "All parameters chosen (the paper's caption values were lost)."}


def offset_vector(u, v, alpha1_deg, alpha2_deg) -> np.ndarray:
    """The state offset ``(u, v, alpha1, alpha2, 0, 0, 0, 0)`` from the balanced state (angles
    given in degrees, stored in radians; rates zero)."""
    return np.array([u, v, np.radians(alpha1_deg), np.radians(alpha2_deg), 0, 0, 0, 0], float)


def solutions(mu, rho, zeta, beta, omega, x0, tau, rk):
    """Deviation from the balanced state by Runge-Kutta (the engine), one term and two terms,
    shape ``(3, len(tau), 8)``; and the expansion (for its eigenvalues and resonances)."""
    z = balanced_state(rho)
    ms = MultipleScales.at(*taylor_at(mu, rho, zeta, beta, omega, z))
    p = rotating_parameters(Dimensionless(mu, rho, zeta, beta), SpeedProfile(omega, "constant"))
    step = tau[1] - tau[0]
    traj = run(engine.ROTATING, p, z + x0, BalanceCriterion(1e-12, 1e-12, float(tau[-1]), step),
               method=rk["method"], rtol=rk["rtol"], atol=rk["atol"], store=True)
    out = np.stack([traj.y[:len(tau)] - z, ms.one_term(x0, tau), ms.two_term(x0, tau)])
    return out, ms


#: Resonances checked: sums of two exponents (secular in T1) and of three (in T2).
RESONANCE_ORDERS = (2, 3)


def responses_dataset(case: dict, offset: dict, betas, tau_end, tau_step, rk) -> xr.Dataset:
    """Figs 2-6: u, v and the ball angles by the three methods for each beta."""
    tau = np.arange(int(round(tau_end / tau_step)) + 1) * tau_step
    x0 = offset_vector(**offset)
    z = balanced_state(case["rho"])
    data = np.empty((len(betas), 3, len(tau), 4))
    eig = np.empty((len(betas), 8), dtype=complex)
    nearest = np.empty((len(betas), len(RESONANCE_ORDERS)))
    resonance_text = []
    for i, beta in enumerate(betas):
        sol, ms = solutions(case["mu"], case["rho"], case["zeta"], beta, case["omega"], x0, tau, rk)
        data[i] = sol[..., :4] + z[:4]
        eig[i] = ms.eigenvalues
        nearest[i] = [ms.resonance_distance(terms) for terms in RESONANCE_ORDERS]
        near = ms.resonances()
        resonance_text.append(f"beta={beta:g}: " + ("; ".join(
            f"l{r.j}+l{r.k}~l{r.l} ({r.distance:.3f})" for r in near) or "none"))
    data[..., 2:] = np.degrees(data[..., 2:])
    dims = ("beta", "method", "tau")
    variables = {name: (dims, data[..., j], {"long_name": long, "units": units})
                 for j, (name, long, units) in enumerate(_STATE)}
    variables["eigenvalue_real"] = (("beta", "mode"), eig.real,
                                    {"long_name": "real part of the eigenvalues of J", "units": "1"})
    variables["eigenvalue_imag"] = (("beta", "mode"), eig.imag,
                                    {"long_name": "imaginary part of the eigenvalues of J",
                                     "units": "1"})
    variables["resonance_distance"] = (("beta", "order"), nearest, {
        "long_name": "least |sum of 'order' exponents - an exponent| / max|lambda|: the distance "
                     "to the nearest resonance that would make the amplitudes depend on T1 "
                     "(order 2) or T2 (order 3)", "units": "1"})
    variables["balanced_angle"] = ((), np.degrees(z[2]),
                                   {"long_name": "balanced ball angle arccos(-1/(2 rho))",
                                    "units": "degree"})
    return xr.Dataset(
        variables,
        coords={"beta": ("beta", np.asarray(betas, float), {"long_name": "ball damping ratio",
                                                            "units": "1"}),
                "order": ("order", np.array(RESONANCE_ORDERS, dtype=np.int32),
                          {"long_name": "number of exponents summed", "units": "1"}),
                "method_name": ("method", np.array(METHODS, dtype=object),
                                {"long_name": "solution method"}),
                "tau": ("tau", tau, {"long_name": "dimensionless time w_n t", "units": "1"})},
        attrs={**_attrs("responses by multiple scales and Runge-Kutta",
                        f"mu = {case['mu']}, rho = {case['rho']}, zeta = {case['zeta']}, Omega = "
                        f"{case['omega']}; near-resonances (relative distance < 0.05): "
                        + " | ".join(resonance_text), "Figs 2-6")},
    )


def stability_region_dataset(mu, rho, zetas, betas, omegas) -> xr.Dataset:
    """Fig 7: growth rate by the multiple-scales eigenvalue problem and by Lyapunov."""
    Z, B, W = np.meshgrid(np.asarray(zetas, float), np.asarray(betas, float),
                          np.asarray(omegas, float), indexing="ij")
    mms = stability.polynomial_roots(mu, rho, Z, B, W).real.max(axis=-1)
    lyap = stability.max_real_part(mu, rho, Z, B, W)
    by_routh = routh.stable(stability.characteristic_coefficients(mu, rho, Z, B, W))
    dims = ("zeta", "beta", "omega")
    crit = {name: _critical_speed(g < 0, omegas) for name, g in (("mms", mms), ("lyapunov", lyap))}
    return xr.Dataset(
        {"growth_mms": (dims, mms, {"long_name": "largest real part of the eight roots of the "
                                                 "4x4 lambda-matrix (multiple scales)", "units": "1"}),
         "growth_lyapunov": (dims, lyap, {"long_name": "largest real part of the eigenvalues of "
                                                       "the 8x8 Jacobian (Lyapunov)", "units": "1"}),
         "critical_speed_mms": (dims[:2], crit["mms"],
                                {"long_name": "lowest speed of the stable range, multiple scales",
                                 "units": "1"}),
         "critical_speed_lyapunov": (dims[:2], crit["lyapunov"],
                                     {"long_name": "lowest speed of the stable range, Lyapunov",
                                      "units": "1"}),
         "stable_routh": (dims, by_routh.astype(np.int8),
                          {"long_name": "1 where Routh's criterion on the characteristic "
                                        "polynomial finds every root in the left half-plane",
                           "units": "1", "flag_values": np.int8([0, 1]),
                           "flag_meanings": "not_stable stable"})},
        coords={"zeta": ("zeta", np.asarray(zetas, float), {"long_name": "support damping ratio",
                                                            "units": "1"}),
                "beta": ("beta", np.asarray(betas, float), {"long_name": "ball damping ratio",
                                                            "units": "1"}),
                "omega": ("omega", np.asarray(omegas, float), {"long_name": "speed ratio Omega",
                                                               "units": "1"})},
        attrs=_attrs("stable region of the balanced state by two methods",
                     f"mu = {mu}, rho = {rho}", "Fig 7"),
    )


def _critical_speed(stable, omegas):
    """Lowest speed from which the last axis stays stable to the top of the grid (NaN: never)."""
    omegas = np.asarray(omegas, float)
    tail_stable = np.flip(np.logical_and.accumulate(np.flip(stable, -1), axis=-1), -1)
    first = np.argmax(tail_stable, axis=-1)
    return np.where(tail_stable.any(axis=-1), omegas[first], np.nan)


def error_study_dataset(case: dict, offset: dict, deltas, tau_end, tau_step, rk) -> xr.Dataset:
    """Maximum error of the one- and two-term solutions against Runge-Kutta as the initial
    distance shrinks (offset direction scaled to each delta), the two-term one with the
    constants of the eight nonlinear equations and with the linear ones, with fitted log-log
    slopes."""
    direction = offset_vector(**offset)
    direction /= np.linalg.norm(direction)
    tau = np.arange(int(round(tau_end / tau_step)) + 1) * tau_step
    errors = np.empty((len(deltas), 3))
    for i, delta in enumerate(deltas):
        sol, ms = solutions(case["mu"], case["rho"], case["zeta"], case["beta"], case["omega"],
                            delta * direction, tau, rk)
        linear = ms.two_term(delta * direction, tau, constants="linear")
        errors[i] = [np.abs(sol[1] - sol[0]).max(), np.abs(sol[2] - sol[0]).max(),
                     np.abs(linear - sol[0]).max()]
    small = np.argsort(deltas)[:3]
    slopes = [np.polyfit(np.log(np.asarray(deltas)[small]), np.log(errors[small, k]), 1)[0]
              for k in range(3)]
    kinds = (("one_term", "one-term"), ("two_term", "two-term"),
                  ("two_term_linear", "two-term (linear constants)"))
    variables = {}
    for k, (name, text) in enumerate(kinds):
        variables[f"error_{name}"] = ("delta", errors[:, k], {
            "long_name": f"max |{text} - Runge-Kutta| over the state", "units": "1"})
        variables[f"slope_{name}"] = ((), slopes[k], {
            "long_name": f"log-log slope of the {text} error (three smallest deltas)",
            "units": "1"})
    return xr.Dataset(
        variables,
        coords={"delta": ("delta", np.asarray(deltas, float),
                          {"long_name": "initial distance from the balanced state (2-norm)",
                           "units": "1"})},
        attrs=_attrs("error of the multiple-scales solutions against the initial distance",
                     "Beyond the paper: error orders of the one- and two-term solutions, the "
                     "latter with nonlinear and with linear constants", "sections 3, 5"),
    )


def slow_flow_rhs(alpha, mu, rho, zeta, beta, omega):
    """Small-mu slow flow (digest A): ``beta a_i' = mu W^4 Im[H e^{-i a_i} / Delta]`` with
    ``H = 1/rho + sum e^{i a_j}`` and ``Delta = 1 - W^2 + 2 i zeta W``."""
    H = 1 / rho + np.exp(1j * alpha).sum()
    delta = 1 - omega**2 + 2j * zeta * omega
    return mu * omega**4 * np.imag(H * np.exp(-1j * alpha) / delta) / beta


def slow_flow_growth(mu, rho, zeta, beta, omega, h=1e-7) -> float:
    """Largest real part of the slow flow's Jacobian at the balanced angles."""
    a = np.arccos(-1 / (2 * rho))
    base = np.array([a, -a])
    J = np.empty((2, 2))
    for j in range(2):
        step = np.zeros(2)
        step[j] = h
        J[:, j] = (slow_flow_rhs(base + step, mu, rho, zeta, beta, omega)
                   - slow_flow_rhs(base - step, mu, rho, zeta, beta, omega)) / (2 * h)
    return float(np.linalg.eigvals(J).real.max())


def slow_flow_dataset(mu, rho, zeta, betas, omegas) -> xr.Dataset:
    """Stability boundary of the slow flow against the exact (Lyapunov) one over (beta, Omega);
    on each beta the boundary is the root of the growth rate between the grid speeds that
    bracket its sign change (theory: exactly Omega = 1 for the slow flow)."""
    betas, omegas = np.asarray(betas, float), np.asarray(omegas, float)
    slow = np.array([[slow_flow_growth(mu, rho, zeta, b, w) for w in omegas] for b in betas])
    B, W = np.meshgrid(betas, omegas, indexing="ij")
    exact = stability.max_real_part(mu, rho, zeta, B, W)
    onsets = {
        "slow": stability.stability_onsets(
            lambda i, w: slow_flow_growth(mu, rho, zeta, betas[i], w), omegas, slow),
        "exact": stability.stability_onsets(
            lambda i, w: stability.max_real_part(mu, rho, zeta, betas[i], w), omegas, exact)}
    return xr.Dataset(
        {"growth_slow_flow": (("beta", "omega"), slow,
                              {"long_name": "largest real part, small-mu slow flow (slow time)",
                               "units": "1"}),
         "growth_exact": (("beta", "omega"), exact,
                          {"long_name": "largest real part, full linearisation", "units": "1"}),
         "critical_speed_slow_flow": ("beta", onsets["slow"],
                                      {"long_name": "lowest stable speed, slow flow", "units": "1"}),
         "critical_speed_exact": ("beta", onsets["exact"],
                                  {"long_name": "lowest stable speed, full linearisation",
                                   "units": "1"})},
        coords={"beta": ("beta", betas, {"long_name": "ball damping ratio", "units": "1"}),
                "omega": ("omega", omegas, {"long_name": "speed ratio Omega", "units": "1"})},
        attrs=_attrs("small-mu slow flow against the exact stability boundary",
                     f"Beyond the paper: mu = {mu}, rho = {rho}, zeta = {zeta}", "digest A"),
    )
