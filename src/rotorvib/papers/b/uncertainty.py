"""Beyond paper B: how sure are its headline numbers?

The peak bearing force, its decay time and the balance times of a run of paper B depend on
inputs the paper does not state or that vary in practice, each uniform on a range with a
source or a reason:

- the race radius R, not printed: every R whose reproduced Table 2 peak forces all match the
  printed ones (within the comparison's MATCH tolerance) -- the band the calibration allows
  (:func:`calibrated_band`); where no R does (another machine or initial condition than the
  paper's), the calibration's whole grid, and the dataset and its rows say so;
- the support damping ratio zeta, which the paper states for Figs 2-3 and 8-14 but not for
  Fig 7 or Tables 1-2: a stated prior range (config), never fitted to the printed times (which
  the bands are set against);
- the initial amplitude r(0), and relative offsets (tolerances) of the eccentricity, the ball
  mass and the support stiffness (config, with reasons).  The eccentricity stays at or below
  the design's eps_max, which eq. (41) sizes the balls for; an eccentricity beyond it is the
  separate overload question (:func:`balances_in_closed_form`).

What the paper states for every run -- the balls' initial positions (eq. 39) -- is not varied:
a distribution over random ball positions is another quantity (the basin study).  For each case (Table 2's optimum row, Fig 7, Table 1's mean over the ICs),
Sobol indices say which input drives each quantity, and its 5-95 % band says whether a printed
value lies within input uncertainty of its reproduction.  A run that never balances has no
time: the bands of times are over the runs that balance, and ``balanced`` gives their share.
"""

from __future__ import annotations

import json
import re
from dataclasses import replace
from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin, Reproduced, within_band
from rotorvib.comparison.verdicts import MATCH_TOL
from rotorvib.io.coords import pick
from rotorvib.methods.bands import band_margin, band_statement
from rotorvib.methods.sensitivity import problem, sample, study_dataset
from rotorvib.models.balancer import certificates
from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.parameters import total_mass_groups
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import LazyInputs, Setup

INPUTS = ("R", "zeta", "r0", "eps_tolerance", "mass_tolerance", "k_tolerance")
#: quantity -> units; a time is NaN for a run without one, ``balanced`` is 1 for a run that
#: balances
QUANTITIES = {"force_max": "N", "force_decay_time": "s", "balance_time": "s",
              "envelope_time": "s", "balanced": "1"}
_claim = partial(Reproduced.claim, "B")


#: How the range of R was found (:func:`calibrated_band`): the band Table 2's forces allow.
CALIBRATED = "the band Table 2's forces allow"
#: The paper values the calibration of R is fitted to: Table 2's printed peak force of each row.
CALIBRATION_KEY = "table2_fmax_{row}"


def calibrated_band(forces: xr.Dataset, printed, *, kinematics: str,
                    tolerance: float = MATCH_TOL) -> tuple[float, float, str]:
    """The race radii R whose reproduced peak forces of Table 2's rows (``forces``, the
    calibration over R) all lie within ``tolerance`` (relative) of the ``printed`` ones: where
    the largest relative error, linear between the grid's radii, is at most ``tolerance``;
    ``(low, high, how)``, ``how`` :data:`CALIBRATED`.  Where no radius of the grid qualifies
    (a configuration whose machine or initial conditions are not the paper's), the grid's
    whole range, ``how`` saying so; ``ValueError`` if the band reaches the grid's end (a grid
    too narrow)."""
    at = pick(forces, kinematics=kinematics)
    R = at.R.values
    printed = np.asarray(printed, float)
    worst = np.max(np.abs(at.force_max.values - printed[:, None]) / printed[:, None], axis=0)
    inside = worst <= tolerance
    if not inside.any():
        return (float(R[0]), float(R[-1]),
                f"no R of the calibration reproduces Table 2's peak forces within "
                f"{tolerance:.0%} (closest {worst.min():.1%} off): the calibration grid's whole "
                "range")
    first, last = np.flatnonzero(inside)[[0, -1]]
    if first == 0 or last == R.size - 1:
        raise ValueError("the calibrated band of R reaches the end of paper_b.calibration.R: "
                         "widen the grid")

    def crossing(i, j):             # the radius between R[i] and R[j] where worst = tolerance
        return float(np.interp(tolerance, [worst[i], worst[j]], [R[i], R[j]])
                     if worst[i] < worst[j] else
                     np.interp(tolerance, [worst[j], worst[i]], [R[j], R[i]]))

    return crossing(first, first - 1), crossing(last, last + 1), CALIBRATED


