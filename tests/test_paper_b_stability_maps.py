"""Paper B's stability maps: exact onsets of stability and marginal points."""

import numpy as np
import pytest

from rotorvib.papers.b.stability_maps import growth_rate, stability_dataset

FIG2 = dict(m_bar=0.01, eps_bar=0.012, zeta=0.01)


def bisect(f, lo, hi, tol=1e-6):
    """Plain bisection of a sign change of ``f`` on ``[lo, hi]`` (f(lo) >= 0 > f(hi))."""
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) >= 0 else (lo, mid)
    return 0.5 * (lo + hi)


def test_onsets_agree_with_bisection_of_the_growth_rate():
    betas = np.array([0.2, 0.5, 1.0, 2.0])
    omega = np.linspace(0.05, 4.0, 12)  # a coarse grid: the onset lies between its points
    ds = stability_dataset(**FIG2, beta=betas, omega_bar=omega, where="test", marginal=1e-9)
    for i, beta in enumerate(betas):
        onset = float(ds.stability_onset[i])
        assert np.isfinite(onset)
        expected = bisect(lambda w: float(growth_rate(0.01, 0.012, 0.01, beta, w)), 0.05, 4.0)
        assert onset == pytest.approx(expected, abs=1e-4)
        # the grid alone would only place it within one step
        assert abs(onset - omega[np.argmax(ds.state.values[i] == 1)]) < omega[1] - omega[0]


def test_no_onset_without_damping():
    ds = stability_dataset(**FIG2, beta=np.array([0.0]), omega_bar=np.linspace(0.05, 4, 40),
                           where="test", marginal=1e-9)
    assert np.isnan(float(ds.stability_onset[0])) and not (ds.state.values == 1).any()


def test_the_existence_bound_is_marginal_not_stable():
    """At m_bar = eps_bar/2 (rho = 1/2, eq. 34) the balls lie on top of each other and the growth
    rate is zero up to round-off: the point is marginal, not classified by the round-off."""
    ds = stability_dataset(m_bar=np.array([0.006, 0.01]), eps_bar=0.012, zeta=0.01, beta=1.0,
                           omega_bar=np.linspace(1.5, 4.0, 6), where="test", marginal=1e-9)
    assert np.all(np.abs(ds.growth_rate.values[0]) < 1e-12)
    assert np.all(ds.state.values[0] == 3) and np.all(ds.state.values[1] == 1)
