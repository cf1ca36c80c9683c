"""What the GA's optimum is (beyond paper B): the whirl's envelope after the run-up, its line on
a log scale, the exact split of a change of balance time, and the comparison row."""

import math

import numpy as np
import pytest
import xarray as xr

from rotorvib.io.coords import label_coord
from rotorvib.papers.b.ga_law import (
    NEIGHBOURS,
    amplitude_share,
    envelope,
    fit_decay,
    ga_law_dataset,
    ga_law_rows,
    split_change,
)
from rotorvib.papers.b.setup import Setup

R_THR = 1e-4


def test_the_envelope_and_its_line_recover_a_decaying_whirl():
    """A whirl of 100 rad/s under an envelope A exp(-sigma (t - t0)): the crests of 0.2 s bins
    lie on the envelope, and the line through them gives A and sigma."""
    t = np.arange(0.0, 8.0, 1e-3)
    a, sigma, t0 = 2e-3, 0.9, 0.5
    r = a * np.exp(-sigma * (t - t0)) * np.abs(np.cos(100.0 * t))
    times, env = envelope(t, r, 1.5, 0.2)
    assert times.size == 32 and np.all((times >= 1.5) & (times < 7.9))
    fitted_sigma, fitted_a, residual = fit_decay(times, env, t0)
    assert fitted_sigma == pytest.approx(sigma, rel=1e-3)
    assert fitted_a == pytest.approx(a, rel=2e-3)
    assert residual < 2e-3
    with pytest.raises(ValueError, match="fewer than three bins of 0.2 s"):
        envelope(t, r, 7.5, 0.2)
    monotone = a * np.exp(-sigma * (t - t0))            # no crest: the bins' largest samples
    times, env = envelope(t, monotone, 1.5, 0.2)
    np.testing.assert_allclose(times[:3], [1.5, 1.7, 1.9], atol=1e-9)
    assert fit_decay(times, env, t0)[0] == pytest.approx(sigma, rel=1e-9)


def test_the_change_of_the_lines_time_splits_exactly_into_amplitude_and_rate():
    """t_n - t_o of the line t_ramp + ln(A / r_thr) / sigma equals the amplitude term plus the
    rate term, for any amplitudes and rates; equal rates leave only the amplitude term."""
    rng = np.random.default_rng(3)
    amplitude = rng.uniform(1e-4, 1e-2, (5, 4))
    sigma = rng.uniform(0.3, 2.0, (5, 4))
    line = 0.5 + np.log(amplitude / R_THR) / sigma
    amp, rate = split_change(amplitude, sigma, R_THR)
    np.testing.assert_allclose(amp + rate, line - line[:, :1], rtol=0, atol=1e-12)
    amp, rate = split_change(amplitude, np.ones_like(sigma), R_THR)
    assert np.all(rate == 0) and amp[0, 1] == pytest.approx(np.log(amplitude[0, 1]
                                                                   / amplitude[0, 0]))


def _ga(beta, mass):
    """A GA dataset of one problem: printed kinematics, eps_bar = 0.012, IC1."""
    dims = ("kinematics", "eps_bar", "ic")
    return xr.Dataset(
        {"beta_opt": (dims, [[[beta]]]), "mass_opt": (dims, [[[mass]]])},
        coords={"eps_bar": ("eps_bar", [0.012], {"long_name": "eps_bar", "units": "1"}),
                **label_coord("kinematics", ["printed"], "kinematics"),
                **label_coord("ic", ["IC1"], "initial condition")})


@pytest.fixture(scope="module")
def around(config):
    """The whirl around (beta, m) = (0.3, 10 g), away from the existence bound (6 g)."""
    b = config["paper_b"]
    setup = Setup.from_paper_b(b)
    return ga_law_dataset(setup, _ga(0.3, 0.01), b["initial_conditions"], [0.1, 1.0],
                          [0.006, 0.02], step=0.1, settle=1.0, horizon=8.0, width=0.2,
                          neutral=b["marginal_growth"])


def test_around_an_optimum_the_fitted_line_is_the_slowest_mode_and_the_integration(around):
    """Away from the existence bound the envelope's decay rate is the slowest eigenvalue's
    (an independent computation: a fit to a trajectory against the linearisation) within 2 %,
    and the line's balance time is the integration's within 0.05 s at every neighbour."""
    np.testing.assert_allclose(around.sigma_fit, around.sigma_eigen, rtol=0.02)
    np.testing.assert_allclose(around.line_time, around.balance_time, atol=0.05)
    assert float(around.fit_residual.max()) < 0.05
    factors = np.array(list(NEIGHBOURS.values()))
    np.testing.assert_allclose(around.beta.values.ravel(), 0.3 * (1 + 0.1 * factors[:, 0]))
    np.testing.assert_allclose(around.mass.values.ravel(), 0.01 * (1 + 0.1 * factors[:, 1]))
    assert around.in_box.values.ravel().tolist() == [1, 1, 1, 1]


