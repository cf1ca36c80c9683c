"""Beyond paper B: a balancer designed for both goals.

Paper B optimises the balance time alone (section 9) and reports the bearing forces of a few
designs afterwards (Table 2).  Here the ball damping ``beta`` and mass ``m`` are chosen by
NSGA-II for two objectives at once, each robust over initial ball positions: a fixed sample of
positions drawn uniformly on the torus (seeded), the same for every design,

* the mean balance time over the sample (for the optimiser, a censored run scores
  ``penalty * t_end``, as in the GA of section 9), and
* the worst peak bearing force over the sample, ``max_i max_t F(t)``.

The dataset stores no penalty as a time: a censored run's time is NaN, a design's mean
balance time is NaN when any of its runs is censored, and the number of censored runs of every
design is stored beside it.

The paper's designs (Table 2's rows, the last being the GA optimum m = 6 g, beta = 0.2) are
evaluated on the same sample and set against the front: a design is on it when it is no
further from it than the standard error of its own mean balance time over the sample.
"""

from __future__ import annotations

from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.progress import Progress
from rotorvib.methods.optima import ParetoFront
from rotorvib.models.balancer.layout import metric
from rotorvib.papers.b.choices import R_CHOICE, ZETA_CHOICE
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import Setup

_claim = partial(Reproduced.claim, "B")


def initial_positions(n: int, seed: int) -> np.ndarray:
    """``n`` initial ball positions ``(phi1, phi2)`` in degrees, uniform on ``[0, 360)^2``."""
    return np.random.default_rng(seed).uniform(0.0, 360.0, (n, 2))


def design_runs(setup: Setup, positions, *, kinematics: str, eps_bar: float, speed: float):
    """``X[:, (beta, m)] -> (times, forces)``, each of shape ``(len(X), len(positions))``: the
    balance time of every design from every initial position (NaN for a censored run, not
    balanced by the criterion's ``t_end``) and its peak bearing force; all runs in one batch."""
    positions = np.asarray(positions, float)

    def runs(x):
        x = np.asarray(x, float)
        metrics = setup.runs([setup.run_inputs(mass=mass, beta=beta, eps_bar=eps_bar,
                                               phi0_deg=tuple(phi), kinematics=kinematics,
                                               speed=speed)
                              for beta, mass in x for phi in positions], progress=False)
        metrics = metrics.reshape(len(x), len(positions), -1)
        times = np.where(metric(metrics, "balanced") == 1, metric(metrics, "balance_time"),
                         np.nan)
        return times, metric(metrics, "force_max")

    return runs


def robust_objectives(runs, censored_time: float):
    """``X -> F[:, (mean balance time (s), worst peak force (N))]`` over the positions of
    :func:`design_runs` ``runs``, a censored run scoring ``censored_time`` (the optimiser needs
    a number; it is never stored as a time)."""

    def objectives(x):
        times, forces = runs(x)
        return np.column_stack([np.where(np.isnan(times), censored_time, times).mean(axis=1),
                                forces.max(axis=1)])

    return objectives


def pareto_dataset(setup: Setup, *, kinematics: str, eps_bar: float, speed: float,
                   beta_bounds, mass_bounds, positions: int, seed: int, pop_size: int,
                   n_gen: int, censored_penalty: float, paper_designs) -> xr.Dataset:
    """The NSGA-II front over the box ``beta_bounds x mass_bounds`` and the paper's designs
    ``[(beta, m), ...]`` (Table 2's rows) on the same objectives; the search's generations are
    logged (:class:`rotorvib.io.progress.Progress`)."""
    from rotorvib.methods.ga import pareto_front  # pymoo: loaded by the search's job only

    phi = initial_positions(positions, seed)
    runs = design_runs(setup, phi, kinematics=kinematics, eps_bar=eps_bar, speed=speed)
    objectives = robust_objectives(runs, censored_penalty * setup.criterion.t_end)
    front: ParetoFront = pareto_front(objectives, 2, [beta_bounds[0], mass_bounds[0]],
                                      [beta_bounds[1], mass_bounds[1]], pop_size=pop_size,
                                      n_gen=n_gen, seed=seed,
                                      progress=Progress("NSGA-II generations", n_gen))
    front_times, _ = runs(front.x)          # the front's runs again, censored ones as NaN
    designs = np.asarray(paper_designs, float)
    design_times, design_forces = runs(designs)
    t_long = {"long_name": "mean balance time over the initial ball positions (NaN if any "
                           "run is censored)", "units": "s"}
    n_long = {"long_name": "runs not balanced by t_end (censored) over the initial ball "
                           "positions", "units": "1"}
    f_long = {"long_name": "largest peak bearing force over the initial ball positions",
              "units": "N"}
    return xr.Dataset(
        {"front_beta": ("front", front.x[:, 0], {"long_name": "ball damping ratio beta, "
                                                              "Pareto front", "units": "1"}),
         "front_mass": ("front", front.x[:, 1], {"long_name": "ball mass m, Pareto front",
                                                 "units": "kg"}),
         "front_balance_time": ("front", front_times.mean(axis=1), t_long),
         "front_censored": ("front", np.isnan(front_times).sum(axis=1), n_long),
         "front_force": ("front", front.f[:, 1], f_long),
         "design_beta": ("design", designs[:, 0], {"long_name": "ball damping ratio of the "
                                                                "paper's design", "units": "1"}),
         "design_mass": ("design", designs[:, 1], {"long_name": "ball mass of the paper's "
                                                                "design", "units": "kg"}),
         "design_balance_time": ("design", design_times.mean(axis=1), t_long),
         "design_censored": ("design", np.isnan(design_times).sum(axis=1), n_long),
         "design_force": ("design", design_forces.max(axis=1), f_long),
         "design_times": (("design", "position"), design_times, {
             "long_name": "balance time of the paper's design from each initial position "
                          "(NaN: censored)", "units": "s"}),
         "initial_phi": (("position", "ball"), phi, {"long_name": "initial ball angle of the "
                                                                   "sample", "units": "degree"}),
         "n_evaluations": ((), front.n_eval, {"long_name": "designs evaluated by NSGA-II",
                                              "units": "1"})},
        coords={"design": ("design", np.arange(1, len(designs) + 1, dtype=np.int32),
                           {"long_name": "row of the paper's Table 2", "units": "1"})},
        attrs={**dataset_attrs(
            "balance time against peak bearing force over (beta, m)",
            f"Beyond the paper: NSGA-II front (population {pop_size}, {n_gen} generations, "
            f"seed {seed}) of the mean balance time and the worst peak bearing force over "
            f"{positions} initial ball positions; {kinematics} kinematics, {speed:g} rad/s, "
            f"eps_bar = {eps_bar:g}", "section 9, Table 2"), "kinematics": kinematics},
    )