def residual_whirl(*, M: float, n: int, mass, eps_bar, R, k, zeta: float, speed: float):
    """Steady whirl radius (m) left when the balls cannot cancel the unbalance: eq. (33) has no
    balanced state when n m R < M eps, and the balls gather at one angle, nearly opposite the
    mass centre, the centre whirling with the unbalance they leave (the rest point of
    :func:`rotorvib.models.balancer.certificates.residual_whirl`, support damping ``c = 2 zeta
    sqrt(M k)``); 0 where the balls suffice.  Arguments broadcast."""
    mass, eps_bar, R, k = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                               (mass, eps_bar, R, k)))
    mu, rho, zeta_t, _ = total_mass_groups(M, mass, R, eps_bar * R, k, 2 * zeta * np.sqrt(M * k),
                                           0.0, n)
    beyond = n * rho < 1
    W = speed / np.sqrt(k / (M + n * mass))
    w = certificates.residual_whirl(mu[beyond], rho[beyond], zeta_t[beyond], W[beyond], n)
    r = np.zeros(mass.shape)
    r[beyond] = R[beyond] * np.hypot(w[:, 0], w[:, 1])
    return r


def balances_in_closed_form(ds: xr.Dataset, x, *, mass_tolerance=None, eps_offsets=None):
    """Whether each input point of an uncertainty case balances by the criterion, predicted in
    closed form: its :func:`residual_whirl` below ``r_threshold``.  ``x`` holds the points'
    inputs (in the dataset's order); given ``mass_tolerance`` and ``eps_offsets`` (each
    ``(lo, hi)``), a fine uniform grid of those offsets at the nominal R and k takes the points'
    place (the overload question)."""
    a = ds.attrs
    if eps_offsets is not None:
        dm, de = np.meshgrid(np.linspace(*mass_tolerance, 401), np.linspace(*eps_offsets, 401))
        R, k = a["nominal_R"], a["support_k"]
    else:
        v = dict(zip([str(n) for n in ds.input_name.values], np.asarray(x, float).T))
        dm, de, R = v["mass_tolerance"], v["eps_tolerance"], v["R"]
        k = a["support_k"] * (1 + v["k_tolerance"])
    zeta = a["support_zeta"] if eps_offsets is not None else v["zeta"]
    r = residual_whirl(M=a["disk_mass"], n=a["balls"], mass=a["design_mass"] * (1 + dm),
                       eps_bar=a["nominal_eps_bar"] * (1 + de), R=R, k=k,
                       zeta=zeta, speed=a["speed"])
    return r < a["r_threshold"]


def run_case(setup: Setup, x, case: dict, *, kinematics: str,
             runs=None) -> dict[str, np.ndarray]:
    """The quantities of :data:`QUANTITIES` at each input point ``x[:, INPUTS]`` for ``case``
    (``beta``, ``mass``, ``eps_bar``, ``speed`` or None for the configured run-up, and its ball
    positions: ``phi0_deg``, or ``ics``, a list of them, when the quantities are means over
    them), all runs in one batch of ``runs(inputs) -> metrics`` (``setup.runs`` unless given:
    a shard of them or their gathering, :mod:`rotorvib.pipeline.shards`).  A run that does not
    balance (or whose force does not decay) by ``t_end`` has no time: NaN, and a mean over ICs
    with such a run is NaN too."""
    positions = case.get("ics") or [case["phi0_deg"]]
    rows = np.asarray(x, float)

    def build(i):
        """Run ``i``: input point ``i // len(positions)`` at the ball positions
        ``i % len(positions)``."""
        row, phi = divmod(i, len(positions))
        v = dict(zip(INPUTS, rows[row]))
        s = replace(setup, k=setup.k * (1 + v["k_tolerance"]), r0=v["r0"], zeta=v["zeta"])
        return s.run_inputs(mass=case["mass"] * (1 + v["mass_tolerance"]),
                            eps_bar=case["eps_bar"] * (1 + v["eps_tolerance"]),
                            beta=case["beta"], phi0_deg=tuple(positions[phi]),
                            kinematics=kinematics, speed=case["speed"], R=v["R"])

    metrics = (runs or (lambda batch: setup.runs(batch, progress=False)))(
        LazyInputs(len(rows) * len(positions), build))
    metrics = metrics.reshape(len(x), len(positions), -1)

    def time_of(time, flag):
        return np.where(metric(metrics, flag) == 1, metric(metrics, time), np.nan).mean(axis=1)

    return {"force_max": metric(metrics, "force_max").mean(axis=1),
            "force_decay_time": time_of("force_decay_time", "force_decayed"),
            "balance_time": time_of("balance_time", "balanced"),
            "envelope_time": time_of("envelope_time", "envelope_balanced"),
            "balanced": (metric(metrics, "balanced") == 1).mean(axis=1)}


