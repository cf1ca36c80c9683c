"""Configurations at the edges that stopped the workflow, found by the configuration fuzzer
(tests/schema_fuzz.py) and now run through to the comparison, saying what they could not
decide; each on synthetic data. Most are a configuration under which no run balances (paper B's
support damping zeta = 0.001 in the reduced configuration)."""

import numpy as np
import pytest
import xarray as xr

from rotorvib.comparison.verdicts import claim_verdict
from rotorvib.papers.b.curves import seconds_text
from rotorvib.papers.b.row_values import optimum_lead


def test_fig16s_optimum_loses_when_only_its_force_never_decays():
    """Decay times in s, the optimum last; NaN: no decay by t_end (later than any that does)."""
    assert optimum_lead([200.0, 120.0, 90.0], [8.1, 5.3, 4.6]) == (
        pytest.approx(5.3 / 4.6 - 1), 4.6)
    assert optimum_lead([200.0, 120.0, 90.0], [np.nan, 5.3, 4.6])[0] == pytest.approx(
        5.3 / 4.6 - 1)                                   # a slower row never decays: still best
    assert optimum_lead([200.0, 120.0, 90.0], [8.1, 5.3, np.nan]) == (-1.0, np.inf)
    lead, last = optimum_lead([200.0, 120.0, 90.0], [np.nan, np.nan, np.nan])
    assert np.isnan(lead) and last == np.inf            # nothing decays: nothing decided


def _no_runs():
    empty = np.zeros(0)
    return xr.Dataset(
        {name: ("run", empty) for name in ("balance_time", "predicted", "sigma", "t_peak",
                                           "m_bar", "beta", "relative_error")},
        coords={"source": ("run", np.array([], dtype=object)),
                "kinematics_name": ("run", np.array([], dtype=object))})


def test_the_laws_trend_rows_over_no_balanced_run_decide_nothing():
    from rotorvib.papers.b.law import TRENDS, trend_rows

    rows = trend_rows(_no_runs())
    assert [r.quantity for r in rows] == list(TRENDS)
    assert all(claim_verdict(r.holds) == "UNDETERMINED" for r in rows)


def test_the_law_figure_over_no_balanced_run_says_so():
    from rotorvib.papers.b.beyond_figures import balance_law

    fig = balance_law(_no_runs(), {})
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert texts and all("no run balanced by t_end" in t for t in texts)


def test_the_basin_distribution_of_a_case_that_never_balances_shows_zero():
    from rotorvib.papers.b.figures import basin_distribution

    phi = np.array([0.0, 180.0])
    basin = xr.Dataset(
        {"balance_time": (("kinematics", "case", "phi1", "phi2"), np.full((1, 1, 2, 2), np.nan)),
         "ic_balance_time": (("kinematics", "case", "ic"), np.full((1, 1, 1), np.nan)),
         "case_beta": ("case", [0.2]), "case_mass": ("case", [0.01])},
        coords={"kinematics_name": ("kinematics", ["printed"]), "phi1": phi, "phi2": phi,
                "ic_name": ("ic", ["IC1"])}, attrs={"eps_bar": 0.012})
    fig = basin_distribution(basin, {})
    assert "(balanced by t_end: 0%)" in fig.axes[0].get_legend_handles_labels()[1][0]


def test_a_run_up_shorter_than_the_sample_step_is_over_by_the_first_sample():
    from rotorvib.papers.b.row_values import runup_end

    assert runup_end([50.0, 50.0, 50.0, 0.0, 0.0]) == 3
    assert runup_end([0.0, 0.0, 0.0]) == 1        # paper_b.speed.t_ramp below sample_dt


def test_table1_keeps_the_papers_speeds_whatever_the_configuration_runs():
    from rotorvib.comparison.reproduced import Reproduced
    from rotorvib.papers.b.row_values import table1_at_paper_speeds

    paper = {"table1_m_opt_200": 0.006, "table1_mean_time_200": 4.7,
             "table1_m_opt_210": 0.006, "table1_mean_time_210": 4.4,
             "table1_mean_time_220_within_uncertainty": None}
    made = [Reproduced.of("B", f"table1_{q}_{s}", 1.0, "run") for s in (20, 210)
            for q in ("m_opt", "mean_time")]
    rows = {r.quantity: r for r in table1_at_paper_speeds(made, paper)}
    assert set(rows) == {"table1_m_opt_200", "table1_mean_time_200", "table1_m_opt_210",
                         "table1_mean_time_210"}                 # none at 20 rad/s
    assert np.isnan(rows["table1_m_opt_200"].reproduced)
    assert rows["table1_m_opt_210"].reproduced == 1.0
    assert "does not run the paper's speed" in rows["table1_mean_time_200"].explanation


def test_a_reduction_from_nothing_is_no_number():
    from rotorvib.papers.b.row_values import reduction

    assert reduction(90.0, 200.0) == pytest.approx(55.0)
    assert np.isnan(reduction(0.0, 0.0)) and np.isnan(reduction(1.0, 0.0))
    assert np.isnan(reduction(np.nan, 4.6))


def test_the_law_figure_where_the_law_predicts_no_balanced_run_says_so():
    """Found by the fuzzer: a balance threshold of 0.1 m balances every run at once, and the law
    (a decay from the passage's peak) predicts none of them."""
    from rotorvib.papers.b.beyond_figures import balance_law

    nan = np.full(2, np.nan)
    law = xr.Dataset(
        {"balance_time": ("run", np.zeros(2)), "predicted": ("run", nan),
         "relative_error": ("run", nan)},
        coords={"source": ("run", ["balance_beta"] * 2),
                "kinematics_name": ("run", ["printed"] * 2)})
    texts = [t.get_text() for ax in balance_law(law, {}).axes for t in ax.texts]
    assert texts and all("the law predicts none of the balanced runs" in t for t in texts)


def test_a_censored_time_reads_as_words_not_nan():
    """Fig 11's beta = 0.1 run under the consistent kinematics never balances: its row said
    'beta0.1 nan s'; a time that never comes is said so."""
    assert seconds_text(4.904) == "4.90 s"
    assert seconds_text(float("nan")) == "not balanced by t_end"
    assert seconds_text(float("nan"), "none by t_end") == "none by t_end"
