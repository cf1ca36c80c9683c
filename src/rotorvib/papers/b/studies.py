"""Paper B's balance-time studies as labelled datasets: balance time against any one run
parameter (Figs 8-10, 12-14 and beyond), Table 1, the forces of Table 2 against the race radius
and the basin of initial ball positions.

Every study is one batch of compiled runs over the product of its axes; each run reports the
threshold balance time (NaN and ``balanced = 0`` when censored), the paper's envelope variant
and the bearing force (eq. 40).  Label axes (kinematics, initial condition) are dimensions with a
string coordinate ``<axis>_name``; select with :func:`rotorvib.io.coords.pick`.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.io.coords import axis_coord, label_coord
from rotorvib.models.balancer.layout import metric
from rotorvib.models.balancer.outcomes import OUTCOMES
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import (IC_LONG_NAME, KINEMATICS_LONG_NAME, LazyInputs, Setup,
                                     describe, parameter_coord)

METRIC_ATTRS = {
    "balance_time": ("balance time: r stays below the threshold afterwards (NaN if censored)", "s"),
    "balanced": ("1 if balanced before the end of the run, 0 if censored", "1"),
    "envelope_time": ("balance time by the envelope through the peaks of r(t) (NaN if censored)",
                      "s"),
    "force_max": ("maximum bearing force F = k r + c r' (eq. 40)", "N"),
    "force_max_time": ("time of the maximum bearing force", "s"),
    "force_decay_time": ("time after which F stays below k r_threshold (NaN if not reached)", "s"),
    "r_end": ("whirl radius at the end of the run", "m"),
}


def metric_attrs(name: str) -> dict:
    """The ``long_name`` and ``units`` attributes of run metric ``name``
    (:data:`METRIC_ATTRS`)."""
    long_name, units = METRIC_ATTRS[name]
    return {"long_name": long_name, "units": units}


def _case_coords(cases, long_name):
    """Coordinates of a list of (beta, m) cases: number, beta and mass of each."""
    return {"case": ("case", np.arange(1, len(cases) + 1, dtype=np.int32),
                     {"long_name": long_name, "units": "1"}),
            "case_beta": ("case", np.array([c[0] for c in cases], float),
                          {"long_name": "ball damping ratio beta of the case", "units": "1"}),
            "case_mass": ("case", np.array([c[1] for c in cases], float),
                          {"long_name": "ball mass of the case", "units": "kg"})}


def grid_dataset(setup: Setup, axes: dict, coords: dict, make_inputs, attrs: dict,
                 symmetric: tuple[str, str] | None = None, runs=None) -> xr.Dataset:
    """Run every point of the product of ``axes`` (name -> values) and label the metrics.
    ``runs(inputs) -> metrics`` computes them (``setup.runs`` unless given: a shard of them or
    the gathered shards, :mod:`rotorvib.pipeline.shards`).

    ``symmetric = (a, b)``: axes ``a`` and ``b`` have the same values and the metrics are
    invariant under swapping them, so only the points with ``index(a) <= index(b)`` are run and
    the others are their mirror images (about half the runs)."""
    names = list(axes)
    shape = tuple(len(v) for v in axes.values())
    index = np.indices(shape).reshape(len(shape), -1)        # every point, in C order
    if symmetric is not None:
        ia, ib = names.index(symmetric[0]), names.index(symmetric[1])
        if not np.array_equal(axes[symmetric[0]], axes[symmetric[1]]):
            raise ValueError(f"symmetric axes {symmetric} must have the same values")
        mirrored = index[ia] > index[ib]
        index[[ia, ib]] = np.where(mirrored, index[[ib, ia]], index[[ia, ib]])
    # the points run, in C order, and which of them answers each point
    run, answer = np.unique(np.ravel_multi_index(index, shape), return_inverse=True)
    del index

    def point_inputs(k):
        return make_inputs(**{name: axes[name][i]
                              for name, i in zip(names, np.unravel_index(run[k], shape))})

    metrics = (runs or setup.runs)(LazyInputs(run.size, point_inputs))
    data = {}
    for var in METRIC_ATTRS:
        values = metric(metrics[answer], var).reshape(shape)
        if var == "balanced":
            values = values.astype(np.int8)
        data[var] = (names, values, metric_attrs(var))
    outcomes = metric(metrics[answer], "outcome")
    if np.isnan(outcomes).any():
        raise ValueError("a run of the grid has no outcome (stopped above a balance bound)")
    data["outcome"] = (names, outcomes.astype(np.int8).reshape(shape),
                       {"long_name": "how the run ends", "units": "1",
                        "flag_values": np.arange(len(OUTCOMES), dtype=np.int8),
                        "flag_meanings": " ".join(OUTCOMES)})
    return xr.Dataset(data, coords=coords, attrs=attrs)


def balance_study_dataset(setup: Setup, *, kinematics, ics: dict, axis: str, values,
                          each: dict | None = None, fixed: dict, where: str,
                          runs=None) -> xr.Dataset:
    """Balance time against one run parameter ``axis`` (a key of
    :data:`~rotorvib.papers.b.setup.RUN_PARAMETERS`) over ``values``, for every kinematics,
    every value of the parameters in ``each`` (name -> list) and every initial condition, with
    the other parameters ``fixed`` (name -> value).  Figs 8-10 vary ``beta`` at fixed ``mass``
    for each ``eps_bar``; Figs 12-14 vary ``mass`` at fixed ``beta``."""
    each = each or {}
    axes = {"kinematics": kinematics, **each, "ic": list(ics), axis: values}

    def make_inputs(kinematics, ic, **point):
        return setup.run_inputs(**fixed, **point, phi0_deg=ics[ic], kinematics=kinematics)

    coords = {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **{name: v for name, vals in each.items()
                 for name, v in parameter_coord(name, vals).items()},
              **label_coord("ic", list(ics), IC_LONG_NAME),
              **parameter_coord(axis, values)}
    over = " and ".join([*each, "initial condition"])
    return grid_dataset(setup, axes, coords, make_inputs,
                        dataset_attrs(f"balance time against {axis}",
                                      f"Balance time, envelope time and bearing force over "
                                      f"{axis} for each {over} ({describe(fixed)}, run-up to "
                                      f"{setup.omega} rad/s)", where), runs=runs)


def table1_dataset(setup: Setup, *, kinematics, speeds, ics: dict, beta, eps_bar, masses,
                   runs=None):
    """Table 1: balance time over ball mass for each operating speed and initial condition."""
    def make_inputs(kinematics, speed, ic, mass):
        return setup.run_inputs(mass=mass, eps_bar=eps_bar, beta=beta, phi0_deg=ics[ic],
                                kinematics=kinematics, speed=speed)

    axes = {"kinematics": kinematics, "speed": speeds, "ic": list(ics), "mass": masses}
    coords = {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **parameter_coord("speed", speeds), **label_coord("ic", list(ics), IC_LONG_NAME),
              **parameter_coord("mass", masses)}
    return grid_dataset(setup, axes, coords, make_inputs,
                        dataset_attrs("optimum ball mass against operating speed",
                                      f"Balance time over ball mass, speed and initial condition "
                                      f"(beta = {beta}, eps_bar = {eps_bar})", "Table 1"),
                        runs=runs)


def force_dataset(setup: Setup, *, kinematics, cases, R_values, speed, eps_bar, phi0_deg,
                  runs=None):
    """Table 2 and the calibration of R: bearing force of each (beta, m) case against R."""
    def make_inputs(kinematics, case, R):
        beta, mass = cases[case]
        return setup.run_inputs(mass=mass, eps_bar=eps_bar, beta=beta, phi0_deg=phi0_deg,
                                kinematics=kinematics, speed=speed, R=R)

    axes = {"kinematics": kinematics, "case": list(range(len(cases))), "R": R_values}
    coords = {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_case_coords(cases, "row of Table 2"), **parameter_coord("R", R_values)}
    return grid_dataset(setup, axes, coords, make_inputs,
                        dataset_attrs("bearing forces of Table 2 against the race radius",
                                      f"Peak and decay of the bearing force at {speed} rad/s for "
                                      "the rows of Table 2, over the race radius R (not printed; "
                                      "inferred)", "Table 2, eq. 40"), runs=runs)


def basin_dataset(setup: Setup, *, kinematics, cases, n, eps_bar, ics, runs=None):
    """Balance time over all initial ball positions (phi1(0), phi2(0)) in [0, 360)^2, and at the
    paper's initial conditions ``ics`` (name -> angles, deg) for comparison; the balls are
    identical, so the map is symmetric under swapping them and half of it is run."""
    angles = np.arange(n) * 360.0 / n

    def make_inputs(kinematics, case, phi1, phi2):
        beta, mass = cases[case]
        return setup.run_inputs(mass=mass, eps_bar=eps_bar, beta=beta, phi0_deg=(phi1, phi2),
                                kinematics=kinematics)

    axes = {"kinematics": kinematics, "case": list(range(len(cases))), "phi1": angles,
            "phi2": angles}
    coords = {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_case_coords(cases, "(beta, m) case"),
              **axis_coord("phi1", angles, "initial angle of ball 1", "degree"),
              **axis_coord("phi2", angles, "initial angle of ball 2", "degree")}
    attrs = dataset_attrs("balance time over all initial ball positions",
                          "Beyond the paper: are the three initial conditions of eq. (39) "
                          f"representative? (eps_bar = {eps_bar}; phi2 < phi1 mirrors "
                          "phi1 < phi2: identical balls)", "eq. (39)")
    grid = grid_dataset(setup, axes, coords, make_inputs, {**attrs, "eps_bar": eps_bar},
                        symmetric=("phi1", "phi2"), runs=runs)
    names = list(ics)
    at_ics = grid_dataset(
        setup, {"kinematics": kinematics, "case": list(range(len(cases))), "ic": names},
        {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
         **_case_coords(cases, "(beta, m) case"), **label_coord("ic", names, IC_LONG_NAME)},
        lambda kinematics, case, ic: make_inputs(kinematics, case, *ics[ic]), {}, runs=runs)
    for var in ("balance_time", "balanced"):
        grid[f"ic_{var}"] = at_ics[var].assign_attrs(
            long_name=f"{at_ics[var].attrs['long_name']} at the paper's initial conditions")
    return grid
