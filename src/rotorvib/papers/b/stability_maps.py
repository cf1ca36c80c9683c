"""Paper B's Figs 2-3: linearised stability of the balanced state r* = 0 at constant speed
(eqs 27-32) over a (beta, omega_bar) or (m_bar, omega_bar) grid."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.io.coords import axis_coord
from rotorvib.models.balancer import stability
from rotorvib.models.balancer.parameters import paper_b_groups
from rotorvib.papers.b.attributes import dataset_attrs


def _where_balanced(m_bar, eps_bar, zeta, beta, omega_bar, n: int):
    """Paper A's groups (``paper_b_groups``) at the points where a balanced state exists
    (rho = m_bar/eps_bar >= 1/2, eq. 34): the broadcast shape, the mask of those points, their
    groups and ``s = sqrt(1 + n m_bar)``, by which eigenvalues on the total-mass scale exceed
    paper B's."""
    mu, rho, z, b, om = paper_b_groups(m_bar, eps_bar, zeta, beta, omega_bar, n)
    exists = rho >= 0.5
    s = np.sqrt(1 + n * np.broadcast_to(m_bar, mu.shape)[exists])
    return mu.shape, exists, tuple(g[exists] for g in (mu, rho, z, b, om)), s


def balanced_eigenvalues(m_bar, eps_bar, zeta, beta, omega_bar, n: int = 2) -> np.ndarray:
    """The eight eigenvalues of the balanced state r* = 0 (eqs 27-32) in units of paper B's
    omega_n, shape ``broadcast shape + (8,)``; NaN where no balanced state exists
    (rho = m_bar/eps_bar < 1/2, eq. 34)."""
    shape, exists, groups, s = _where_balanced(m_bar, eps_bar, zeta, beta, omega_bar, n)
    eig = np.full(shape + (8,), np.nan, dtype=complex)
    if exists.any():
        eig[exists] = stability.eigenvalues(*groups) / s[:, None]
    return eig


def balanced_modes(m_bar, eps_bar, zeta, beta, omega_bar, n: int = 2):
    """The balanced state's eigenvalues (as :func:`balanced_eigenvalues`) and each mode's share
    of the whirl: ``|(u, v)| / |(u, v, a1, a2)|`` of its eigenvector's positions (the rotor's
    centre against the balls' angles, in units of R and radians), 1 for a mode of the rotor
    alone and near 0 for a mode of the balls alone; NaN where no balanced state exists."""
    shape, exists, groups, s = _where_balanced(m_bar, eps_bar, zeta, beta, omega_bar, n)
    eig = np.full(shape + (8,), np.nan, dtype=complex)
    share = np.full(shape + (8,), np.nan)
    if exists.any():
        lam, vectors = np.linalg.eig(stability.jacobian(*groups))
        eig[exists] = lam / s[:, None]
        positions = np.linalg.norm(vectors[..., :4, :], axis=-2)
        share[exists] = np.linalg.norm(vectors[..., :2, :], axis=-2) / positions
    return eig, share


def growth_rate(m_bar, eps_bar, zeta, beta, omega_bar, n: int = 2) -> np.ndarray:
    """Largest real part of the eigenvalues of the balanced state (:func:`balanced_eigenvalues`)
    in units of paper B's omega_n; NaN where no balanced state exists.  Vectorised over
    broadcast arguments."""
    return balanced_eigenvalues(m_bar, eps_bar, zeta, beta, omega_bar, n).real.max(axis=-1)


def stability_dataset(*, m_bar, eps_bar, zeta, beta, omega_bar, n=2, where,
                      marginal: float) -> xr.Dataset:
    """Growth rate of the balanced state (largest real part of the eigenvalues, in units of
    paper B's omega_n) over a 2-D grid; ``m_bar`` or ``beta`` is the grid's first axis.  A point
    whose growth rate lies within ``marginal`` of zero is marginal, neither stable nor unstable;
    the onset of stability of every row is located exactly (:func:`stability_onsets`)."""
    first = "m_bar" if np.ndim(m_bar) else "beta"
    axis = np.asarray(m_bar if first == "m_bar" else beta, dtype=float)
    omega_bar = np.asarray(omega_bar, dtype=float)
    A, W = np.meshgrid(axis, omega_bar, indexing="ij")
    mb, bt = (A, np.full(A.shape, beta)) if first == "m_bar" else (np.full(A.shape, m_bar), A)
    growth = growth_rate(mb, eps_bar, zeta, bt, W, n)
    state = np.select([np.isnan(growth), np.abs(growth) <= marginal, growth < 0], [2, 3, 1],
                      0).astype(np.int8)
    onsets = stability.stability_onsets(
        lambda i, w: growth_rate(mb[i, 0], eps_bar, zeta, bt[i, 0], w, n), omega_bar,
        np.where(np.abs(growth) <= marginal, 0.0, growth))
    names = {"m_bar": ("ball/disk mass ratio m/M", "1"), "beta": ("ball damping ratio beta", "1")}
    return xr.Dataset(
        {"growth_rate": ((first, "omega_bar"), growth,
                         {"long_name": "largest real part of the eigenvalues / omega_n "
                                       "(NaN: no balanced state)", "units": "1"}),
         "state": ((first, "omega_bar"), state,
                   {"long_name": "balanced state", "units": "1",
                    "flag_values": np.int8([0, 1, 2, 3]),
                    "flag_meanings": "unstable stable no_balanced_state marginal"}),
         "marginal_growth": ((), float(marginal),
                             {"long_name": "|growth rate| at or below which a point is marginal",
                              "units": "1"}),
         "stability_onset": (first, onsets,
                             {"long_name": "speed ratio omega/omega_n at which the balanced "
                                           "state turns stable, located exactly (NaN: not on "
                                           "the grid)", "units": "1"}),
         "critical_speed": (first, 1 / np.sqrt(1 + n * mb[:, 0]),
                            {"long_name": "undamped critical speed of disk and balls, "
                                          "sqrt(M/(M + n m)) (omega_bar)", "units": "1"}),
         "fixed_eps_bar": ((), float(eps_bar), {"long_name": "eccentricity ratio eps/R",
                                                "units": "1"}),
         "fixed_zeta": ((), float(zeta), {"long_name": "support damping ratio", "units": "1"}),
         **({"fixed_beta": ((), float(beta), {"long_name": "ball damping ratio", "units": "1"})}
            if first == "m_bar" else
            {"fixed_m_bar": ((), float(m_bar), {"long_name": "ball/disk mass ratio",
                                               "units": "1"})})},
        coords={**axis_coord(first, axis, *names[first]),
                **axis_coord("omega_bar", omega_bar, "speed ratio omega/omega_n", "1")},
        attrs=dataset_attrs(f"stability of the balanced state ({where})",
                            "Linearised stability of the balanced state r* = 0 at constant speed "
                            "(eqs 27-32) on a grid", where),
    )


