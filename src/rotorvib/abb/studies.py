"""Paper B's studies as labelled datasets: stability maps, balance-time grids, time responses,
the genetic algorithm, Tables 1-2, the calibration of R and the basin of initial ball positions.

Every balance-time study is one batch of compiled runs (``run_batch``) over the product of its
axes; each run reports the threshold balance time (NaN and ``balanced = 0`` when censored), the
paper's envelope variant and the bearing force (eq. 40).  Label axes (kinematics, initial
condition) are dimensions with a string coordinate ``<axis>_name``; select with :func:`pick`.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..ga import GAResult
from . import engine, stability
from .optimise import balance_time_objective, tune_balancer
from .parameters import (Balancer, SpeedProfile, fixed_parameters, fixed_state,
                         paper_b_groups)
from .simulate import check_batch, run, run_batch

REFERENCE = ("Paper B: M. Rezaee, R. Fathi, The effect of damping ratio and balls mass on the "
             "stability of automatic ball balancer and determining their optimum values, "
             "Modares Mechanical Engineering 14(3):110-118, 2014 (Persian)")

METRIC_ATTRS = {
    "balance_time": ("balance time: r stays below the threshold afterwards (NaN if censored)", "s"),
    "balanced": ("1 if balanced before the end of the run, 0 if censored", "1"),
    "envelope_time": ("balance time by the envelope through the peaks of r(t) (NaN if censored)",
                      "s"),
    "force_max": ("maximum bearing force F = k r + c r' (eq. 40)", "N"),
    "force_max_time": ("time of the maximum bearing force", "s"),
    "force_decay_time": ("time after which F stays below k r_threshold (NaN if not reached)", "s"),
}
_METRIC_COLUMNS = {"balance_time": 2, "balanced": 3, "envelope_time": 4, "force_max": 6,
                   "force_max_time": 7, "force_decay_time": 8}


@dataclass(frozen=True)
class Setup:
    """Paper B's machine, initial state, speed profile and balance criterion (config)."""

    M: float
    k: float
    R: float
    n: int
    zeta: float
    r0: float
    theta0: float
    omega: float
    t_ramp: float
    r_threshold: float
    t_end: float
    sample_dt: float

    @classmethod
    def from_config(cls, machine, initial_state, speed, balance) -> "Setup":
        return cls(**machine, **initial_state, **speed, **balance)

    def balancer(self, *, m, eps_bar, beta, R=None) -> Balancer:
        R = self.R if R is None else R
        return Balancer.from_paper_b(M=self.M, k=self.k, R=R, m_bar=m / self.M, eps_bar=eps_bar,
                                     zeta=self.zeta, beta=beta, n=self.n)

    def profile(self, kinematics, speed=None) -> SpeedProfile:
        return SpeedProfile(self.omega if speed is None else speed, "runup", self.t_ramp,
                            kinematics)

    def run_inputs(self, *, m, eps_bar, beta, phi0_deg, kinematics, speed=None, R=None):
        b = self.balancer(m=m, eps_bar=eps_bar, beta=beta, R=R)
        y0 = fixed_state(self.n, r0=self.r0, theta0=self.theta0, phi0=np.radians(phi0_deg))
        return fixed_parameters(b, self.profile(kinematics, speed)), y0

    def runs(self, inputs) -> np.ndarray:
        """Metrics of many ``(params, y0)`` runs, in parallel; failures raise."""
        params = np.stack([p for p, _ in inputs])
        y0s = np.stack([y for _, y in inputs])
        metrics = run_batch(engine.FIXED, params, y0s, self.t_end, sample_dt=self.sample_dt,
                            r_threshold=self.r_threshold,
                            f_threshold=self.k * self.r_threshold)
        check_batch(metrics)
        return metrics


def pick(ds: xr.Dataset, **labels) -> xr.Dataset:
    """Select label axes by name, e.g. ``pick(ds, kinematics="printed", ic="IC1")``."""
    index = {axis: list(ds[f"{axis}_name"].values).index(label) for axis, label in labels.items()}
    return ds.isel(index)


def _label(axis, names, long_name):
    return {f"{axis}_name": (axis, np.array(names, dtype=object), {"long_name": long_name})}


def _axis(name, values, long_name, units):
    return {name: (name, np.asarray(values, dtype=float), {"long_name": long_name,
                                                           "units": units})}


def _case_coords(cases, long_name):
    """Coordinates of a list of (beta, m) cases: number, beta and mass of each."""
    return {"case": ("case", np.arange(1, len(cases) + 1, dtype=np.int32),
                     {"long_name": long_name, "units": "1"}),
            "case_beta": ("case", np.array([c[0] for c in cases], float),
                          {"long_name": "ball damping ratio beta of the case", "units": "1"}),
            "case_mass": ("case", np.array([c[1] for c in cases], float),
                          {"long_name": "ball mass of the case", "units": "kg"})}


