"""Paper B's genetic algorithm: its objective scores the study runs, it is deterministic for a
seed, it runs its problems in lockstep, and a GA that never balances or whose seeds disagree
decides nothing."""

import dataclasses

import numpy as np
import pytest

from rotorvib.comparison.verdicts import verdict
from rotorvib.models.balancer import layout
from rotorvib.models.balancer.layout import metric
from rotorvib.papers.b.optimise import balance_time_objective, ga_dataset, tune_balancer

IC1 = (40.0, 45.0)


def test_ga_objective_scores_the_study_runs(setup):
    X = np.array([[0.2, 0.006], [1.0, 0.02]])
    objective = balance_time_objective(setup, kinematics="printed", eps_bar=0.012,
                                       phi0_deg=IC1, censored_penalty=2.0)
    runs = setup.runs([setup.run_inputs(mass=m, eps_bar=0.012, beta=beta, phi0_deg=IC1,
                                        kinematics="printed") for beta, m in X])
    balanced = metric(runs, "balanced") == 1
    assert list(balanced) == [True, False]  # the heavy ball is not balanced within 8 s
    np.testing.assert_array_equal(objective(X), [metric(runs, "balance_time")[0],
                                                 2.0 * setup.criterion.t_end])


def test_ga_objective_runs_any_number_of_balls(setup):
    """Three balls of mass m balance a disk as two would, faster or slower, but the objective
    sets the runs up through the same Setup: state size 2 + 3 + 2 + 3 = 10."""
    three = dataclasses.replace(setup, n=3)
    p, y0 = three.run_inputs(mass=0.01, eps_bar=0.012, beta=1.0, phi0_deg=(40.0, 45.0, 200.0),
                             kinematics="printed")
    assert y0.shape == (10,) and p[layout.P_FIXED.index("n")] == 3
    objective = balance_time_objective(three, kinematics="printed", eps_bar=0.012,
                                       phi0_deg=(40.0, 45.0, 200.0), censored_penalty=2.0)
    t = objective(np.array([[1.0, 0.01]]))
    assert 0 < t[0] < three.criterion.t_end


def test_balancer_ga_is_deterministic_for_a_seed(setup):
    objective = balance_time_objective(setup, kinematics="printed", eps_bar=0.012,
                                       phi0_deg=IC1, censored_penalty=2.0)
    a, b = (tune_balancer(objective, (0.1, 1.0), (0.006, 0.02), pop_size=6, n_gen=3, seed=4)
            for _ in range(2))
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.history["best_f"], b.history["best_f"])
    assert 0.1 <= a.x[0] <= 1.0 and 0.006 <= a.x[1] <= 0.02


def test_the_ga_dataset_runs_all_problems_in_lockstep_with_the_results_of_separate_runs(setup):
    """ga_dataset runs the (eps_bar x IC) problems together, one batch of runs per generation;
    each optimum equals that of its problem's own GA."""
    ics = {"IC1": IC1, "IC3": (260.0, 265.0)}
    ds = ga_dataset(setup, kinematics=["printed"], eps_bars=[0.012, 0.02], ics=ics,
                    beta_bounds=(0.1, 1.0), mass_bounds=(0.006, 0.02), pop_size=6, n_gen=3,
                    seed=4, censored_penalty=2.0)
    for eps_bar in (0.012, 0.02):
        for ic, phi0 in ics.items():
            objective = balance_time_objective(setup, kinematics="printed", eps_bar=eps_bar,
                                               phi0_deg=phi0, censored_penalty=2.0)
            alone = tune_balancer(objective, (0.1, 1.0), (0.006, 0.02), pop_size=6, n_gen=3,
                                  seed=4)
            at = ds.sel(eps_bar=eps_bar).isel(kinematics=0, ic=list(ics).index(ic))
            assert float(at.beta_opt) == alone.x[0] and float(at.mass_opt) == alone.x[1]
            assert float(at.balance_time_opt) == alone.f


def test_a_ga_that_never_balances_keeps_no_penalty_as_a_time(setup):
    """With runs of 0.3 s (before any balance) every run is censored: the GA's optimum and
    its history are NaN (the penalty 2 t_end is never stored as a time), flagged censored, and
    the comparison calls such a number UNDETERMINED rather than comparing it."""
    short = dataclasses.replace(setup, criterion=dataclasses.replace(setup.criterion,
                                                                      t_end=0.3))
    ds = ga_dataset(short, kinematics=["printed"], eps_bars=[0.012], ics={"IC1": IC1},
                    beta_bounds=(0.1, 1.0), mass_bounds=(0.006, 0.02), pop_size=4, n_gen=2,
                    seed=4, censored_penalty=2.0)
    assert np.isnan(ds.balance_time_opt).all() and np.isnan(ds.best_balance_time).all()
    assert (ds.censored == 1).all()
    assert verdict(5.0, float(ds.balance_time_opt.squeeze())) == (None, "UNDETERMINED")


def test_a_ga_claim_inside_the_seed_spread_is_undetermined():
    """ga_rows decides "the optimum beta lies in [0.1, 0.2]" only when every seed's optimum
    falls on the same side of the band's edge; the margin is measured to the upper edge only,
    the lower one being the GA's own bound."""
    import xarray as xr

    from rotorvib.comparison.verdicts import claim_verdict
    from rotorvib.papers.b.claims import ga_rows

    def ga(by_seed):
        by_seed = np.asarray(by_seed, float).reshape(1, 1, 1, -1)
        dims = ("kinematics", "eps_bar", "ic")
        return xr.Dataset(
            {"beta_opt": (dims, by_seed[..., 0]), "mass_opt": (dims, [[[0.006]]]),
             "balance_time_opt": (dims, [[[4.0]]]), "censored": (dims, [[[0]]]),
             "beta_opt_by_seed": (dims + ("seed",), by_seed)},
            coords={"kinematics_name": ("kinematics", ["printed"]), "eps_bar": [0.012],
                    "ic_name": ("ic", ["IC1"])},
            attrs={"summary": "pymoo GA, population 20, 20 generations"})

    bounds = {"mass": [0.006, 0.02], "beta": [0.1, 1.0]}

    def verdict(by_seed):
        row = ga_rows(ga(by_seed), "printed", bounds, (0.1, 0.2))[0]
        return claim_verdict(row.holds), row.margin

    assert verdict([0.15, 0.151, 0.149, 0.15, 0.15])[0] == "SUPPORTED"
    assert verdict([0.3, 0.3, 0.31, 0.29, 0.3])[0] == "NOT SUPPORTED"
    word, margin = verdict([0.19, 0.12, 0.35, 0.15, 0.18])     # 0.01 inside, one seed 0.15 out
    assert word == "UNDETERMINED"
    assert margin.value == pytest.approx(0.01) and margin.uncertainty == pytest.approx(0.16)
    assert verdict([0.1, 0.1, 0.12, 0.1, 0.1])[0] == "SUPPORTED"      # at the bound: inside
