"""Paper B's stability boundaries by continuation, against the grids' exact onsets, the
analytic limit beta -> inf and brute-force checks of the least balancing beta."""

import numpy as np
import pytest
import sympy as sp

from rotorvib.models.balancer import equations, stability
from rotorvib.papers.b.boundaries import (
    approach_limit,
    boundary_dataset,
    boundary_rows,
    exact_onset,
    onset,
)
from rotorvib.papers.b.boundary_limits import approach_coefficient, lowest_beta
from rotorvib.papers.b.stability_maps import growth_rate, stability_dataset

BASE = {"m_bar": 0.01, "eps_bar": 0.012, "zeta": 0.01, "beta": 1.0}
STEP = {"initial": 0.02, "min": 1e-7, "max": 0.5}


def plane(name, lo, hi, omega_max=20.0):
    return boundary_dataset(name, fixed={k: v for k, v in BASE.items() if k != name},
                            p_range=(lo, hi), start=BASE[name], omega_max=omega_max,
                            step=STEP, tol=1e-10, neutral=1e-9, window_samples=20000)


@pytest.fixture(scope="module")
def beta_plane():
    return plane("beta", 1e-4, 1e4, omega_max=50.0)


@pytest.mark.parametrize("name, lo, hi", [("beta", 0.05, 3.0), ("m_bar", 0.007, 0.05),
                                          ("zeta", 1e-3, 1.0)])
def test_boundary_points_are_the_grid_method_onsets(name, lo, hi):
    """Every traced point on the boundary within Fig 2/3-like ranges against the grid method
    of the maps (first unstable -> stable change over 400 speeds, then Brent) at its own
    parameter: the same speed within 1e-7."""
    ds = plane(name, lo / 2, hi * 2)
    inside = (ds[name].values >= lo) & (ds[name].values <= hi) & (ds.on_boundary.values == 1)
    values, traced = ds[name].values[inside], ds.omega_onset.values[inside]
    assert values.size >= 5
    args = {k: v for k, v in BASE.items() if k != name}
    speeds = np.linspace(0.05, 4.0, 400)
    growth = np.stack([growth_rate(omega_bar=speeds, **args, **{name: v}) for v in values])
    brent = stability.stability_onsets(
        lambda i, w: growth_rate(omega_bar=w, **args, **{name: values[i]}), speeds, growth,
        xtol=1e-12)
    np.testing.assert_allclose(traced, brent, atol=1e-7)
    assert np.max(np.abs(ds.crossing_real.values)) < 1e-9


def test_the_map_dataset_and_the_continuation_agree_at_the_start():
    """The start is the Fig 2 map's exact onset at beta = 1."""
    st = stability_dataset(m_bar=0.01, eps_bar=0.012, zeta=0.01, beta=np.array([0.5, 1.0]),
                           omega_bar=np.linspace(0.05, 4.0, 200), where="test", marginal=1e-9)
    ds = plane("beta", 0.1, 10.0)
    start = ds.isel(point=np.argmin(np.abs(ds.beta.values - 1.0)))
    assert float(start.beta) == pytest.approx(1.0, rel=1e-9)
    assert float(start.omega_onset) == pytest.approx(float(st.stability_onset[1]), abs=1e-7)


def test_reduced_ball_equation_changes_sign_at_the_critical_speed():
    """Symbolic: with the rotor eliminated quasi-statically (beta -> inf) the balls obey
    mu beta a' = -S a, S = K_ar K_rr^-1 K_ra; tr S = 2 Omega^4 mu^2 (1 - Omega^2) / D with
    D = (1 - Omega^2)^2 + 4 zeta^2 Omega^2 > 0: it vanishes at Omega = 1, the critical speed on
    the total-mass scale."""
    M, C, K = equations.pencil_matrices()
    S = K[2:, :2] * K[:2, :2].inv() * K[:2, 2:]
    mu, zeta, omega = equations.MU, equations.ZETA, equations.OMEGA
    D = (1 - omega**2) ** 2 + 4 * zeta**2 * omega**2
    assert sp.simplify(S.trace() - 2 * omega**4 * mu**2 * (1 - omega**2) / D) == 0