def prior_name(name: str, low: float, high: float) -> str:
    """A prior of one input as the rows name it: ``zeta = 0.01`` (fixed), ``zeta in [0.008,
    0.012]`` (uniform)."""
    return f"{name} = {low:g}" if low == high else f"{name} in [{low:g}, {high:g}]"


def fixed_priors(alternatives: dict) -> list[tuple[str, float]]:
    """The alternative priors that fix an input, ``(input, value)``, in the configuration's
    order; the narrower ranges need no run of their own (:func:`prior_samples`)."""
    return [(name, float(low)) for name, ranges in alternatives.items()
            for low, high in ranges if low == high]


def fixed_prior_runs(run, x, n_inputs: int, fixed: list[tuple[str, float]]) -> dict:
    """``run`` at Saltelli's first base points (rows ``0, D + 2, ...`` of ``x``: independent
    and uniform over the ranges) with one input fixed, for each ``(input, value)`` of
    ``fixed``, in one batch: quantity -> array (fixed prior, point)."""
    base = np.asarray(x, float)[::n_inputs + 2]
    points = np.concatenate([np.where(np.arange(n_inputs) == INPUTS.index(name), value, base)
                             for name, value in fixed])
    return {q: v.reshape(len(fixed), len(base)) for q, v in run(points).items()}


def with_fixed_priors(ds: xr.Dataset, fixed: list[tuple[str, float]], y: dict) -> xr.Dataset:
    """The study ``ds`` with the outputs ``y`` of :func:`fixed_prior_runs` for the priors
    ``fixed`` (``fixed_y``, by ``fixed_prior``: its name, :func:`prior_name`)."""
    ds = ds.assign(fixed_y=(("fixed_prior", "quantity", "base_point"),
                            np.stack([np.asarray(y[str(q)], float)
                                      for q in ds.quantity_name.values], axis=1),
                            {"long_name": "model output at Saltelli's base points with one input "
                                          "fixed (units by quantity)", "units": "1"}))
    return ds.assign_coords(fixed_prior=("fixed_prior", np.array(
        [prior_name(n, v, v) for n, v in fixed], dtype=object),
        {"long_name": "the input fixed and its value"}))


