"""Sobol indices recovered on the Ishigami function, whose indices are known in closed form
(Ishigami & Homma 1990; Sobol' & Levitan 1999), within their bootstrap intervals."""

import numpy as np
import pytest

from rotorvib.methods.sensitivity import problem, sample, sobol_indices

A, B = 7.0, 0.1


def ishigami(x):
    return np.sin(x[:, 0]) + A * np.sin(x[:, 1]) ** 2 + B * x[:, 2] ** 4 * np.sin(x[:, 0])


def exact_indices():
    """V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2; V1 = (1 + b pi^4/5)^2 / 2, V2 = a^2/8,
    V13 = b^2 pi^8 (1/18 - 1/50); V3 = 0."""
    v = A**2 / 8 + B * np.pi**4 / 5 + B**2 * np.pi**8 / 18 + 0.5
    v1, v2 = (1 + B * np.pi**4 / 5) ** 2 / 2, A**2 / 8
    v13 = B**2 * np.pi**8 * (1 / 18 - 1 / 50)
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def test_ishigami_indices_lie_within_their_intervals_and_tighten():
    spec = problem({name: (-np.pi, np.pi) for name in ("x1", "x2", "x3")})
    x = sample(spec, 2048, seed=3)
    assert x.shape == (2048 * 5, 3)
    s = sobol_indices(spec, ishigami(x), [256, 2048], resamples=200, seed=3)
    s1, st = exact_indices()
    for key, exact in (("S1", s1), ("ST", st)):
        error = np.abs(s[key][-1] - exact)
        assert np.all(error <= s[f"{key}_conf"][-1]), (key, s[key][-1], exact)
        assert np.all(s[f"{key}_conf"][-1] < s[f"{key}_conf"][0])      # more points, tighter


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="input 'x': range"):
        problem({"x": (1.0, 1.0)})
    spec = problem({"x": (0.0, 1.0), "y": (0.0, 1.0)})
    with pytest.raises(ValueError, match="power of 2"):
        sample(spec, 100, seed=0)
    with pytest.raises(ValueError, match="needs 32 outputs"):
        sobol_indices(spec, np.zeros(16), [8], resamples=10, seed=0)
    with pytest.raises(ValueError, match="y"):
        sobol_indices(spec, np.full(32, np.nan), [8], resamples=10, seed=0)


def test_a_study_dataset_states_its_band_and_dominant_input():
    """y = 10 x1 + x2 on the unit square: x1 dominates (ST = 100/101), the band of y spans
    [0.5, 10.45] at 5-95 %, and a value outside it is reported outside."""
    from rotorvib.methods.bands import band_statement
    from rotorvib.methods.sensitivity import study_dataset

    spec = problem({"x1": (0.0, 1.0), "x2": (0.0, 1.0)})
    x = sample(spec, 512, seed=1)
    y = 10 * x[:, 0] + x[:, 1]
    ds = study_dataset(spec, x, {"y": y}, {"y": 5.5}, {"y": "m"}, n_bases=[64, 512],
                       resamples=100, seed=1)
    assert ds.ST.values[0, -1, 0] == pytest.approx(100 / 101, abs=ds.ST_conf.values[0, -1, 0])
    np.testing.assert_allclose(ds.band.values[0], np.percentile(y, [5, 50, 95]))
    (margin, uncertainty), text = band_statement(ds, "y", 5.0)
    assert margin == pytest.approx(5.0 - ds.band.values[0, 0]) and margin > uncertainty > 0
    assert "largest total Sobol index: x1 (0.99 +/- 0.0" in text and "nominal 5.5" in text
    _, text = band_statement(ds.isel(n_base=[0]), "y", 5.0)             # 64 base points
    assert "the largest total Sobol index, x1 (1.01 +/- 0.26, 64 base points), is not " \
           "resolved within +/- 0.1" in text
    (margin, uncertainty), _ = band_statement(ds, "y", 12.0)
    assert margin == pytest.approx(ds.band.values[0, -1] - 12.0) and 0 < uncertainty < 1


def test_the_spread_of_a_band_edge_is_the_percentiles_standard_error():
    """For n uniform samples the p-quantile has standard error sqrt(p (1 - p) / n) (density
    1): the bootstrap spread of the 5 % and 95 % edges agrees within 15 %."""
    from rotorvib.methods.bands import percentile_spread

    y = np.random.default_rng(3).uniform(size=4000)
    spread = percentile_spread(y, [5.0, 95.0], resamples=400, seed=1)
    np.testing.assert_allclose(spread, np.sqrt(0.05 * 0.95 / 4000), rtol=0.15)


