"""Genetic-algorithm search of the ball damping and mass for the shortest balance time
(paper B, section 9), and its dataset."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.io.coords import label_coord
from rotorvib.methods.ga import GAResult, minimise
from rotorvib.models.balancer.simulate import metric
from rotorvib.papers.b.setup import (IC_LONG_NAME, KINEMATICS_LONG_NAME, Setup, dataset_attrs,
                                     parameter_coord)


def balance_time_objective(setup: Setup, *, kinematics: str, eps_bar: float, phi0_deg,
                           censored_penalty: float):
    """``X[:, (beta, mass)] -> balance time`` (s), one batch of runs per population, set up by
    ``setup`` like every study; a censored run (not balanced by the criterion's ``t_end``)
    scores ``censored_penalty * t_end`` (>= t_end, so that it never passes for a time)."""
    if not (np.isfinite(censored_penalty) and censored_penalty >= 1):
        raise ValueError(f"censored_penalty = {censored_penalty!r}: must be a finite number >= 1 "
                         "(a censored run must never score as a balance time)")

    def objective(X):
        metrics = setup.runs([setup.run_inputs(mass=mass, eps_bar=eps_bar, beta=beta,
                                               phi0_deg=phi0_deg, kinematics=kinematics)
                              for beta, mass in X], progress=False)
        return np.where(metric(metrics, "balanced") == 1, metric(metrics, "balance_time"),
                        censored_penalty * setup.criterion.t_end)

    return objective


def tune_balancer(objective, beta_bounds, mass_bounds, *, pop_size, n_gen, seed) -> GAResult:
    lower = np.array([beta_bounds[0], mass_bounds[0]])
    upper = np.array([beta_bounds[1], mass_bounds[1]])
    return minimise(objective, lower, upper, pop_size=pop_size, n_gen=n_gen, seed=seed)


def ga_dataset(setup: Setup, *, kinematics, eps_bars, ics: dict, beta_bounds, mass_bounds,
               pop_size, n_gen, seed, censored_penalty) -> xr.Dataset:
    """Genetic algorithm over (beta, m) for every eps_bar x initial condition (section 9)."""
    shape = (len(kinematics), len(eps_bars), len(ics))
    x_opt, f_opt = np.empty(shape + (2,)), np.empty(shape)
    history = np.empty(shape + (n_gen,))
    n_eval = np.empty(shape, dtype=np.int64)
    for i, kin in enumerate(kinematics):
        for j, eps_bar in enumerate(eps_bars):
            for q, ic in enumerate(ics):
                objective = balance_time_objective(setup, kinematics=kin, eps_bar=eps_bar,
                                                   phi0_deg=ics[ic],
                                                   censored_penalty=censored_penalty)
                res = tune_balancer(objective, beta_bounds, mass_bounds, pop_size=pop_size,
                                    n_gen=n_gen, seed=seed)
                x_opt[i, j, q], f_opt[i, j, q] = res.x, res.f
                history[i, j, q] = res.history["best_f"]
                n_eval[i, j, q] = res.history["n_eval"][-1]
    dims = ("kinematics", "eps_bar", "ic")
    return xr.Dataset(
        {"beta_opt": (dims, x_opt[..., 0], {"long_name": "optimum ball damping ratio",
                                            "units": "1"}),
         "mass_opt": (dims, x_opt[..., 1], {"long_name": "optimum ball mass", "units": "kg"}),
         "balance_time_opt": (dims, f_opt, {"long_name": "balance time at the optimum "
                                                         "(penalised if censored)", "units": "s"}),
         "censored": (dims, (f_opt >= setup.criterion.t_end).astype(np.int8),
                      {"long_name": "1 if even the optimum did not balance by t_end (its "
                                    "balance_time_opt is the penalty, not a time)", "units": "1"}),
         "n_evaluations": (dims, n_eval, {"long_name": "balance-time evaluations (runs) of the "
                                                       "GA", "units": "1"}),
         "best_balance_time": (dims + ("generation",), history,
                               {"long_name": "best balance time of each generation",
                                "units": "s"})},
        coords={**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **parameter_coord("eps_bar", eps_bars),
                **label_coord("ic", list(ics), IC_LONG_NAME),
                "generation": ("generation", np.arange(1, n_gen + 1, dtype=np.int32),
                               {"long_name": "GA generation", "units": "1"})},
        attrs=dataset_attrs("genetic-algorithm optimum of ball damping and mass",
                            f"pymoo GA, population {pop_size}, {n_gen} generations, seed "
                            f"{seed}; objective: balance time (censored runs score "
                            f"{censored_penalty} t_end)", "section 9"),
    )