def test_the_row_says_which_term_makes_the_optimum(around):
    """Equal amplitudes at every neighbour leave only the rate term: the row does not hold;
    equal rates leave only the amplitude term: it holds with the largest margin, 1/2."""
    def with_terms(amplitude, sigma):
        amp, rate = split_change(amplitude, sigma, R_THR)
        line = float(around.t_ramp) + np.log(amplitude / R_THR) / sigma
        return around.assign(amplitude=(around.amplitude.dims, amplitude),
                             sigma_fit=(around.sigma_fit.dims, sigma),
                             amplitude_term=(around.amplitude.dims, amp),
                             rate_term=(around.amplitude.dims, rate),
                             line_time=(around.amplitude.dims, line))

    a, s = around.amplitude.values, around.sigma_fit.values
    (by_rate,) = ga_law_rows(with_terms(np.broadcast_to(a[..., :1], a.shape).copy(),
                                        s * np.array([1.0, 0.9, 1.1, 0.95])), flat=0.0)
    assert by_rate.margin.value == pytest.approx(-0.5) and by_rate.holds == (("flat = 0 s",
                                                                               False),)
    (by_amplitude,) = ga_law_rows(with_terms(a * np.array([1.0, 2.0, 1.5, 1.2]),
                                             np.broadcast_to(s[..., :1], s.shape).copy()),
                                  flat=0.0)
    assert by_amplitude.margin.value == pytest.approx(0.5) and by_amplitude.holds[0][1]
    assert "the optimum leaves the least whirl of its neighbours in 1 of 1 problems" in \
        by_amplitude.explanation
    (real,) = ga_law_rows(around, flat=1e-3)
    assert "heavier" not in real.explanation and "Heavier balls (+10%)" in real.explanation
    # a flat change (no term carries it) is left out, and counted
    flat = with_terms(np.broadcast_to(a[..., :1], a.shape).copy(),
                      np.broadcast_to(s[..., :1], s.shape).copy())
    t = around.balance_time.values
    flat = flat.assign(balance_time=(around.balance_time.dims,
                                     np.broadcast_to(t[..., :1], t.shape).copy()))
    (none,) = ga_law_rows(flat, flat=1e-5)
    assert none.holds == (("flat = 1e-05 s", None),)
    assert "all 3 neighbours whose change is flat, within 1e-05 s, left out" in none.explanation


def test_terms_that_cancel_to_a_flat_change_carry_no_share(around):
    """Two large terms cancelling where the integrated balance time hardly moves (paper B's
    flat IC2 optima: a few tenths of a millisecond) have no share to give: left out as flat at
    the used 1 ms, counted at 1e-5 s (each then near 1/2); the row names both values."""
    amp = np.array([0.0, 0.05, 0.05, 0.05]).reshape(around.amplitude.shape)
    rate = -amp + np.array([0.0, 2e-3, 3e-3, 4e-3]).reshape(amp.shape)
    times = float(around.balance_time.values.ravel()[0]) + np.array([0.0, 4e-4, 3e-4, 8e-4])
    cancelling = around.assign(amplitude_term=(around.amplitude.dims, amp),
                               rate_term=(around.amplitude.dims, rate),
                               balance_time=(around.amplitude.dims, times.reshape(amp.shape)))
    (row,) = ga_law_rows(cancelling, flat=1e-3, flat_alternatives=(1e-5,))
    assert [name for name, _ in row.holds] == ["flat = 0.001 s", "flat = 1e-05 s"]
    assert row.holds[0][1] is None and "all 3 neighbours whose change is flat" in row.explanation
    share, left_out = amplitude_share(cancelling, 1e-5)
    assert left_out == 0 and share.value == pytest.approx(0.05 / (0.05 + 0.047) - 0.5, abs=0.01)


def test_a_band_edge_the_study_shares_is_not_a_failure_edge():
    """beta_opt_range and the GA rows: a best beta at the studied range's lower end, 0.1, is
    measured only to the band's upper edge 0.2 (no value of the study can fall below 0.1);
    moving the studied range's end below the band (one choice) makes the lower edge count and
    flips the margin's sign for a value outside it."""
    from rotorvib.papers.b.curves import within_studied

    margin, text = within_studied([0.1, 0.15], (0.1, 0.2), (0.1, 1.0))
    assert margin == pytest.approx(0.05) and "0.1 is the studied range's own" in text
    assert within_studied([0.05, 0.15], (0.1, 0.2), (0.01, 1.0))[0] == pytest.approx(-0.05)
    assert within_studied([0.1], (0.1, 0.2), (0.1, 0.2))[0] == math.inf


def test_a_ga_claim_that_a_seed_decides_is_undetermined():
    """Two of five seeds outside the band: the margin lies inside its uncertainty; every seed
    inside: decided, however spread the seeds."""
    from rotorvib.comparison.reproduced import Margin
    from rotorvib.papers.b.claims import _seed_spread

    inside = 0.004                               # the optimum just inside [0.1, 0.2]
    by_seed = [0.004, 0.03, -0.02, -0.01, 0.05]  # two seeds outside
    assert Margin(inside, _seed_spread(inside, by_seed), "beta", "seeds").holds() is None
    assert Margin(inside, _seed_spread(inside, [0.004, 0.09, 0.05]), "beta", "s").holds()


def test_a_rise_with_a_censored_end_is_said_in_words_not_as_infinity():
    """A curve censored at its bottom rises by -inf in numbers: its row says so in words."""
    from rotorvib.papers.b.curves import rise, rise_text

    assert rise_text(rise([math.nan, 3.0])) == "censored at the bottom"
    assert rise_text(rise([1.0, math.nan])) == "censored at the top"
    assert rise_text(rise([math.nan, math.nan])) == "censored at both ends"
    assert rise_text(rise([1.0, 1.5])) == "+0.5 s"
