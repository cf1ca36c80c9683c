"""Genetic-algorithm search of the ball damping and mass for the shortest balance time
(paper B, section 9), and its dataset.

The searches import pymoo where they run (:mod:`rotorvib.methods.ga`): the job that gathers
the searches of the GA's shards into the dataset runs none."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.checks import number
from rotorvib.io.coords import label_coord
from rotorvib.io.progress import Progress
from rotorvib.methods.optima import GAResult
from rotorvib.models.balancer.layout import ABOVE_BOUND, metric
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import IC_LONG_NAME, KINEMATICS_LONG_NAME, Setup, parameter_coord


def balance_time_objectives(setup: Setup, problems: list[dict], *, censored_penalty: float):
    """``([X_i[:, (beta, mass)]], worst) -> [balance times (s)]`` for GA problems
    ``{"kinematics", "eps_bar", "phi0_deg"}``: the populations of all problems run as one batch,
    set up and run by ``setup`` like every study; a censored run (not balanced by the
    criterion's ``t_end``) scores ``censored_penalty * t_end`` (>= t_end, so that it never passes
    for a time).  A run of problem ``i`` stops as soon as its balance time is known to exceed
    ``worst[i]`` (the worst of its population, :func:`rotorvib.methods.ga.minimise_many`) and
    scores ``inf``: its time would not change the search."""
    number("censored_penalty", censored_penalty, minimum=1.0, inclusive=True,
           what=" (a censored run must never score as a balance time)")

    def objectives(xs, worst):
        sizes = [len(x) for x in xs]
        metrics = setup.runs([pair for problem, x in zip(problems, xs)
                              for pair in setup.batch_inputs(masses=x[:, 1], betas=x[:, 0],
                                                             **problem)],
                             progress=False, balance_bounds=np.repeat(worst, sizes))
        scores = np.where(metric(metrics, "balanced") == 1, metric(metrics, "balance_time"),
                          censored_penalty * setup.criterion.t_end)
        scores[metric(metrics, "status") == ABOVE_BOUND] = np.inf
        return np.split(scores, np.cumsum(sizes)[:-1])

    return objectives


def balance_time_objective(setup: Setup, *, kinematics: str, eps_bar: float, phi0_deg,
                           censored_penalty: float):
    """``X[:, (beta, mass)] -> balance time`` (s) of one problem, every run to its end (see
    :func:`balance_time_objectives`)."""
    objectives = balance_time_objectives(
        setup, [{"kinematics": kinematics, "eps_bar": eps_bar, "phi0_deg": phi0_deg}],
        censored_penalty=censored_penalty)
    return lambda x: objectives([x], [np.inf])[0]


def _box(beta_bounds, mass_bounds) -> tuple[np.ndarray, np.ndarray]:
    return (np.array([beta_bounds[0], mass_bounds[0]]),
            np.array([beta_bounds[1], mass_bounds[1]]))


def tune_balancer(objective, beta_bounds, mass_bounds, *, pop_size, n_gen, seed) -> GAResult:
    """Minimise one balance-time ``objective`` over the box of (beta, m)."""
    from rotorvib.methods.ga import minimise

    return minimise(objective, *_box(beta_bounds, mass_bounds), pop_size=pop_size, n_gen=n_gen,
                    seed=seed)


def ga_searches(kinematics, eps_bars, ics: dict, seeds) -> list[tuple[dict, int]]:
    """The GA's searches: every kinematics x eps_bar x initial condition problem (section 9)
    under each of ``seeds``, the first seed's problems first."""
    problems = [{"kinematics": kin, "eps_bar": eps_bar, "phi0_deg": ics[ic]}
                for kin in kinematics for eps_bar in eps_bars for ic in ics]
    return [(problem, s) for s in seeds for problem in problems]


def solve(setup: Setup, searches: list[tuple[dict, int]], *, beta_bounds, mass_bounds,
          pop_size, n_gen, censored_penalty) -> list[GAResult]:
    """Run ``searches`` (:func:`ga_searches`) over the box of (beta, m) in lockstep, one batch
    of runs per generation (:func:`balance_time_objectives`); each generation's progress is
    logged (rotorvib.io.progress)."""
    from rotorvib.methods.ga import minimise_many

    objectives = balance_time_objectives(setup, [problem for problem, _ in searches],
                                         censored_penalty=censored_penalty)
    progress = Progress(f"GA generations ({len(searches)} searches in lockstep)", n_gen)
    return minimise_many(objectives, len(searches), *_box(beta_bounds, mass_bounds),
                         pop_size=pop_size, n_gen=n_gen, seed=[s for _, s in searches],
                         progress=lambda gen, best: progress(gen, f"first search's best "
                                                                  f"{best:.3g} s"))


