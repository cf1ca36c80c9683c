"""Paper A's studies that integrate nothing, as labelled datasets: stability regions by the
multiple-scales eigenvalue problem and by Lyapunov's Jacobian (Fig 7) and the classical small-mu
slow flow (beyond the paper); and what its studies share (reference, state variables, the
offset from the balanced state).  The studies that integrate are in
:mod:`rotorvib.papers.a.responses`: a job that imports only these loads no compiler."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.methods import routh
from rotorvib.models.balancer import stability

REFERENCE = ("Paper A: Dynamics and stability of a rotor equipped with an automatic ball balancer "
             "by the multiple scales method (Persian; data/papers.yaml); model and parameters "
             "reconstructed in digest A")
METHODS = ("runge_kutta", "one_term", "two_term")
STATE = (("u", "x of the geometric centre in the rotating frame / R", "1"),
         ("v", "y of the geometric centre in the rotating frame / R", "1"),
         ("alpha1", "angle of ball 1 from the mass-centre direction", "degree"),
         ("alpha2", "angle of ball 2 from the mass-centre direction", "degree"))


def dataset_attrs(title, summary, where):
    """Global attributes of a paper A dataset; ``where`` names the figures or sections."""
    return {"title": f"Paper A: {title}", "summary": summary,
            "references": f"{REFERENCE}; {where}",
            "comment": "All parameters chosen (the paper's caption values were lost)."}


def offset_vector(u, v, alpha1_deg, alpha2_deg) -> np.ndarray:
    """The state offset ``(u, v, alpha1, alpha2, 0, 0, 0, 0)`` from the balanced state (angles
    given in degrees, stored in radians; rates zero)."""
    return np.array([u, v, np.radians(alpha1_deg), np.radians(alpha2_deg), 0, 0, 0, 0], float)


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
        attrs=dataset_attrs("stable region of the balanced state by two methods",
                     f"mu = {mu}, rho = {rho}", "Fig 7"),
    )


def _critical_speed(stable, omegas):
    """Lowest speed from which the last axis stays stable to the top of the grid (NaN: never)."""
    omegas = np.asarray(omegas, float)
    tail_stable = np.flip(np.logical_and.accumulate(np.flip(stable, -1), axis=-1), -1)
    first = np.argmax(tail_stable, axis=-1)
    return np.where(tail_stable.any(axis=-1), omegas[first], np.nan)


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
        attrs=dataset_attrs("small-mu slow flow against the exact stability boundary",
                     f"Beyond the paper: mu = {mu}, rho = {rho}, zeta = {zeta}", "digest A"),
    )