def test_onset_tends_to_the_critical_speed_as_one_over_beta(beta_plane):
    """omega_onset - omega_c = a / beta + O(1/beta^2): a from the top decade, and a point at
    beta = 1e4 on the curve within 1e-3 of the critical speed, above it."""
    a, spread = approach_coefficient(beta_plane)
    assert 0.3 < a < 0.6 and spread < 1e-3 * a * 10
    top = beta_plane.isel(point=np.argmax(beta_plane.beta.values))
    excess = float(top.omega_onset - top.critical_speed)
    assert 0 < excess < 1e-3
    assert excess * float(top.beta) == pytest.approx(a, rel=1e-2)
    assert float(top.frequency) == pytest.approx(0.466 / float(top.beta), rel=0.05)


def test_the_exact_onset_is_the_eigenvalues_onset_and_the_roots_cross_there():
    """At beta = 1e3, where doubles still resolve the growth rate, the onset by Routh's
    criterion in 50 digits is the eigenvalues' onset (Brent in doubles) within 1e-11; at
    beta = 1e6, where they do not, the roots of the characteristic polynomial (mpmath's
    polyroots, another method) have their largest real part change sign across it."""
    import mpmath

    fixed = {k: v for k, v in BASE.items() if k != "beta"}
    exact = exact_onset(fixed, 1e3, 2, digits=50)
    assert float(exact) == pytest.approx(onset("beta", fixed, 1e3, 50.0, 2, 20000), abs=1e-11)
    beta = 1e6
    at = exact_onset(fixed, beta, 2, digits=50)
    with mpmath.workdps(50):
        s = mpmath.sqrt(1 + 2 * mpmath.mpf(fixed["m_bar"]))

        def growth(omega):
            coefficients = stability.exact_characteristic_coefficients(
                fixed["m_bar"] / s**2, mpmath.mpf(fixed["m_bar"]) / fixed["eps_bar"],
                fixed["zeta"] / s, beta * s, omega * s)
            return max(mpmath.re(r) for r in mpmath.polyroots(coefficients, maxsteps=200,
                                                              extraprec=200))

        assert growth(at - mpmath.mpf(10) ** -30) > 0 > growth(at + mpmath.mpf(10) ** -30)


def test_the_asymptote_does_not_depend_on_the_arithmetic():
    """a from onsets in 50 and in 70 digits agree within 1e-12, far inside its error bound
    (about 1e-9), which is far inside the six digits the comparison prints."""
    fixed = {k: v for k, v in BASE.items() if k != "beta"}
    a, error = approach_limit(fixed, 2)
    a70, _ = approach_limit(fixed, 2, digits=70)
    assert abs(a - a70) < 1e-12 and 1e-11 < error < 1e-8
    assert round(a, 6) == round(a + error, 6) == round(a - error, 6)


def test_least_beta_balances_nowhere_below_and_somewhere_above(beta_plane):
    """Brute force over 4000 speeds up to 50: just below the least beta no speed is stable,
    just above it some are."""
    b_min, at, moves = lowest_beta(beta_plane)
    assert moves < 1e-2 * b_min and at > 40
    speeds = np.geomspace(0.5, 50.0, 4000)
    args = {k: v for k, v in BASE.items() if k != "beta"}
    assert (growth_rate(beta=0.98 * b_min, omega_bar=speeds, **args) > 0).all()
    assert (growth_rate(beta=1.05 * b_min, omega_bar=speeds, **args) < 0).any()


def test_rows_decide_on_the_whole_curve(beta_plane):
    rows = {r.quantity: r for r in boundary_rows({"beta": beta_plane,
                                                  "m_bar": plane("m_bar", 0.0061, 0.1),
                                                  "zeta": plane("zeta", 1e-3, 10.0)})}
    above = rows["boundary_above_critical"]
    assert above.holds == (("", True),)
    # the least excess over the critical speed is set by the traced range (a / beta at its
    # top, under 1e-3): the margin is a, the excess scaled by beta, which tends to a
    # the limit of beta (omega - omega_c), from exact onsets, and the traced points' fit agree
    a, spread = approach_coefficient(beta_plane)
    limit = float(beta_plane.asymptote_a)
    assert above.margin.value == limit and above.margin.unit == "beta x omega_bar"
    assert abs(limit - a) < 1e-3 and float(beta_plane.asymptote_error) < 1e-4
    assert "the margin is a, not the least excess" in above.explanation
    assert rows["boundary_lowest_beta"].holds == (("", True),)
    assert rows["boundary_lowest_beta"].margin.value == pytest.approx(9.53e-4, rel=2e-2)


