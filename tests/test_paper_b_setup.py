"""Paper B's run setup: one balance criterion from the config, every study set up by it,
balance-time studies generic over the varied parameter, the basin map, and the measures of a
balance-time curve with censored runs (the GA, the robust designs and the law have files of
their own)."""

import numpy as np
import pytest

from rotorvib.models.balancer.criteria import BalanceCriterion
from rotorvib.models.balancer.simulate import simulate
from rotorvib.papers.b.config_checks import study_problem
from rotorvib.papers.b.setup import RUN_PARAMETERS, Setup
from rotorvib.papers.b.studies import balance_study_dataset, basin_dataset, grid_dataset

IC1 = (40.0, 45.0)


def test_criterion_force_threshold_is_the_support_force_at_the_radius_threshold(config):
    b = config["paper_b"]
    c = BalanceCriterion.from_config(b["balance"], b["machine"]["k"])
    assert c.f_threshold == b["machine"]["k"] * b["balance"]["r_threshold"]
    assert c.times[-1] == pytest.approx(b["balance"]["t_end"])
    assert c.n_samples == round(b["balance"]["t_end"] / b["balance"]["sample_dt"]) + 1


def test_the_setup_runs_the_configured_integrator(config, setup):
    assert setup.tolerances == config["paper_b"]["balance"]["integrator"]


@pytest.mark.parametrize("fixed", [
    {"eps_bar": 0.012, "phi0_deg": [30.0, -30.0], "kinematics": "printed"},
    {"eps_bar": 0.004, "phi0_deg": [90.0, 10.0], "kinematics": "consistent", "speed": 150.0,
     "R": 0.08, "zeta": 0.02}])
def test_a_batch_of_inputs_is_each_run_s_own(setup, fixed):
    """The inputs built for a batch at once (the GA's) are bit for bit those of each run built
    and checked alone, over the GA's box and beyond it."""
    betas, masses = np.random.default_rng(3).uniform([0.01, 0.001], [5.0, 0.1], (500, 2)).T
    batch = setup.batch_inputs(masses=masses, betas=betas, **fixed)
    alone = [setup.run_inputs(mass=m, beta=b, **fixed) for b, m in zip(betas, masses)]
    assert len(batch) == len(alone) == 500
    assert all(np.array_equal(p, q) and np.array_equal(y, z)
               for (p, y), (q, z) in zip(batch, alone))


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
    assert dip_depth([6.0, 4.0, 5.0]) == 1.0
    # the lowest point an end: how far the interior stays above it, not 0 (undecidable)
    assert dip_depth([4.0, 5.0, 6.0]) == -1.0 and dip_depth([4.0, 4.5, 5.0, 6.0]) == -0.5
    assert dip_depth([np.nan, 4.0, 5.0]) == 1.0
    assert within([0.12, 0.18], (0.1, 0.2)) == pytest.approx(0.02)
    assert within([0.05, 0.15], (0.1, 0.2)) == pytest.approx(-0.05)


def test_tables_1_and_2_carry_the_papers_values_beside_ours_as_printed():
    """Each column the paper prints gets the paper's value, as printed, just before ours; a
    speed the paper does not print gets an empty cell."""
    from rotorvib.papers.b.row_values import beside_printed

    printed = {"table1_m_opt_220": "0.006", "table1_mean_time_220": "4.70",
               "table2_fmax_1": "201.8", "table2_decay_1": "8.5"}
    (t1, t1_unprinted) = beside_printed(
        [{"speed_rad_s": 220.0, "m_opt_kg": 0.006, "mean_balance_time_s": 3.81},
         {"speed_rad_s": 225.0, "m_opt_kg": 0.007, "mean_balance_time_s": 3.9}], "table1", printed)
    assert list(t1) == ["speed_rad_s", "m_opt_paper_kg", "m_opt_kg",
                        "mean_balance_time_paper_s", "mean_balance_time_s"]
    assert (t1["m_opt_paper_kg"], t1["mean_balance_time_paper_s"]) == ("0.006", "4.70")
    assert t1_unprinted["m_opt_paper_kg"] == ""
    (t2,) = beside_printed([{"row": 1, "force_max_N": 201.9, "force_decay_time_s": 8.1}],
                           "table2", printed)
    assert t2 == {"row": 1, "force_max_paper_N": "201.8", "force_max_N": 201.9,
                  "force_decay_time_paper_s": "8.5", "force_decay_time_s": 8.1}