def ga_dataset(setup: Setup, *, kinematics, eps_bars, ics: dict, beta_bounds, mass_bounds,
               pop_size, n_gen, seed, spread_seeds=(), censored_penalty) -> xr.Dataset:
    """Genetic algorithm over (beta, m) for every kinematics x eps_bar x initial condition
    (section 9), all problems in lockstep (:func:`solve`), as :func:`results_dataset`."""
    searches = ga_searches(kinematics, eps_bars, ics, [seed, *spread_seeds])
    results = solve(setup, searches, beta_bounds=beta_bounds, mass_bounds=mass_bounds,
                    pop_size=pop_size, n_gen=n_gen, censored_penalty=censored_penalty)
    return results_dataset(setup, results, kinematics=kinematics, eps_bars=eps_bars, ics=ics,
                           pop_size=pop_size, n_gen=n_gen, seed=seed, spread_seeds=spread_seeds,
                           censored_penalty=censored_penalty)


def results_dataset(setup: Setup, results: list[GAResult], *, kinematics, eps_bars, ics: dict,
                    pop_size, n_gen, seed, spread_seeds=(), censored_penalty) -> xr.Dataset:
    """The GA's dataset from the ``results`` of all its searches, in the order of
    :func:`ga_searches`.  The optimum is that of ``seed``; each problem is solved again from each
    of ``spread_seeds``, and the ``*_by_seed`` variables hold the optima of all the seeds, the
    first ``seed``'s: the spread of a GA's answer over its seeds."""
    seeds = [seed, *spread_seeds]
    shape = (len(kinematics), len(eps_bars), len(ics))
    if len(results) != len(seeds) * int(np.prod(shape)):
        raise ValueError(f"{len(results)} search results for {len(seeds)} seeds x "
                         f"{int(np.prod(shape))} problems")
    x_all = np.moveaxis(np.array([r.x for r in results]).reshape((len(seeds),) + shape + (2,)),
                        0, -2)
    f_all = np.moveaxis(np.array([r.f for r in results]).reshape((len(seeds),) + shape), 0, -1)
    first = results[:len(results) // len(seeds)]
    history = np.array([r.history["best_f"] for r in first]).reshape(shape + (n_gen,))
    t_end = setup.criterion.t_end
    censored = f_all[..., 0] >= t_end         # scored the penalty: it is no time, kept as NaN
    f_all, history = (np.where(v >= t_end, np.nan, v) for v in (f_all, history))
    n_eval = np.array([r.history["n_eval"][-1] for r in first], dtype=np.int64).reshape(shape)
    dims = ("kinematics", "eps_bar", "ic")
    return xr.Dataset(
        {"beta_opt": (dims, x_all[..., 0, 0], {"long_name": "optimum ball damping ratio",
                                               "units": "1"}),
         "mass_opt": (dims, x_all[..., 0, 1], {"long_name": "optimum ball mass", "units": "kg"}),
         "balance_time_opt": (dims, f_all[..., 0], {"long_name": "balance time at the optimum "
                                                                 "(NaN if censored)", "units": "s"}),
         "censored": (dims, censored.astype(np.int8),
                      {"long_name": "1 if even the optimum did not balance by t_end",
                       "units": "1"}),
         "n_evaluations": (dims, n_eval, {"long_name": "balance-time evaluations (runs) of the "
                                                       "GA", "units": "1"}),
         "best_balance_time": (dims + ("generation",), history,
                               {"long_name": "best balance time of each generation (NaN: no "
                                             "run of it balanced by t_end)", "units": "s"}),
         "beta_opt_by_seed": (dims + ("seed",), x_all[..., 0],
                              {"long_name": "optimum ball damping ratio from each seed",
                               "units": "1"}),
         "mass_opt_by_seed": (dims + ("seed",), x_all[..., 1],
                              {"long_name": "optimum ball mass from each seed", "units": "kg"}),
         "balance_time_opt_by_seed": (dims + ("seed",), f_all,
                                      {"long_name": "balance time at each seed's optimum (NaN if "
                                                    "censored)", "units": "s"})},
        coords={**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **parameter_coord("eps_bar", eps_bars),
                **label_coord("ic", list(ics), IC_LONG_NAME),
                "generation": ("generation", np.arange(1, n_gen + 1, dtype=np.int32),
                               {"long_name": "GA generation", "units": "1"}),
                "seed": ("seed", np.arange(len(seeds), dtype=np.int32),
                         {"long_name": "index of the GA's seed (0 gives the optimum)",
                          "units": "1"}),
                "seed_value": ("seed", np.asarray(seeds, np.int64),
                               {"long_name": "seed of the GA's random generator",
                                "units": "1"})},
        attrs=dataset_attrs("genetic-algorithm optimum of ball damping and mass",
                            f"pymoo GA, population {pop_size}, {n_gen} generations, seed "
                            f"{seed} (and {len(spread_seeds)} more seeds for the spread of the "
                            f"optimum); objective: balance time (censored runs score "
                            f"{censored_penalty} t_end)", "section 9"),
    )
