"""Paper B's run setup: one balance criterion from the config, every study and the GA objective
set up by it, balance-time studies generic over the varied parameter."""

import dataclasses

import numpy as np
import pytest

from rotorvib.comparison import verdict
from rotorvib.models.balancer import engine
from rotorvib.models.balancer.simulate import BalanceCriterion, metric, run, simulate
from rotorvib.papers.b.optimise import balance_time_objective, ga_dataset, tune_balancer
from rotorvib.papers.b.config_checks import study_problem
from rotorvib.papers.b.setup import RUN_PARAMETERS, Setup
from rotorvib.papers.b.studies import balance_study_dataset, basin_dataset, grid_dataset

IC1 = (40.0, 45.0)


@pytest.fixture(scope="module")
def setup(config):
    """Paper B's setup from the configuration, with 8 s runs (every run below balances)."""
    s = Setup.from_paper_b(config["paper_b"])
    return dataclasses.replace(s, criterion=dataclasses.replace(s.criterion, t_end=8.0))


def test_criterion_force_threshold_is_the_support_force_at_the_radius_threshold(config):
    b = config["paper_b"]
    c = BalanceCriterion.from_config(b["balance"], b["machine"]["k"])
    assert c.f_threshold == b["machine"]["k"] * b["balance"]["r_threshold"]
    assert c.times[-1] == pytest.approx(b["balance"]["t_end"])
    assert c.n_samples == round(b["balance"]["t_end"] / b["balance"]["sample_dt"]) + 1


def test_the_setup_runs_the_configured_integrator(config, setup):
    assert setup.tolerances == config["paper_b"]["balance"]["integrator"]


def test_run_parameters_match_the_schema(schema):
    assert set(schema["$defs"]["run_parameter"]["enum"]) == set(RUN_PARAMETERS)


@pytest.mark.parametrize("study, problem", [
    ({"axis": "beta", "fixed": {"mass": 0.01, "eps_bar": 0.01}}, None),
    ({"axis": "beta", "each": {"eps_bar": [0.01]}, "fixed": {"mass": 0.01}}, None),
    ({"axis": "beta", "fixed": {"mass": 0.01}}, "['eps_bar'] missing"),
    ({"axis": "beta", "fixed": {"beta": 1.0, "mass": 0.01, "eps_bar": 0.01}},
     "['beta'] given more than once"),
])
def test_study_problems_name_the_parameter(study, problem):
    found = study_problem(study)
    assert found == problem or (problem is not None and problem in found)


def test_study_runs_are_the_public_simulate_runs(setup):
    """A balance-time study over eps_bar gives, point by point, the result of the public
    ``simulate`` on the same balancer (an independent route through the API)."""
    eps = [0.004, 0.012]
    ds = balance_study_dataset(setup, kinematics=["printed"], ics={"IC1": IC1}, axis="eps_bar",
                               values=eps, fixed={"beta": 1.0, "mass": 0.01}, where="test")
    assert ds.balance_time.dims == ("kinematics", "ic", "eps_bar")
    assert ds.eps_bar.attrs["long_name"] == RUN_PARAMETERS["eps_bar"][0]
    c = setup.criterion
    for j, e in enumerate(eps):
        b = setup.balancer(mass=0.01, eps_bar=e, beta=1.0)
        res = simulate(b, setup.profile("printed"), np.radians(IC1), c.t_end, r0=setup.r0,
                       theta0=setup.theta0, sample_dt=c.sample_dt, r_threshold=c.r_threshold,
                       **setup.tolerances)
        assert float(ds.balance_time[0, 0, j]) == res.balance_time
        assert float(ds.force_max[0, 0, j]) == res.force_max
    assert float(ds.balance_time[0, 0, 1]) != float(ds.balance_time[0, 0, 0])  # eps_bar varied


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
    assert y0.shape == (10,) and p[engine.P_FIXED.index("n")] == 3
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