def test_a_design_that_cannot_be_run_is_named():
    from rotorvib.checks import sobol_design_problem

    assert sobol_design_problem(128, [32, 64, 128]) is None
    assert "96 base points: must be a power of 2" in sobol_design_problem(96, [32])
    assert "at most n_base = 64" in sobol_design_problem(64, [32, 128])


def test_an_output_that_does_not_vary_has_no_indices():
    """SALib gives 0 for a constant output; the variance shared out is 0/0: NaN, and the band
    statement says the output does not vary."""
    from rotorvib.methods.bands import band_statement
    from rotorvib.methods.sensitivity import study_dataset

    spec = problem({"x1": (0.0, 1.0), "x2": (0.0, 1.0)})
    x = sample(spec, 16, seed=1)
    ds = study_dataset(spec, x, {"y": np.ones(len(x))}, {"y": 1.0}, {"y": "1"}, n_bases=[16],
                       resamples=20, seed=1)
    assert np.all(np.isnan(ds.ST.values)) and np.all(np.isnan(ds.S1.values))
    (margin, uncertainty), text = band_statement(ds, "y", 1.0)
    assert margin == 0.0 and uncertainty == 0.0 and "does not vary" in text


def test_a_band_holds_no_capped_value_and_an_output_without_values_has_no_index():
    """y = x1 where x1 < 0.8, no value (NaN, a run that never balances) elsewhere: the band is
    that of the valued points only -- never a cap at some t_end -- n_valued counts them, and
    the indices, which need every point, are NaN; an index wider than +/- 0.1 is unresolved."""
    from rotorvib.methods.bands import RESOLVED_HALF_WIDTH, band_statement
    from rotorvib.methods.sensitivity import study_dataset

    spec = problem({"x1": (0.0, 1.0), "x2": (0.0, 1.0)})
    x = sample(spec, 256, seed=2)
    y = np.where(x[:, 0] < 0.8, x[:, 0], np.nan)
    ds = study_dataset(spec, x, {"t": y}, {"t": 0.5}, {"t": "s"}, n_bases=[256],
                       resamples=50, seed=1)
    valued = y[np.isfinite(y)]
    assert int(ds.n_valued[0]) == valued.size < y.size
    np.testing.assert_allclose(ds.band.values[0], np.percentile(valued, [5, 50, 95]))
    assert ds.band.values[0, -1] < 0.8                      # no capped value inside
    assert np.all(np.isnan(ds.ST.values))
    _, text = band_statement(ds, "t", 0.5)
    assert f"the {valued.size} of {y.size} input points where it has a value" in text
    assert "no Sobol index (it needs a value at every point)" in text
    assert RESOLVED_HALF_WIDTH == ds.attrs["sobol_resolved_half_width"] == 0.1


def test_an_output_no_point_of_which_has_a_value_decides_nothing():
    """Every run censored (found by the configuration fuzzer, tests/schema_fuzz.py: paper B's
    Fig 7 case at beta = 0.001 never balances): no band, a NaN margin with a NaN uncertainty,
    which the comparison counts UNDETERMINED, and a statement that says why."""
    from rotorvib.comparison.reproduced import Margin
    from rotorvib.methods.bands import band_statement, percentile_spread
    from rotorvib.methods.sensitivity import study_dataset

    spec = problem({"x1": (0.0, 1.0), "x2": (0.0, 1.0)})
    x = sample(spec, 16, seed=1)
    ds = study_dataset(spec, x, {"t": np.full(len(x), np.nan)}, {"t": np.nan}, {"t": "s"},
                       n_bases=[16], resamples=20, seed=1)
    assert np.all(np.isnan(percentile_spread(ds.y.values[0], [5.0, 95.0], resamples=20,
                                             seed=1)))
    (margin, uncertainty), text = band_statement(ds, "t", 9.04)
    assert np.isnan(margin) and np.isnan(uncertainty)
    assert f"none of the {len(x)} input points has a value" in text
    assert Margin(margin, uncertainty, "s", "bootstrap").holds() is None
    with pytest.raises(ValueError, match="uncertainty must be >= 0"):
        Margin(1.0, np.nan, "s", "bootstrap")
