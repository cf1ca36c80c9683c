"""Paper B beyond the paper: the balance-time law (the passage's peak force and the decay rate
of the mode that carries the whirl), the factor that moves the time, and the law's row."""

import numpy as np
import pytest

from rotorvib.models.balancer import layout
from rotorvib.models.balancer.simulate import run


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
    result = run(layout.FIXED, *setup.run_inputs(mass=0.01, beta=1.0, eps_bar=0.01,
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
    from rotorvib.comparison.verdicts import claim_verdict
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

    from rotorvib.comparison.verdicts import claim_verdict
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

    from rotorvib.comparison.choices import Close
    from rotorvib.comparison.verdicts import claim_verdict
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
