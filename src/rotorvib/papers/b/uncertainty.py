"""Beyond paper B: how sure are its headline numbers?

The peak bearing force, its decay time and the balance time of a run of paper B depend on
inputs the paper leaves uncertain or that vary in practice: the inferred race radius R, the
support damping zeta, the initial amplitude r(0), the balls' initial positions (uniform over
the circle), and relative offsets (tolerances) of the eccentricity, the ball mass and the
support stiffness.  Each is uniform on its range (config, with reasons).  For each case (a
design and operating point of the paper: Table 2's optimum row, Fig 7), Sobol indices say which
input drives each quantity, and the 5-95 % band of each quantity over the ranges says whether a
printed value lies within input uncertainty of its reproduction.
"""

from __future__ import annotations

import json
from dataclasses import replace
from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison import Margin, Reproduced, within_band
from rotorvib.methods.sensitivity import band_statement, problem, sample, study_dataset
from rotorvib.models.balancer.simulate import metric
from rotorvib.papers.b.setup import Setup, dataset_attrs

INPUTS = ("R", "zeta", "r0", "phi1", "phi2", "eps_tolerance", "mass_tolerance", "k_tolerance")
#: quantity -> units; the times are capped at t_end, ``balanced`` is 1 for a run that balances
QUANTITIES = {"force_max": "N", "force_decay_time": "s", "balance_time": "s",
              "envelope_time": "s", "balanced": "1"}
_claim = partial(Reproduced.claim, "B")


def case_inputs(case: dict) -> tuple[str, ...]:
    """The uncertain inputs of ``case``: all of :data:`INPUTS`, but the ball positions when
    the case fixes its own (``ics``: a quantity defined as a mean over initial conditions)."""
    return tuple(n for n in INPUTS if not (case.get("ics") and n in ("phi1", "phi2")))