def uncertainty_dataset(setup: Setup, *, case: dict, ranges: dict, R_band, kinematics: str,
                        n_base: int, convergence, resamples: int, seed: int,
                        alternatives: dict, runs=None) -> xr.Dataset:
    """Sobol indices and bands of the quantities of ``case`` (``name``, ``title``, ``beta``,
    ``mass``, ``eps_bar``, ``speed`` or None, ``phi0_deg`` or ``ics``, and ``printed``: the
    paper's values to set against the bands, quantity -> key in the paper values) over
    ``ranges`` (input -> ``[low, high]`` for every input but R) and ``R_band``
    (:func:`calibrated_band`: low, high and how they were found); the nominal run is the case
    as the paper runs it: R and r(0) of ``setup``, no tolerances.  ``runs`` as
    :func:`run_case`'s.  ``alternatives`` (input -> list of ``[low, high]`` within its range)
    are the other priors the rows are evaluated under: a narrower range is the sample's points
    inside it, uniform there too; a fixed value (``low == high``) is a run of each of Saltelli's
    base points with the input at that value (``fixed_y``)."""
    R_low, R_high, R_how = R_band
    spec = problem({"R": (R_low, R_high), **{name: tuple(ranges[name])
                                              for name in INPUTS[1:]}})
    x = sample(spec, n_base, seed)
    run = partial(run_case, setup, case=case, kinematics=kinematics, runs=runs)
    at = {"R": setup.R, "zeta": setup.zeta, "r0": setup.r0}
    nominal = {q: v[0] for q, v in run([[at.get(n, 0.0) for n in INPUTS]]).items()}
    ds = study_dataset(spec, x, run(x), nominal, QUANTITIES, n_bases=convergence,
                       resamples=resamples, seed=seed)
    if fixed := fixed_priors(alternatives):
        ds = with_fixed_priors(ds, fixed, fixed_prior_runs(run, x, len(INPUTS), fixed))
    speed = "the run-up" if case["speed"] is None else f"{case['speed']:g} rad/s"
    over = (f" (each a mean over {len(case['ics'])} initial conditions)" if case.get("ics")
            else "")
    attrs = dataset_attrs(
        f"uncertainty of {case['title']}",
        f"Beyond the paper: Sobol indices ({n_base} base points) and 5-95 % bands of the peak "
        f"bearing force, its decay time and the balance times{over} at beta = "
        f"{case['beta']:g}, m = {1e3 * case['mass']:g} g, eps_bar = {case['eps_bar']:g}, "
        f"{speed} over the uncertain inputs (R within {R_low:.4g}-{R_high:.4g} m, {R_how})",
        case["title"])
    return ds.assign_attrs(case=case["name"], case_title=case["title"], design_beta=case["beta"],
                           design_mass=case["mass"], nominal_eps_bar=case["eps_bar"],
                           disk_mass=setup.M, balls=setup.n, support_k=setup.k,
                           support_zeta=setup.zeta, nominal_R=setup.R,
                           speed=setup.omega if case["speed"] is None else case["speed"],
                           r_threshold=setup.criterion.r_threshold,
                           printed=json.dumps(case["printed"]),
                           mass_tolerance=json.dumps(list(ranges["mass_tolerance"])),
                           overload=float(ranges["overload"]), R_range=R_how,
                           prior_alternatives=json.dumps(alternatives), **attrs)


#: What the rows of the uncertainty study rest on.
_CHOICES = ("paper_b.uncertainty.ranges (the inputs' ranges, chosen, zeta's a stated prior; "
            "R's range from the calibration of rule b_forces)",
            "paper_b.uncertainty.prior_alternatives (the other priors the rows are evaluated "
            "under, chosen)",
            "paper_b.uncertainty.n_base (the sample, chosen from its convergence)")


def prior_samples(ds: xr.Dataset, quantity: str) -> dict[str, np.ndarray]:
    """The values of ``quantity`` under each prior of the study ``ds``: its own ranges (the
    whole sample) first, then each alternative of ``prior_alternatives``: a narrower range the
    sample's points inside it (uniform there, the other inputs as before), a fixed value its
    runs (``fixed_y``). Keyed by the priors' names; one entry ``""`` where there are no
    alternatives."""
    q = list(ds.quantity_name.values).index(quantity)
    y = ds.y.values[q]
    alternatives = json.loads(ds.attrs["prior_alternatives"])
    if not alternatives:
        return {"": y}
    names = [str(n) for n in ds.input_name.values]
    own = ", ".join(prior_name(n, float(ds.input_low[names.index(n)]),
                               float(ds.input_high[names.index(n)])) for n in alternatives)
    samples = {own: y}
    for name, ranges in alternatives.items():
        column = ds.x.values[:, names.index(name)]
        for low, high in ranges:
            key = prior_name(name, low, high)
            samples[key] = (ds.fixed_y.sel(fixed_prior=key).values[q] if low == high
                            else y[(column >= low) & (column <= high)])
    return samples


def _bands_text(ds: xr.Dataset, quantity: str, samples: dict) -> str:
    """The 5-95 % band of ``quantity`` under each alternative prior of ``samples``."""
    p = ds.percentile.values
    unit = str(ds.quantity_units.values[list(ds.quantity_name.values).index(quantity)])

    def band(y):
        y = y[np.isfinite(y)]
        return (f"{np.percentile(y, p[0]):.4g}-{np.percentile(y, p[-1]):.4g} {unit} over "
                f"{y.size} points" if y.size else "no point with a value")

    return "; ".join(f"with {name}: {band(y)}" for name, y in list(samples.items())[1:])