def test_a_second_stable_window_above_the_critical_speed_for_heavy_balls():
    """Up to balls as heavy as the disk a second stable window opens just above the critical
    speed: traced as curve 1 from the range's top down to its tip (a fold in m_bar) and back.
    Checked by brute force on 200 000 speeds between the critical speed and 1.3 times it:
    no stable speed just below the tip's m_bar, a stable one just above."""
    ds = plane("m_bar", 0.007, 1.0)
    window = ds.isel(point=ds.curve.values == 1)
    assert set(np.unique(ds.curve.values)) == {0, 1}
    tip = int(np.argmin(window.m_bar.values))
    m_tip = float(window.m_bar[tip])
    assert 0.5 < m_tip < 0.65 and ds.fold_m_bar.size >= 1
    assert np.all(window.on_boundary.values == 1)
    assert np.all(window.omega_onset.values > window.critical_speed.values)
    assert np.max(np.abs(window.crossing_real.values)) < 1e-9
    args = {k: v for k, v in BASE.items() if k != "m_bar"}

    def stable_near_critical(m):
        w_c = 1 / np.sqrt(1 + 2 * m)
        return bool(np.any(growth_rate(m, omega_bar=np.linspace(w_c, 1.3 * w_c, 200_000),
                                       **args) < 0))

    assert not stable_near_critical(0.99 * m_tip) and stable_near_critical(1.01 * m_tip)
    rows = {r.quantity: r for r in boundary_rows({"beta": plane("beta", 1e-3, 10.0),
                                                  "m_bar": ds, "zeta": plane("zeta", 1e-3,
                                                                             1.0)})}
    assert "a second stable window" in rows["boundary_above_critical"].explanation


def test_no_boundary_to_start_from_below_the_least_beta():
    """Below the least balancing beta (about 9.5e-4) no speed turns the balanced state
    stable: tracing cannot start there, and says why."""
    from rotorvib.papers.b.boundaries import onset

    fixed = {k: v for k, v in BASE.items() if k != "beta"}
    with pytest.raises(ValueError, match="never turns stable below omega_bar = 20.0"):
        onset("beta", fixed, 5e-4, 20.0, 2, 20000)


def test_where_the_linearisation_does_not_exist_the_tracked_value_is_nan():
    """Balls 1e17 times the disk's mass (mu rounds to 1/2, the mass matrix is singular) or an
    overflowing ratio: NaN, which the corrector treats as a failed step, never an exception that
    stops the job (found by the configuration fuzzer: Fig 3's beta = 0.1 sent a corrector step of
    the m_bar plane there). A point of the plane keeps its finite value."""
    from rotorvib.papers.b.boundaries import TrackedEigenvalue

    with np.errstate(over="ignore", invalid="ignore"):
        g = TrackedEigenvalue("m_bar", {"eps_bar": 0.012, "beta": 0.1, "zeta": 0.01}, 2, 0j)
        with pytest.raises(np.linalg.LinAlgError):
            g.eigenvalues(np.array([17.0, 1.0]))
        assert np.isnan(g(np.array([17.0, 1.0]))) and np.isnan(g(np.array([300.0, 1.0])))
        assert np.isfinite(g(np.array([0.0, 1.0])))


def test_the_onsets_extremes_are_located_and_a_brute_force_scan_agrees(beta_plane):
    """The traced points only bracket the onset's extremes (Fig 2's maximum sits between
    points some 0.1 in beta apart); solving Re lambda = 0 with d Re lambda / d beta = 0 locates
    each, and exact onsets on a fine grid of beta around it never pass the located extreme
    speed, come within 1e-5 of it and place it within a grid step."""
    from rotorvib.papers.b.boundaries import onset

    fixed = {k: v for k, v in BASE.items() if k != "beta"}
    turns = zip(beta_plane.turn_omega_bar_beta.values, beta_plane.turn_omega_bar_omega_bar.values,
                beta_plane.turn_omega_bar_error.values)
    found = 0
    for b_star, w_star, error in turns:
        grid = b_star * np.geomspace(0.95, 1.05, 21)
        onsets = np.array([onset("beta", fixed, b, 50.0, 2, 2000) for b in grid])
        sign = 1.0 if onsets[[0, -1]].max() < w_star else -1.0    # a maximum, else a minimum
        k = int(np.argmax(sign * onsets))
        assert error < 1e-8
        assert sign * (onsets - w_star).max() <= 1e-9 and abs(onsets[k] - w_star) < 1e-5
        assert abs(np.log(grid[k] / b_star)) <= np.log(1.05 / 0.95) / 20
        found += 1
    assert found >= 1