def run_case(setup: Setup, x, case: dict, *, kinematics: str) -> dict[str, np.ndarray]:
    """The quantities of :data:`QUANTITIES` at each input point ``x[:, case_inputs(case)]``
    for ``case`` (``beta``, ``mass``, ``eps_bar``, ``speed`` or None for the configured
    run-up, and ``ics``, a list of ball positions, when the quantities are means over them),
    all runs in one batch.  A run that does not balance (or whose force does not decay) by
    ``t_end`` has no time: its time is capped at ``t_end`` (the quantities are ``min(time,
    t_end)``, exact below the cap) and ``balanced`` says which runs balanced."""
    names = case_inputs(case)
    inputs = []
    for row in np.asarray(x, float):
        v = dict(zip(names, row))
        positions = case.get("ics") or [(v["phi1"], v["phi2"])]
        s = replace(setup, k=setup.k * (1 + v["k_tolerance"]), r0=v["r0"])
        inputs += [s.run_inputs(mass=case["mass"] * (1 + v["mass_tolerance"]),
                                eps_bar=case["eps_bar"] * (1 + v["eps_tolerance"]),
                                beta=case["beta"], phi0_deg=tuple(phi), kinematics=kinematics,
                                speed=case["speed"], R=v["R"], zeta=v["zeta"])
                   for phi in positions]
    metrics = setup.runs(inputs, progress=False)
    metrics = metrics.reshape(len(x), len(inputs) // len(x), -1)
    t_end = setup.criterion.t_end

    def capped(time, flag):
        return np.where(metric(metrics, flag) == 1, metric(metrics, time), t_end).mean(axis=1)

    return {"force_max": metric(metrics, "force_max").mean(axis=1),
            "force_decay_time": capped("force_decay_time", "force_decayed"),
            "balance_time": capped("balance_time", "balanced"),
            "envelope_time": capped("envelope_time", "envelope_balanced"),
            "balanced": (metric(metrics, "balanced") == 1).mean(axis=1)}


def uncertainty_dataset(setup: Setup, *, case: dict, ranges: dict, kinematics: str,
                        n_base: int, convergence, resamples: int, seed: int) -> xr.Dataset:
    """Sobol indices and bands of the quantities of ``case`` (``name``, ``title``, ``beta``,
    ``mass``, ``eps_bar``, ``speed`` or None, ``phi0_deg`` or ``ics``, and ``printed``: the
    paper's values to set against the bands, quantity -> key in the paper values) over ``ranges``
    (input -> ``[low, high]``, keys :func:`case_inputs`); the nominal run is the case as the
    paper runs it: R, zeta and r(0) of ``setup``, its ball positions, no tolerances."""
    names = case_inputs(case)
    spec = problem({name: tuple(ranges[name]) for name in names})
    x = sample(spec, n_base, seed)
    run = partial(run_case, setup, case=case, kinematics=kinematics)
    at = {"R": setup.R, "zeta": setup.zeta, "r0": setup.r0,
          **dict(zip(("phi1", "phi2"), case.get("phi0_deg", ())))}
    nominal = {q: v[0] for q, v in run([[at.get(n, 0.0) for n in names]]).items()}
    ds = study_dataset(spec, x, run(x), nominal, QUANTITIES, n_bases=convergence,
                       resamples=resamples, seed=seed)
    speed = "the run-up" if case["speed"] is None else f"{case['speed']:g} rad/s"
    over = (f" (each a mean over {len(case['ics'])} initial conditions)" if case.get("ics")
            else "")
    attrs = dataset_attrs(
        f"uncertainty of {case['title']}",
        f"Beyond the paper: Sobol indices ({n_base} base points) and 5-95 % bands of the peak "
        f"bearing force, its decay time and the balance times{over} at beta = "
        f"{case['beta']:g}, m = {1e3 * case['mass']:g} g, eps_bar = {case['eps_bar']:g}, "
        f"{speed} over the uncertain inputs", case["title"])
    return ds.assign_attrs(case=case["name"], case_title=case["title"], design_beta=case["beta"],
                           design_mass=case["mass"], nominal_eps_bar=case["eps_bar"],
                           disk_mass=setup.M, printed=json.dumps(case["printed"]), **attrs)


def within_band_rows(ds: xr.Dataset, paper: dict, printed: dict) -> list[Reproduced]:
    """One row per ``quantity -> paper key`` of ``printed``: is the paper's value within the
    band of its reproduction?"""
    rows = []
    for quantity, key in printed.items():
        margin, text = band_statement(ds, quantity, paper[key])
        rows.append(_claim(f"{key}_within_uncertainty", within_band(ds, quantity, margin),
                           f"printed {text}"))
    return rows


def balances_row(ds: xr.Dataset) -> Reproduced:
    """Does the case balance over the whole input ranges?  States the share that does, the
    inputs that decide it, and the case against the existence bound m/M >= eps_bar/2 (eq. 34)."""
    q = list(ds.quantity_name.values).index("balanced")
    share = float(ds.y.values[q].mean())
    st, conf, names = ds.ST.values[q, -1], ds.ST_conf.values[q, -1], ds.input_name.values
    drivers = ("no input (it does not vary)" if np.all(np.isnan(st)) else
               ", ".join(f"{names[i]} ({st[i]:.2f} +/- {conf[i]:.2f})"
                         for i in np.argsort(-np.nan_to_num(st, nan=-1.0))[:2]))
    ratio = ds.attrs["design_mass"] / ds.attrs["disk_mass"]
    half = ds.attrs["nominal_eps_bar"] / 2
    return _claim("optimum_balances_within_tolerances",
                  Margin(share - 1.0, 0.0, "share of the input points",
                         "count over the sample (exact); a sample can find an input that does "
                         "not balance, never prove that all do"),
                  f"{share:.1%} of the {ds.sizes['sample']} input points balance by t_end; "
                  f"whether a run balances depends most on {drivers} (total Sobol indices): "
                  f"the design has m/M = {ratio:.4g} against eps_bar/2 = {half:.4g} (eq. 34: a "
                  "balanced state needs m/M >= eps_bar/2), a bound that a lighter ball or a "
                  "larger eccentricity crosses")


def uncertainty_rows(studies: dict[str, xr.Dataset], paper: dict) -> list[Reproduced]:
    """Every printed value of every case against its band; whether Table 2's optimum balances
    over the whole ranges."""
    rows = [row for ds in studies.values()
            for row in within_band_rows(ds, paper, json.loads(ds.attrs["printed"]))]
    return rows + [balances_row(studies["table2"])]
