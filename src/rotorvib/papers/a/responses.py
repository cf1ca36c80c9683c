"""Paper A's studies that integrate the equations of motion (the compiled engine), as labelled
datasets: responses by Runge-Kutta and by the one- and two-term multiple-scales solutions
(Figs 2-6), and their error against the initial distance (beyond the paper)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.methods.multiple_scales import MultipleScales
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.expansion import balanced_state, taylor_at
from rotorvib.models.balancer.parameters import Dimensionless, SpeedProfile, rotating_parameters
from rotorvib.models.balancer.simulate import run
from rotorvib.papers.a.studies import METHODS, STATE, dataset_attrs, offset_vector


def solutions(mu, rho, zeta, beta, omega, x0, tau, rk):
    """Deviation from the balanced state by Runge-Kutta (the engine), one term and two terms,
    shape ``(3, len(tau), 8)``; and the expansion (for its eigenvalues and resonances)."""

    z = balanced_state(rho)
    ms = MultipleScales.at(*taylor_at(mu, rho, zeta, beta, omega, z))
    p = rotating_parameters(Dimensionless(mu, rho, zeta, beta), SpeedProfile(omega, "constant"))
    step = tau[1] - tau[0]
    traj = run(layout.ROTATING, p, z + x0, BalanceCriterion(1e-12, 1e-12, float(tau[-1]), step),
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
                 for j, (name, long, units) in enumerate(STATE)}
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
        attrs=dataset_attrs("responses by multiple scales and Runge-Kutta",
                            f"mu = {case['mu']}, rho = {case['rho']}, zeta = {case['zeta']}, "
                            f"Omega = {case['omega']}; near-resonances (relative distance < "
                            "0.05): " + " | ".join(resonance_text), "Figs 2-6"),
    )


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
        attrs=dataset_attrs("error of the multiple-scales solutions against the initial "
                            "distance", "Beyond the paper: error orders of the one- and two-term "
                            "solutions, the latter with nonlinear and with linear constants",
                            "sections 3, 5"),
    )