def lead_over_front(ds: xr.Dataset) -> np.ndarray:
    """For each paper design, how much shorter (s) its mean balance time is than the front's
    best at no more peak force: negative where the front does better, ``+inf`` where no front
    design has as little force (nothing on the front dominates it)."""
    t, f = ds.front_balance_time.values, ds.front_force.values
    f = np.where(np.isfinite(t), f, np.inf)        # a design with a censored run is no match
    return np.array([t[f <= fd].min() - td if (f <= fd).any() else np.inf
                     for td, fd in zip(ds.design_balance_time.values, ds.design_force.values)])


def gap_to_front(ds: xr.Dataset) -> np.ndarray:
    """For each paper design, how much longer (s) its mean balance time is than the front's
    best at no more peak force (0 where no front design has as little force)."""
    return np.maximum(0.0, -lead_over_front(ds))


def standard_errors(ds: xr.Dataset) -> np.ndarray:
    """Standard error (s) of each paper design's mean balance time over the sampled positions."""
    times = ds.design_times.values
    return times.std(axis=1, ddof=1) / np.sqrt(times.shape[1])


_CHOICES = (R_CHOICE, ZETA_CHOICE, "paper_b.pareto.positions, seed (the sampled initial "
             "positions, chosen)", "paper_b.pareto.pop_size, n_gen (the front's search, chosen)")


def pareto_rows(ds: xr.Dataset) -> list[Reproduced]:
    """Is the paper's GA optimum (Table 2's last row) on the front, i.e. no further from it
    than the standard error of its own mean balance time over the sampled positions?"""
    if not np.isfinite(ds.design_balance_time.values[-1]):
        return [_claim("optimum_efficient_for_force", None,
                       "undetermined: the GA optimum (Table 2's last row) leaves "
                       f"{int(ds.design_censored.values[-1])} of {ds.sizes['position']} "
                       "sampled initial positions unbalanced by t_end, so it has no mean "
                       "balance time", choices=_CHOICES)]
    gaps, errors = gap_to_front(ds), standard_errors(ds)
    parts = [f"row {int(r)} (beta = {b:g}, m = {1e3 * m:g} g): {t:.3g} s +/- {e:.2g} s, "
             f"{f:.4g} N, {g:.2g} s slower than the front at no more force"
             for r, b, m, t, e, f, g in zip(ds.design.values, ds.design_beta.values,
                                            ds.design_mass.values, ds.design_balance_time.values,
                                            errors, ds.design_force.values, gaps)]
    t, f = ds.front_balance_time.values, ds.front_force.values
    fast, gentle = np.nanargmin(t), np.argmin(np.where(np.isfinite(t), f, np.inf))
    return [_claim("optimum_efficient_for_force",
                   Margin(float(lead_over_front(ds)[-1]), float(errors[-1]), "s",
                          f"standard error of the mean balance time over "
                          f"{ds.sizes['position']} random initial positions"),
                   f"mean balance time (+/- its standard error) and worst peak force over "
                   f"{ds.sizes['position']} random initial positions ({ds.attrs['kinematics']} "
                   "kinematics): " + "; ".join(parts) + ". The front runs from "
                   f"{t[fast]:.3g} s at {f[fast]:.4g} N (beta = {ds.front_beta.values[fast]:.2g}, "
                   f"m = {1e3 * ds.front_mass.values[fast]:.3g} g) to {t[gentle]:.3g} s at "
                   f"{f[gentle]:.4g} N (beta = {ds.front_beta.values[gentle]:.2g}, m = "
                   f"{1e3 * ds.front_mass.values[gentle]:.3g} g)", choices=_CHOICES)]