def test_basin_map_is_run_on_half_the_grid_and_mirrors_the_full_one(setup, monkeypatch):
    """Identical balls: swapping them leaves the run unchanged, so the basin map computed on
    phi1 <= phi2 and mirrored equals the map computed on every point (to round-off), with
    n (n + 1) / 2 runs instead of n^2."""
    n, counted = 6, []
    runs = setup.runs

    def counting(inputs, **kwargs):
        counted.append(len(inputs))
        return runs(inputs, **kwargs)

    monkeypatch.setattr(Setup, "runs", lambda self, inputs, **kw: counting(inputs, **kw))
    half = basin_dataset(setup, kinematics=["printed"], cases=[(0.2, 0.006)], n=n,
                         eps_bar=0.012, ics={"IC1": (60.0, 120.0)})
    angles = half.phi1.values

    def make_inputs(kinematics, case, phi1, phi2):
        return setup.run_inputs(mass=0.006, eps_bar=0.012, beta=0.2, phi0_deg=(phi1, phi2),
                                kinematics=kinematics)

    full = grid_dataset(setup, {"kinematics": ["printed"], "case": [0], "phi1": angles,
                                "phi2": angles}, half.coords, make_inputs, half.attrs)
    assert counted == [n * (n + 1) // 2, 1, n * n]   # the map, the paper's IC, the full map
    # the IC lies on the grid here: its run is the map's at (60, 120)
    assert float(half.ic_balance_time[0, 0, 0]) == float(half.balance_time[0, 0, 1, 2])
    assert np.all(half.balanced.values == 1)
    np.testing.assert_allclose(half.balance_time.values, full.balance_time.values, atol=1e-7)
    np.testing.assert_array_equal(half.balance_time.values[0, 0],
                                  half.balance_time.values[0, 0].T)


def test_the_share_balanced_by_a_time_counts_censored_runs_as_never():
    from rotorvib.papers.b.curves import share_balanced_by

    times = np.array([[1.0, 2.0], [np.nan, 3.0]])
    assert [share_balanced_by(times, t) for t in (0.5, 1.0, 2.5, 3.0, 1e9)] == \
        [0.0, 0.25, 0.5, 0.75, 0.75]


def test_an_ic_is_typical_when_its_share_lies_in_the_band():
    """faster_share places a censored IC after every balanced run; basin_rows holds only when
    every IC of every case lies within the band, under each kinematics."""
    import xarray as xr

    from rotorvib.papers.b.claims import basin_rows
    from rotorvib.papers.b.curves import faster_share

    times = np.array([[1.0, 2.0], [np.nan, 3.0]])
    assert faster_share(times, np.nan) == 0.75 and faster_share(times, 2.0) == 0.5
    grid = np.arange(1.0, 101.0).reshape(1, 1, 10, 10)
    basin = xr.Dataset(
        {"balance_time": (("kinematics", "case", "phi1", "phi2"), grid),
         "ic_balance_time": (("kinematics", "case", "ic"), [[[20.0, 50.0, 90.0]]])},
        coords={"kinematics_name": ("kinematics", ["printed"]), "case_beta": ("case", [0.2]),
                "case_mass": ("case", [0.006]), "ic_name": ("ic", ["IC1", "IC2", "IC3"])})
    (row,) = basin_rows(basin, "printed", (0.1, 0.95))
    assert row.holds == (("", True),) and "IC1 20%, IC2 50%, IC3 90%" in row.explanation
    assert row.margin.value == pytest.approx(0.05) and row.margin.uncertainty == 0.01
    (row,) = basin_rows(basin, "printed", (0.25, 0.9))
    assert row.holds == (("", False),)
    # IC3 at 90 % on the edge of the band: within one grid cell (1 %), nothing is decided
    (row,) = basin_rows(basin, "printed", (0.1, 0.9))
    assert row.holds == (("", None),)


def test_the_robust_objectives_are_the_mean_time_and_the_worst_force_of_direct_runs(setup):
    """Each design's two objectives against the same runs made one by one."""
    from rotorvib.papers.b.pareto import design_runs, initial_positions, robust_objectives

    phi = initial_positions(3, seed=1)
    assert phi.shape == (3, 2) and np.all((phi >= 0) & (phi < 360))
    designs = np.array([[0.2, 0.006], [1.0, 0.02]])
    f = robust_objectives(design_runs(setup, phi, kinematics="printed", eps_bar=0.012,
                                      speed=220.0), censored_time=16.0)(designs)
    for (beta, mass), (mean_time, worst_force) in zip(designs, f):
        runs = [run(engine.FIXED, *setup.run_inputs(mass=mass, beta=beta, eps_bar=0.012,
                                                    phi0_deg=tuple(p), kinematics="printed",
                                                    speed=220.0),
                    setup.criterion, **setup.tolerances) for p in phi]
        assert not any(r.censored for r in runs)
        assert mean_time == pytest.approx(np.mean([r.balance_time for r in runs]), rel=1e-12)
        assert worst_force == pytest.approx(max(r.force_max for r in runs), rel=1e-12)


def test_the_gap_to_the_front_is_measured_at_no_more_force():
    """A design is on the front when its gap is within the standard error of its mean."""
    import xarray as xr

    from rotorvib.papers.b.pareto import gap_to_front, pareto_rows, standard_errors

    times = np.array([[4.0, 4.8, 4.4, 4.4], [2.0] * 4, [3.0, 3.1, 2.9, 3.12]])
    ds = xr.Dataset(
        {"front_balance_time": ("front", [3.0, 4.0, 5.0]), "front_force": ("front", [90, 80, 70]),
         "front_beta": ("front", [0.2, 0.5, 1.0]), "front_mass": ("front", [0.006] * 3),
         "design_balance_time": ("design", times.mean(axis=1)),
         "design_times": (("design", "position"), times),
         "design_force": ("design", [85.0, 200.0, 95.0]),
         "design_beta": ("design", [0.4, 1.0, 0.2]), "design_mass": ("design", [0.01] * 3)},
        coords={"design": [1, 2, 3]}, attrs={"kinematics": "printed"})
    np.testing.assert_allclose(gap_to_front(ds), [0.4, 0.0, 0.03])
    np.testing.assert_allclose(standard_errors(ds)[0], np.std([4.0, 4.8, 4.4, 4.4], ddof=1) / 2)
    (row,) = pareto_rows(ds)                         # 0.03 s gap, standard error 0.05 s
    assert row.holds == (("", None),) and "0.03 s slower" in row.explanation
    assert row.margin.value == pytest.approx(-0.03) and row.margin.unit == "s"
    ds["design_times"][2] = [3.03] * 4               # same mean, no spread: off the front
    (row,) = pareto_rows(ds)
    assert row.holds == (("", False),)
    ds["design_times"][2] = [2.5] * 4                # 0.5 s ahead of the front: efficient
    ds["design_balance_time"][2] = 2.5
    (row,) = pareto_rows(ds)
    assert row.holds == (("", True),) and row.margin.value == pytest.approx(0.5)


def test_an_uncertainty_run_without_a_time_has_none_and_the_closed_form_predicts_which(setup):
    """Ball masses below the existence bound m/M >= eps_bar/2 leave a residual whirl; the
    closed form (residual_whirl against the threshold) says which runs balance, and the engine
    agrees: a run that never balances has NaN times (never t_end, a cap), is flagged, and a
    nominal run gives the engine's own numbers; a case over fixed ICs averages over them."""
    from rotorvib.papers.b.uncertainty import residual_whirl, run_case

    case = {"beta": 0.2, "mass": 0.006, "eps_bar": 0.012, "speed": 220.0,
            "phi0_deg": (40.0, 45.0)}
    offsets = [0.0, -0.03, -0.1, -0.2]
    # R, zeta, r0, eps, mass, k offsets
    x = [[0.1, setup.zeta, 1e-3, 0.0, dm, 0.0] for dm in offsets]
    out = run_case(setup, x, case, kinematics="printed")
    whirl = residual_whirl(M=setup.M, n=setup.n, mass=0.006 * (1 + np.array(offsets)),
                           eps_bar=0.012, R=0.1, k=setup.k, zeta=setup.zeta, speed=220.0)
    assert whirl[0] == 0.0 and 0 < whirl[1] < setup.criterion.r_threshold < whirl[2] < whirl[3]
    np.testing.assert_array_equal(out["balanced"], whirl < setup.criterion.r_threshold)
    np.testing.assert_array_equal(np.isnan(out["balance_time"]), [False, False, True, True])

    def direct(phi):
        return run(engine.FIXED, *setup.run_inputs(mass=0.006, beta=0.2, eps_bar=0.012,
                                                   phi0_deg=phi, kinematics="printed",
                                                   speed=220.0), setup.criterion,
                   **setup.tolerances)

    assert out["balance_time"][0] == direct((40.0, 45.0)).balance_time
    assert out["force_max"][0] == direct((40.0, 45.0)).force_max
    ics = {**case, "ics": [(40.0, 45.0), (110.0, 115.0)]}
    mean = run_case(setup, [[0.1, setup.zeta, 1e-3, 0.0, 0.0, 0.0]], ics, kinematics="printed")
    assert mean["balance_time"][0] == pytest.approx(
        np.mean([direct(p).balance_time for p in ics["ics"]]), rel=1e-12)


def test_the_calibrated_band_of_R_is_where_every_force_matches():
    """Forces proportional to R, printed ones at R = 0.1: within 1 % every force matches for R
    in [0.099, 0.101], found between grid radii 0.005 apart; where no radius matches (another
    machine than the paper's: found by the configuration fuzzer), the grid's whole range, said
    so; a band that reaches the grid's end is an error."""
    import xarray as xr

    from rotorvib.papers.b.uncertainty import CALIBRATED, calibrated_band

    R = np.arange(0.05, 0.2001, 0.005)
    printed = np.array([200.0, 120.0, 90.0])
    forces = xr.Dataset({"force_max": (("kinematics", "case", "R"),
                                       (printed[:, None] * R / 0.1)[None])},
                        coords={"kinematics_name": ("kinematics", ["printed"]), "R": R})
    lo, hi, how = calibrated_band(forces, printed, kinematics="printed")
    assert (lo, hi, how) == (pytest.approx(0.099), pytest.approx(0.101), CALIBRATED)
    lo, hi, how = calibrated_band(forces, 3 * printed, kinematics="printed", tolerance=0.01)
    assert (lo, hi) == (R[0], R[-1])
    assert how == ("no R of the calibration reproduces Table 2's peak forces within 1% (closest "
                   "33.3% off): the calibration grid's whole range")
    with pytest.raises(ValueError, match="reaches the end"):
        calibrated_band(forces, printed, kinematics="printed", tolerance=0.6)


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


def test_a_design_with_a_censored_run_has_no_mean_and_decides_nothing():
    """No penalty stored as a time: a design one of whose runs never balanced has a NaN mean,
    is no match on the front, and the claim about the GA optimum is undetermined when it is
    that design."""
    import xarray as xr

    from rotorvib.papers.b.pareto import gap_to_front, pareto_rows

    times = np.array([[4.0, 4.8, 4.4, 4.4], [3.0, np.nan, 2.9, 3.1]])
    ds = xr.Dataset(
        {"front_balance_time": ("front", [3.0, np.nan, 5.0]),
         "front_force": ("front", [90, 60, 70]), "front_beta": ("front", [0.2, 0.5, 1.0]),
         "front_mass": ("front", [0.006] * 3), "front_censored": ("front", [0, 2, 0]),
         "design_balance_time": ("design", times.mean(axis=1)),
         "design_censored": ("design", np.isnan(times).sum(axis=1)),
         "design_times": (("design", "position"), times),
         "design_force": ("design", [65.0, 95.0]),
         "design_beta": ("design", [0.4, 0.2]), "design_mass": ("design", [0.01] * 2)},
        coords={"design": [1, 2]}, attrs={"kinematics": "printed"})
    assert np.isnan(ds.design_balance_time[1]) and gap_to_front(ds)[0] == 0.0  # the 60 N design has no mean
    (row,) = pareto_rows(ds)
    assert row.holds == (("", None),) and "1 of 4" in row.explanation
    assert verdict(None, None, holds=row.holds) == (None, "UNDETERMINED")


def test_curve_measures_order_a_censored_run_after_every_balanced_one():
    """rise and dip_depth on curves with censored runs (NaN): a censored run is longer than
    any balanced one; two censored ends decide nothing (NaN); largest_fall counts drops between
    balanced neighbours only."""
    from rotorvib.papers.b.curves import dip_depth, largest_fall, rise, within

    assert rise([4.0, 5.0, 4.5, 6.0]) == 2.0 and largest_fall([4.0, 5.0, 4.5, 6.0]) == 0.5
    assert rise([np.nan, 5.0, 6.0]) == -np.inf                 # slowest at the bottom
    assert rise([4.0, np.nan]) == np.inf
    assert np.isnan(rise([np.nan, 5.0, np.nan]))
    assert largest_fall([np.nan, 5.0, 6.0]) == 0.0 and largest_fall([np.nan, np.nan]) == 0.0
    assert largest_fall([6.0, np.nan, 5.0, 4.0]) == 1.0
    assert dip_depth([6.0, 4.0, 5.0]) == 1.0 and dip_depth([4.0, 5.0, 6.0]) == 0.0
    assert dip_depth([np.nan, 4.0, 5.0]) == 1.0
    assert within([0.12, 0.18], (0.1, 0.2)) == pytest.approx(0.02)
    assert within([0.05, 0.15], (0.1, 0.2)) == pytest.approx(-0.05)


def test_a_ga_claim_inside_the_seed_spread_is_undetermined():
    """ga_rows decides "the optimum beta lies in [0.1, 0.2]" only when every seed's optimum
    falls on the same side of the band's edge; the margin is measured to the upper edge only,
    the lower one being the GA's own bound."""
    import xarray as xr

    from rotorvib.comparison import claim_verdict
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


def test_the_law_uses_the_slowest_decaying_mode_and_predicts_a_run(setup):
    """The law's rate is minus the balanced state's growth rate (the stability maps') away
    from the existence bound; on the bound, where one mode is neutral, it is the slowest of the
    others. On Fig 7's balancer the law, from the run's force peak, gives its balance time
    within the comparison's 10 %."""
    from rotorvib.papers.b.law import balance_time_law, run_parameters, slow_decay_rate
    from rotorvib.papers.b.stability_maps import growth_rate

    m_bar, eps_bar, zeta, beta, omega_bar = 0.01, np.array([0.01, 0.02]), 0.01, 1.0, 2.0
    rate = slow_decay_rate(m_bar, eps_bar, zeta, beta, omega_bar, neutral=1e-9)
    growth = growth_rate(m_bar, eps_bar, zeta, beta, omega_bar)
    assert rate[0] == pytest.approx(-growth[0], rel=1e-12)          # inside the bound
    assert abs(growth[1]) < 1e-9 < rate[1]                         # on it: a neutral mode
    assert np.isnan(slow_decay_rate(m_bar, 0.03, zeta, beta, omega_bar, neutral=1e-9))
    result = run(engine.FIXED, *setup.run_inputs(mass=0.01, beta=1.0, eps_bar=0.01,
                                                 phi0_deg=(45.0, 90.0), kinematics="printed"),
                 setup.criterion, **setup.tolerances)
    wn = np.sqrt(setup.k / setup.M)
    sigma = float(slow_decay_rate(0.01 / setup.M, 0.01, setup.zeta, 1.0,
                                  setup.omega / wn, neutral=1e-9)) * wn
    law = balance_time_law(result.force_max_time, result.force_max,
                           setup.k * setup.criterion.r_threshold, sigma)
    assert law == pytest.approx(result.balance_time, rel=0.1)
    import xarray as xr
    ds = xr.Dataset({"balance_time": (("kinematics", "beta"), [[1.0, 2.0]])},
                    coords={"beta": [0.1, 0.2], "kinematics_name": ("kinematics", ["printed"])})
    values = run_parameters(ds, {"mass": 0.01, "eps_bar": 0.012, "speed": 200.0})
    assert values["beta"].values.tolist() == [[0.1, 0.2]] and values["mass"].shape == (1, 2)
    with pytest.raises(ValueError, match=r"\['speed'\] are neither coordinates nor fixed"):
        run_parameters(ds, {"mass": 0.01, "eps_bar": 0.012})


def _law_runs(sigma, t_peak, log_force, source="balance_mass", m_bar=None):
    import xarray as xr
    n = len(sigma)
    law = np.asarray(t_peak) + np.asarray(log_force) / np.asarray(sigma)
    return xr.Dataset(
        {"balance_time": ("run", law * (1 + 0.01 * np.cos(np.arange(n)))),
         "predicted": ("run", law), "sigma": ("run", np.asarray(sigma, float)),
         "t_peak": ("run", np.asarray(t_peak, float)),
         "m_bar": ("run", np.linspace(0.006, 0.02, n) if m_bar is None else m_bar)},
        coords={"source": ("run", [source] * n), "kinematics_name": ("run", ["printed"] * n)})


def test_the_factor_that_moves_the_balance_time_is_found():
    """Synthetic runs t = t_pk + L / sigma with one factor varying: that factor alone explains
    the times (share near 1), the others nothing; the mass row holds only when sigma varies
    and falls with the mass."""
    from rotorvib.comparison import claim_verdict
    from rotorvib.papers.b.law import factor_shares, trend_rows

    n = 40
    ramp = np.linspace(1.0, 3.0, n)
    flat = np.ones(n)
    by_sigma = _law_runs(1 / ramp, 0.5 * flat, 2.0 * flat)          # sigma falls with mass
    shares = factor_shares(by_sigma, np.arange(n))
    assert shares["sigma"] > 0.99 and shares["force"] < 0.05 and shares["t_peak"] < 0.05
    assert claim_verdict(trend_rows(by_sigma)[0].holds) == "SUPPORTED"
    by_force = _law_runs(flat, 0.5 * flat, ramp)
    assert factor_shares(by_force, np.arange(n))["force"] > 0.99
    assert claim_verdict(trend_rows(by_force)[0].holds) == "NOT SUPPORTED"
    rising = _law_runs(ramp, 0.5 * flat, 2.0 * flat)                # sigma rises with mass
    assert claim_verdict(trend_rows(rising)[0].holds) == "NOT SUPPORTED"


def test_support_damping_moves_the_decay_rate_and_beta_hardly():
    """At Fig 7's balancer (m_bar 0.01, eps_bar 0.01, beta 1, omega_bar 2): the elasticity of
    the slowest decay rate to the support damping is above 1 and to beta small; it predicts a
    finite change (zeta 20 % larger) within 1 %; the row holds."""
    import xarray as xr
    from rotorvib.comparison import claim_verdict
    from rotorvib.papers.b.law import decay_elasticities, slow_decay_rate, support_damping_rows

    one = {"m_bar": 0.01, "eps_bar": 0.01, "beta": 1.0, "omega_bar": 2.0}
    ds = xr.Dataset({k: ("run", [v, v]) for k, v in one.items()})
    e = {k: float(v[0]) for k, v in decay_elasticities(ds, 0.01, neutral=1e-9).items()}
    assert e["zeta"] > 1.0 and abs(e["beta"]) < 0.2 < abs(e["zeta"]) - abs(e["m_bar"])
    sigma = [float(slow_decay_rate(0.01, 0.01, z, 1.0, 2.0, neutral=1e-9)) for z in (0.01, 0.012)]
    assert sigma[1] / sigma[0] == pytest.approx(1.2 ** e["zeta"], rel=0.01)
    row = support_damping_rows(ds, 0.01, neutral=1e-9)[0]
    assert claim_verdict(row.holds) == "SUPPORTED"


def test_the_law_takes_the_rate_of_the_mode_that_carries_the_whirl():
    """For balls heavy against the unbalance (m_bar / eps_bar = 5) the slowest decaying mode is
    one of the balls alone (its share of the whirl about 0.002): r does not see it. The law
    takes the slowest mode with a share of the whirl above its threshold, a whirl mode (share
    0.8), whatever threshold between the two families; with a share of 0 it is the slowest of
    all, as before."""
    from rotorvib.papers.b.law import slow_decay_rate
    from rotorvib.papers.b.stability_maps import balanced_modes

    args = (0.01, 0.002, 0.01, 1.0, 2.0)
    eig, share = balanced_modes(*args)
    ball = np.argmax(eig.real)                                  # the slowest mode of all
    assert share[ball] < 0.01
    whirl = -np.max(eig.real[share > 0.5])
    assert float(slow_decay_rate(*args, neutral=1e-9)) == pytest.approx(-eig.real[ball])
    for threshold in (0.05, 0.1, 0.3):
        assert float(slow_decay_rate(*args, neutral=1e-9, share=threshold)) == whirl
    assert whirl > 5 * float(slow_decay_rate(*args, neutral=1e-9))


def test_the_law_row_is_evaluated_at_each_whirl_share_and_states_its_domain():
    """A constructed law dataset, two studies: one where the law is within 'close' and one
    where it is 40 % off at every share; the row names both, and depends on no share."""
    import xarray as xr

    from rotorvib.choices import Close
    from rotorvib.comparison import claim_verdict
    from rotorvib.papers.b.law import law_rows

    n = 40
    good = 0.03 * np.cos(np.arange(n))
    error = np.concatenate([good, np.full(n // 4, 0.4)])
    runs = error.size
    ds = xr.Dataset(
        {"relative_error": (("share", "run"), np.stack([error, error])),
         "relative_error_slowest": ("run", 2 * error),
         "m_bar": ("run", np.full(runs, 0.01)), "eps_bar": ("run", np.full(runs, 0.012)),
         "balance_time": ("run", np.linspace(3.0, 6.0, runs))},
        coords={"whirl_share": ("share", [0.1, 0.3]),
                "source": ("run", ["balance_beta"] * n + ["calibration"] * (n // 4))})
    (row,) = law_rows(ds, Close(0.1, (0.05,)), resamples=50)
    assert claim_verdict(row.holds) == "SUPPORTED" and len(row.holds) == 4
    assert "Within 10% at the median for balance_beta; not for calibration" in row.explanation
    assert any("whirl_share = 0.1" in c for c in row.choices)