def within_band_rows(ds: xr.Dataset, paper: dict, printed: dict) -> list[Reproduced]:
    """One row per ``quantity -> paper key`` of ``printed``: is the paper's value within the
    band of its reproduction, under the study's priors and each alternative
    (:func:`prior_samples`; DEPENDS, naming the prior, where they disagree)?  Where R's range
    is not the calibrated band, the row says so; where it is, a value the calibration was
    fitted to (:data:`CALIBRATION_KEY`) is labelled so: its band holds it by construction."""
    calibrated = ds.attrs["R_range"] == CALIBRATED
    caveat = "" if calibrated else f" ({ds.attrs['R_range']})"
    fitted = re.compile(CALIBRATION_KEY.format(row=r"\d+"))
    rows = []
    for quantity, key in printed.items():
        _, text = band_statement(ds, quantity, paper[key])
        samples = prior_samples(ds, quantity)
        holds = {name: within_band(ds, quantity, band_margin(ds, quantity, paper[key], y),
                                   int(np.size(y)))
                 for name, y in samples.items()}
        others = _bands_text(ds, quantity, samples)
        used = calibrated and fitted.fullmatch(key)
        rows.append(_claim(f"{key}_within_uncertainty", holds if len(holds) > 1 else holds[""],
                           f"printed {text}{caveat}" + (f"; {others}" if others else ""),
                           choices=_CHOICES,
                           calibrated=(f"R's range is {CALIBRATED}, {key} among them"
                                       if used else "")))
    return rows


def balances_row(ds: xr.Dataset) -> Reproduced:
    """Does the case balance over the whole input ranges?  States the share that does, and how
    many of the runs' outcomes the closed form (:func:`balances_in_closed_form`: the residual
    whirl when eq. 34's existence bound fails, against the threshold) predicts; and the
    overload question, the share with the eccentricity beyond the design's eps_max."""
    q = list(ds.quantity_name.values).index("balanced")
    balanced = ds.y.values[q] == 1
    share = float(balanced.mean())
    predicted = balances_in_closed_form(ds, ds.x.values)
    masses = json.loads(ds.attrs["mass_tolerance"])
    overload = float(balances_in_closed_form(ds, None, mass_tolerance=masses,
                                             eps_offsets=(0.0, ds.attrs["overload"])).mean())
    ratio = ds.attrs["design_mass"] / ds.attrs["disk_mass"]
    return _claim("optimum_balances_within_tolerances",
                  Margin(share - 1.0, 0.0, "share of the input points",
                         "count over the sample (exact); a sample can find an input that does "
                         "not balance, never prove that all do"),
                  f"{share:.1%} of the {ds.sizes['sample']} input points balance by t_end. The "
                  f"design has m/M = {ratio:.4g} against eps_bar/2 = "
                  f"{ds.attrs['nominal_eps_bar'] / 2:.4g}, on eq. (34)'s existence bound: where "
                  "a lighter ball or a larger eccentricity crosses it, the balls gather opposite "
                  "the unbalance and leave a residual whirl, which balances by the criterion "
                  f"while it stays below {1e3 * ds.attrs['r_threshold']:g} mm. That closed form "
                  f"predicts {int(np.sum(predicted == balanced))} of the {balanced.size} "
                  f"outcomes. Overload, a separate question: with the eccentricity up to "
                  f"{ds.attrs['overload']:.0%} beyond eps_max and the ball mass within "
                  f"{masses[0]:+.0%} to {masses[1]:+.0%}, it predicts {overload:.1%} balance",
                  choices=_CHOICES)


def uncertainty_rows(studies: dict[str, xr.Dataset], paper: dict) -> list[Reproduced]:
    """Every printed value of every case against its band; whether Table 2's optimum balances
    over the whole ranges.  A claim row of the paper values (``*_within_uncertainty``) that no
    case could test -- its case runs under other conditions than the paper's, e.g. another
    Table 2 speed, at which the paper prints no value (found by the configuration fuzzer) --
    is UNDETERMINED, saying so."""
    rows = [row for ds in studies.values()
            for row in within_band_rows(ds, paper, json.loads(ds.attrs["printed"]))]
    return (rows + untested_rows(paper, {row.quantity for row in rows})
            + [balances_row(studies["table2"])])


def untested_rows(paper: dict, made: set[str]) -> list[Reproduced]:
    """An UNDETERMINED row for each ``*_within_uncertainty`` claim of ``paper`` not in
    ``made``, saying why."""
    return [_claim(key, None, "not tested under this configuration: no case of the "
                   "uncertainty study runs under the paper's conditions for this value "
                   "(e.g. Table 2's speed differs from the paper's)", choices=_CHOICES)
            for key in paper if key.endswith("_within_uncertainty") and key not in made]