KINEMATICS_LONG_NAME = ("disk-angle kinematics: printed (w t, as in eqs 7-9) or consistent "
                        "(int w dt)")
IC_LONG_NAME = "initial ball angles, eq. (39)"


def _grid_dataset(setup: Setup, axes: dict, coords: dict, make_inputs, attrs: dict) -> xr.Dataset:
    """Run every point of the product of ``axes`` (name -> values) and label the metrics."""
    names = list(axes)
    points = list(itertools.product(*axes.values()))
    metrics = setup.runs([make_inputs(**dict(zip(names, pt))) for pt in points])
    shape = tuple(len(v) for v in axes.values())
    data = {}
    for var, col in _METRIC_COLUMNS.items():
        values = metrics[:, col].reshape(shape)
        if var == "balanced":
            values = values.astype(np.int8)
        data[var] = (names, values, _metric_attrs(var))
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _metric_attrs(name):
    long_name, units = METRIC_ATTRS[name]
    return {"long_name": long_name, "units": units}


def _attrs(title, summary, where):
    return {"title": f"Paper B: {title}", "summary": summary,
            "references": f"{REFERENCE}; {where}"}


def stability_dataset(*, m_bar, eps_bar, zeta, beta, omega_bar, n=2, where) -> xr.Dataset:
    """Growth rate of the balanced state (largest real part of the eigenvalues, in units of
    paper B's omega_n) over a 2-D grid; ``m_bar`` or ``beta`` is the grid's first axis."""
    first = "m_bar" if np.ndim(m_bar) else "beta"
    axis = np.asarray(m_bar if first == "m_bar" else beta, dtype=float)
    A, W = np.meshgrid(axis, np.asarray(omega_bar, dtype=float), indexing="ij")
    mb, bt = (A, np.full(A.shape, beta)) if first == "m_bar" else (np.full(A.shape, m_bar), A)
    mu, rho, z, b, Om = paper_b_groups(mb, eps_bar, zeta, bt, W, n)
    exists = rho >= 0.5
    growth = np.full(A.shape, np.nan)
    if exists.any():
        growth[exists] = stability.max_real_part(mu[exists], rho[exists], z[exists], b[exists],
                                                 Om[exists]) / np.sqrt(1 + n * mb[exists])
    state = np.where(~exists, 2, np.where(growth < 0, 1, 0)).astype(np.int8)
    names = {"m_bar": ("ball/disk mass ratio m/M", "1"), "beta": ("ball damping ratio beta", "1")}
    return xr.Dataset(
        {"growth_rate": ((first, "omega_bar"), growth,
                         {"long_name": "largest real part of the eigenvalues / omega_n "
                                       "(NaN: no balanced state)", "units": "1"}),
         "state": ((first, "omega_bar"), state,
                   {"long_name": "balanced state", "units": "1", "flag_values": np.int8([0, 1, 2]),
                    "flag_meanings": "unstable stable no_balanced_state"}),
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
        coords={**_axis(first, axis, *names[first]),
                **_axis("omega_bar", omega_bar, "speed ratio omega/omega_n", "1")},
        attrs=_attrs(f"stability of the balanced state ({where})",
                     "Linearised stability of the balanced state r* = 0 at constant speed "
                     "(eqs 27-32) on a grid", where),
    )


def balance_grid_dataset(setup: Setup, *, kinematics, eps_bars, ics: dict, axis: str, values,
                         beta=None, m=None) -> xr.Dataset:
    """Figs 8-10 (``axis="beta"``, fixed mass ``m``) or 12-14 (``axis="mass"``, fixed ``beta``)."""
    def make_inputs(kinematics, eps_bar, ic, **point):
        value = point[axis]
        return setup.run_inputs(m=value if axis == "mass" else m, eps_bar=eps_bar,
                                beta=value if axis == "beta" else beta, phi0_deg=ics[ic],
                                kinematics=kinematics)

    axes = {"kinematics": kinematics, "eps_bar": eps_bars, "ic": list(ics), axis: values}
    coords = {**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_axis("eps_bar", eps_bars, "eccentricity ratio eps/R", "1"),
              **_label("ic", list(ics), IC_LONG_NAME),
              **(_axis("beta", values, "ball damping ratio beta", "1") if axis == "beta" else
                 _axis("mass", values, "ball mass m", "kg"))}
    fixed = f"m = {m} kg" if axis == "beta" else f"beta = {beta}"
    figs = "Figs 8-10" if axis == "beta" else "Figs 12-14"
    return _grid_dataset(setup, axes, coords, make_inputs,
                         _attrs(f"balance time against {axis}",
                                f"Balance time, envelope time and bearing force over {axis} for "
                                f"each eps_bar and initial condition ({fixed}, run-up to "
                                f"{setup.omega} rad/s)", figs))


def table1_dataset(setup: Setup, *, kinematics, speeds, ics: dict, beta, eps_bar, masses):
    """Table 1: balance time over ball mass for each operating speed and initial condition."""
    def make_inputs(kinematics, speed, ic, mass):
        return setup.run_inputs(m=mass, eps_bar=eps_bar, beta=beta, phi0_deg=ics[ic],
                                kinematics=kinematics, speed=speed)

    axes = {"kinematics": kinematics, "speed": speeds, "ic": list(ics), "mass": masses}
    coords = {**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_axis("speed", speeds, "operating speed", "rad s-1"),
              **_label("ic", list(ics), IC_LONG_NAME), **_axis("mass", masses, "ball mass m", "kg")}
    return _grid_dataset(setup, axes, coords, make_inputs,
                         _attrs("optimum ball mass against operating speed",
                                f"Balance time over ball mass, speed and initial condition "
                                f"(beta = {beta}, eps_bar = {eps_bar})", "Table 1"))


def force_dataset(setup: Setup, *, kinematics, cases, R_values, speed, eps_bar, phi0_deg):
    """Table 2 and the calibration of R: bearing force of each (beta, m) case against R."""
    def make_inputs(kinematics, case, R):
        beta, m = cases[case]
        return setup.run_inputs(m=m, eps_bar=eps_bar, beta=beta, phi0_deg=phi0_deg,
                                kinematics=kinematics, speed=speed, R=R)

    axes = {"kinematics": kinematics, "case": list(range(len(cases))), "R": R_values}
    coords = {**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_case_coords(cases, "row of Table 2"),
              **_axis("R", R_values, "race radius R", "m")}
    return _grid_dataset(setup, axes, coords, make_inputs,
                         _attrs("bearing forces of Table 2 against the race radius",
                                f"Peak and decay of the bearing force at {speed} rad/s for the "
                                "rows of Table 2, over the race radius R (not printed; inferred)",
                                "Table 2, eq. 40"))


def basin_dataset(setup: Setup, *, kinematics, cases, n, eps_bar):
    """Balance time over all initial ball positions (phi1(0), phi2(0)) in [0, 360)^2."""
    angles = np.arange(n) * 360.0 / n

    def make_inputs(kinematics, case, phi1, phi2):
        beta, m = cases[case]
        return setup.run_inputs(m=m, eps_bar=eps_bar, beta=beta, phi0_deg=(phi1, phi2),
                                kinematics=kinematics)

    axes = {"kinematics": kinematics, "case": list(range(len(cases))), "phi1": angles,
            "phi2": angles}
    coords = {**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **_case_coords(cases, "(beta, m) case"),
              **_axis("phi1", angles, "initial angle of ball 1", "degree"),
              **_axis("phi2", angles, "initial angle of ball 2", "degree")}
    return _grid_dataset(setup, axes, coords, make_inputs,
                         _attrs("balance time over all initial ball positions",
                                "Beyond the paper: are the three initial conditions of eq. (39) "
                                f"representative? (eps_bar = {eps_bar})", "eq. (39)"))


def time_response_dataset(setup: Setup, *, kinematics, runs: dict) -> xr.Dataset:
    """Sampled r(t), ball angles and bearing force of named runs (Figs 4-7, 11, 15, 16).

    ``runs`` maps a name to ``dict(beta, m, eps_bar, phi0, speed)``."""
    t = np.arange(int(np.floor(setup.t_end / setup.sample_dt + 1e-9)) + 1) * setup.sample_dt
    names = list(runs)
    shape = (len(kinematics), len(names), len(t))
    r, phi1, phi2, force = (np.empty(shape) for _ in range(4))
    bal, env = np.empty(shape[:2]), np.empty(shape[:2])
    for i, kin in enumerate(kinematics):
        for j, name in enumerate(names):
            spec = runs[name]
            b = setup.balancer(m=spec["m"], eps_bar=spec["eps_bar"], beta=spec["beta"])
            p, y0 = setup.run_inputs(m=spec["m"], eps_bar=spec["eps_bar"], beta=spec["beta"],
                                     phi0_deg=spec["phi0"], kinematics=kin, speed=spec["speed"])
            traj = run(engine.FIXED, p, y0, setup.t_end, sample_dt=setup.sample_dt,
                       r_threshold=setup.r_threshold, f_threshold=setup.k * setup.r_threshold,
                       store=True)
            r[i, j], force[i, j] = traj.r, traj.bearing_force(b.k, b.c)
            phi1[i, j], phi2[i, j] = np.degrees(traj.y[:, 2]), np.degrees(traj.y[:, 3])
            bal[i, j], env[i, j] = traj.result.balance_time, traj.result.envelope_time
    speed = setup.profile("consistent").speed(t)
    dims = ("kinematics", "run", "t")
    spec_var = {key: ("run", np.array([runs[nm][key] for nm in names], float),
                      {"long_name": long_name, "units": units})
                for key, long_name, units in (("beta", "ball damping ratio beta", "1"),
                                              ("m", "ball mass", "kg"),
                                              ("eps_bar", "eccentricity ratio eps/R", "1"),
                                              ("speed", "operating speed", "rad s-1"))}
    return xr.Dataset(
        {"r": (dims, r, {"long_name": "whirl radius of the geometric centre", "units": "m"}),
         "phi1": (dims, phi1, {"long_name": "angle of ball 1 on the disk", "units": "degree"}),
         "phi2": (dims, phi2, {"long_name": "angle of ball 2 on the disk", "units": "degree"}),
         "force": (dims, force, {"long_name": "bearing force F = k r + c r' (eq. 40)",
                                 "units": "N"}),
         "balance_time": (dims[:2], bal, _metric_attrs("balance_time")),
         "envelope_time": (dims[:2], env, _metric_attrs("envelope_time")),
         "omega": ("t", speed[0], {"long_name": "disk speed of the run-up at the configured "
                                                "operating speed (eq. 37)", "units": "rad s-1"}),
         "alpha": ("t", speed[1], {"long_name": "angular acceleration d omega/dt (eq. 38)",
                                   "units": "rad s-2"}),
         **{f"run_{k}": v for k, v in spec_var.items()}},
        coords={**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **_label("run", names, "named run (figure)"),
                "t": ("t", t, {"long_name": "time", "units": "s"})},
        attrs=_attrs("time responses", "r(t), ball angles and bearing force of the runs of "
                     "Figs 4-7, 11, 15, 16", "Figs 4-7, 11, 15, 16"),
    )


def ga_dataset(setup: Setup, *, kinematics, eps_bars, ics: dict, beta_bounds, mass_bounds,
               pop_size, n_gen, seed, censored_penalty) -> xr.Dataset:
    """Genetic algorithm over (beta, m) for every eps_bar x initial condition (section 9)."""
    shape = (len(kinematics), len(eps_bars), len(ics))
    x_opt, f_opt = np.empty(shape + (2,)), np.empty(shape)
    history = np.empty(shape + (n_gen,))
    for i, kin in enumerate(kinematics):
        for j, eps_bar in enumerate(eps_bars):
            for q, ic in enumerate(ics):
                objective = balance_time_objective(
                    setup.M, setup.k, setup.R, setup.zeta, eps_bar, setup.profile(kin),
                    np.radians(ics[ic]), r0=setup.r0, theta0=setup.theta0, t_end=setup.t_end,
                    sample_dt=setup.sample_dt, r_threshold=setup.r_threshold,
                    censored_penalty=censored_penalty)
                res: GAResult = tune_balancer(objective, beta_bounds, mass_bounds,
                                              pop_size=pop_size, n_gen=n_gen, seed=seed)
                x_opt[i, j, q], f_opt[i, j, q] = res.x, res.f
                history[i, j, q] = res.history["best_f"]
    dims = ("kinematics", "eps_bar", "ic")
    return xr.Dataset(
        {"beta_opt": (dims, x_opt[..., 0], {"long_name": "optimum ball damping ratio",
                                            "units": "1"}),
         "mass_opt": (dims, x_opt[..., 1], {"long_name": "optimum ball mass", "units": "kg"}),
         "balance_time_opt": (dims, f_opt, {"long_name": "balance time at the optimum "
                                                         "(penalised if censored)", "units": "s"}),
         "best_balance_time": (dims + ("generation",), history,
                               {"long_name": "best balance time of each generation",
                                "units": "s"})},
        coords={**_label("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **_axis("eps_bar", eps_bars, "eccentricity ratio eps/R", "1"),
                **_label("ic", list(ics), IC_LONG_NAME),
                "generation": ("generation", np.arange(1, n_gen + 1, dtype=np.int32),
                               {"long_name": "GA generation", "units": "1"})},
        attrs=_attrs("genetic-algorithm optimum of ball damping and mass",
                     f"pymoo GA, population {pop_size}, {n_gen} generations, seed {seed}; "
                     f"objective: balance time (censored runs score {censored_penalty} t_end)",
                     "section 9"),
    )
