"""Beyond paper B: how sure are Table 2's numbers for the paper's optimum?

The peak bearing force, its decay time and the balance time of Table 2's last row (beta = 0.2,
m = 6 g, 220 rad/s, eps_bar = 0.012) depend on inputs the paper leaves uncertain or that vary
in practice: the inferred race radius R, the support damping zeta, the initial amplitude r(0),
the balls' initial positions (uniform over the circle), eps_bar, and manufacturing tolerances
on the ball mass and the support stiffness (relative offsets).  Each is uniform on its range
(config, with reasons); Sobol indices say which input drives each quantity, and the 5-95 %
band of each quantity over the ranges says whether a printed value lies within input
uncertainty of its reproduction.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison import Reproduced
from rotorvib.methods.sensitivity import band_statement, problem, sample, study_dataset
from rotorvib.models.balancer.simulate import metric
from rotorvib.papers.b.setup import Setup, dataset_attrs

INPUTS = ("R", "zeta", "r0", "phi1", "phi2", "eps_bar", "mass_tolerance", "k_tolerance")
#: quantity -> units; the two times are capped at t_end, ``balanced`` is 1 for a run that balances
QUANTITIES = {"force_max": "N", "force_decay_time": "s", "balance_time": "s", "balanced": "1"}
_claim = partial(Reproduced.claim, "B")


def run_table2_case(setup: Setup, x, *, beta: float, mass: float, speed: float,
                    kinematics: str) -> dict[str, np.ndarray]:
    """The quantities of :data:`QUANTITIES` at each input point ``x[:, INPUTS]``, all runs in
    one batch.  A run that does not balance (or whose force does not decay) by ``t_end`` has
    no time: its time is capped at ``t_end`` (the quantities are ``min(time, t_end)``, exact
    below the cap) and ``balanced`` says which runs balanced."""
    inputs = []
    for R, zeta, r0, phi1, phi2, eps_bar, dm, dk in np.asarray(x, float):
        s = replace(setup, k=setup.k * (1 + dk), r0=r0)
        inputs.append(s.run_inputs(mass=mass * (1 + dm), eps_bar=eps_bar, beta=beta,
                                   phi0_deg=(phi1, phi2), kinematics=kinematics, speed=speed,
                                   R=R, zeta=zeta))
    metrics = setup.runs(inputs, progress=False)
    t_end = setup.criterion.t_end
    return {"force_max": metric(metrics, "force_max"),
            "force_decay_time": np.where(metric(metrics, "force_decayed") == 1,
                                         metric(metrics, "force_decay_time"), t_end),
            "balance_time": np.where(metric(metrics, "balanced") == 1,
                                     metric(metrics, "balance_time"), t_end),
            "balanced": (metric(metrics, "balanced") == 1).astype(float)}


def uncertainty_dataset(setup: Setup, *, ranges: dict, design, eps_bar: float, phi0_deg,
                        speed: float, kinematics: str, n_base: int, convergence, resamples: int,
                        seed: int) -> xr.Dataset:
    """Sobol indices and bands of Table 2's last-row quantities over ``ranges`` (input ->
    ``[low, high]``, keys :data:`INPUTS`) for ``design = (beta, m)``; the nominal run is
    Table 2's: R, zeta and r(0) of ``setup``, ``eps_bar``, balls at ``phi0_deg``, no
    tolerances."""
    spec = problem({name: tuple(ranges[name]) for name in INPUTS})
    x = sample(spec, n_base, seed)
    beta, mass = design
    run = partial(run_table2_case, setup, beta=beta, mass=mass, speed=speed,
                  kinematics=kinematics)
    nominal = {q: v[0] for q, v in run([[setup.R, setup.zeta, setup.r0, *phi0_deg, eps_bar,
                                         0.0, 0.0]]).items()}
    ds = study_dataset(spec, x, run(x), nominal, QUANTITIES, n_bases=convergence,
                       resamples=resamples, seed=seed)
    attrs = dataset_attrs(
        "uncertainty of Table 2's optimum row",
        f"Beyond the paper: Sobol indices ({n_base} base points) and 5-95 % bands of the peak "
        f"bearing force, its decay time and the balance time at beta = {beta:g}, m = "
        f"{1e3 * mass:g} g, {speed:g} rad/s over the uncertain inputs", "Table 2")
    return ds.assign_attrs(design_beta=beta, design_mass=mass, nominal_eps_bar=eps_bar,
                           disk_mass=setup.M, **attrs)


def uncertainty_rows(ds: xr.Dataset, paper: dict) -> list[Reproduced]:
    """Are Table 2's printed force and decay time of the optimum row within input uncertainty,
    and does that row balance over the whole input ranges?"""
    rows = []
    for quantity, key in (("force_max", "table2_fmax_3"), ("force_decay_time", "table2_decay_3")):
        holds, text = band_statement(ds, quantity, paper[key])
        rows.append(_claim(f"{key}_within_uncertainty", holds, f"printed {text}"))
    q = list(ds.quantity_name.values).index("balanced")
    share = float(ds.y.values[q].mean())
    st, conf, names = ds.ST.values[q, -1], ds.ST_conf.values[q, -1], ds.input_name.values
    drivers = ", ".join(f"{names[i]} ({st[i]:.2f} +/- {conf[i]:.2f})"
                        for i in np.argsort(st)[::-1][:2])
    ratio = ds.attrs["design_mass"] / ds.attrs["disk_mass"]
    half = ds.attrs["nominal_eps_bar"] / 2
    rows.append(_claim("optimum_balances_within_tolerances", share == 1.0,
                       f"{share:.1%} of the {ds.sizes['sample']} input points balance by t_end; "
                       f"whether a run balances depends most on {drivers} (total Sobol "
                       f"indices): the design has m/M = {ratio:.4g} against eps_bar/2 = "
                       f"{half:.4g} (eq. 34: a balanced state needs m/M >= eps_bar/2), a "
                       "bound that a lighter ball or a larger eccentricity crosses"))
    return rows
