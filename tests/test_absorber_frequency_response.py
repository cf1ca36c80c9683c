"""Paper C steady state: three routes to Theta agree; analytic limits; Den Hartog's optimum."""

import numpy as np
import pytest

from rotorvib.models.absorber.frequency_response import (
    bare_rotor_amplitude,
    dimensionless_amplitude,
    matrices,
    natural_frequencies,
    rotor_peak,
    steady_state,
    theta_eq20,
)
from rotorvib.models.absorber.parameters import (
    AbsorberSet,
    dual_to_vector,
    effective_mass_ratio,
    undamped,
)
from rotorvib.models.absorber.tuning import den_hartog_single, mass_ratio_family

W = np.concatenate([np.linspace(0.5, 0.99, 50), np.linspace(1.01, 1.5, 50)])


def test_omega_n_matches_section_4(rotor):
    assert rotor.omega_n == pytest.approx(np.sqrt(1e4 / (0.5 * 5 * 0.14**2)))


def test_bare_rotor_is_one_over_one_minus_w_squared(rotor):
    D = dimensionless_amplitude(rotor, steady_state(rotor, (), W * rotor.omega_n)[:, 0])
    np.testing.assert_allclose(D, 1 / np.abs(1 - W**2), rtol=1e-12)
    np.testing.assert_allclose(bare_rotor_amplitude(W), D, rtol=1e-12)


def test_eq20_with_true_determinant_equals_linear_solve(rotor, table2):
    omega = W * rotor.omega_n
    solved = steady_state(rotor, table2, omega)[:, 0]
    closed = theta_eq20(rotor, dual_to_vector(table2), omega)
    np.testing.assert_allclose(closed, solved, rtol=1e-10)
    printed = theta_eq20(rotor, dual_to_vector(table2), omega, printed_determinant=True)
    assert np.max(np.abs(printed / solved - 1)) > 0.1


def test_eq20_vectorises_over_designs(rotor, table2):
    x = np.stack([dual_to_vector(table2), dual_to_vector(mass_ratio_family(table2, 0.5))])
    batch = theta_eq20(rotor, x, rotor.omega_n)
    single = [theta_eq20(rotor, xi, rotor.omega_n) for xi in x]
    np.testing.assert_allclose(batch, single, rtol=1e-14)


def test_undamped_absorber_cancels_the_disk_at_its_own_frequency(rotor, table2):
    sets = undamped(table2[:1])
    q = steady_state(rotor, sets, sets[0].omega_a)
    assert abs(q[0]) < 1e-12 * rotor.Gamma0 / rotor.k_t
    # the absorber then carries the torque: 2 (2k) d S1 = -Gamma0 (eq. 11 with theta = 0)
    assert 4 * sets[0].k * sets[0].d * q[1].real == pytest.approx(-rotor.Gamma0, rel=1e-9)


@pytest.mark.parametrize("construction", ["tuned", "mass_only"])
def test_mass_ratio_family_reproduces_table2_at_085(table2, construction):
    assert mass_ratio_family(table2, 0.85, construction) == pytest.approx(table2)


def test_mass_ratio_constructions_differ_only_in_the_second_spring(table2):
    tuned, mass_only = (mass_ratio_family(table2, 0.5, c) for c in ("tuned", "mass_only"))
    assert tuned[0] == mass_only[0] and tuned[1].m == mass_only[1].m == 0.5 * table2[0].m
    assert tuned[1].k == 0.5 * table2[0].k and mass_only[1].k == table2[1].k
    with pytest.raises(ValueError, match="unknown construction"):
        mass_ratio_family(table2, 0.5, "other")


def test_matrices_of_eq14(rotor, table2):
    M, C, K = matrices(rotor, table2)
    s1, s2 = table2
    assert M[0, 0] == pytest.approx(rotor.J + 2 * s1.m * s1.d**2 + 2 * s2.m * s2.d**2)
    assert (M[0, 1], M[1, 0], M[1, 1]) == pytest.approx((2 * s1.m * s1.d, s1.m * s1.d, s1.m))
    np.testing.assert_allclose(np.diag(C), [0, 2 * s1.c, 2 * s2.c])
    np.testing.assert_allclose(np.diag(K), [rotor.k_t, 2 * s1.k, 2 * s2.k])


def test_den_hartog_single_absorber_reaches_the_classical_peak(rotor):
    """Den Hartog's optimum: equal fixed points and peak D = sqrt(1 + 2/mu)."""
    single = den_hartog_single(rotor, m=0.185, d=0.10)
    mu = effective_mass_ratio(rotor, (single,))
    w = np.linspace(0.7, 1.3, 60001)
    D = dimensionless_amplitude(rotor, steady_state(rotor, (single,), w * rotor.omega_n)[:, 0])
    assert D.max() == pytest.approx(np.sqrt(1 + 2 / mu), rel=0.03)
    low, high = D[w < 1].max(), D[w > 1].max()
    assert low == pytest.approx(high, rel=0.05)
    # the classical absorber equivalence: natural frequency f omega_n with f = 1/(1 + mu)
    assert single.omega_a == pytest.approx(rotor.omega_n / (1 + mu))


def test_absorber_set_frequency():
    assert AbsorberSet(m=0.1, k=10000.0, c=0.0, d=0.1).omega_a == pytest.approx(np.sqrt(2e5))


def test_undamped_response_is_unbounded_at_the_natural_frequencies(rotor, table2):
    """No absorber: the single natural frequency is w = 1. Table 2 undamped: D grows without
    bound towards the two frequencies the rotor takes part in (the middle one, sqrt(2k/m) of
    the equally tuned sets, is the anti-phase mode the torque does not excite)."""
    assert natural_frequencies(rotor, ()) == pytest.approx([1.0], rel=1e-12)
    w_nat = natural_frequencies(rotor, undamped(table2))
    assert w_nat[1] == pytest.approx(np.sqrt(2 * 1e4 / 0.1) / rotor.omega_n, rel=1e-10)
    for w in w_nat[[0, 2]]:
        D = [dimensionless_amplitude(rotor, steady_state(rotor, undamped(table2),
                                                         w * (1 + e) * rotor.omega_n)[0])
             for e in (1e-3, 1e-6)]
        assert D[1] > 900 * D[0]  # D ~ 1/|w - w_i|


def test_true_peak_beats_a_dense_grid_and_approaches_den_hartog(rotor, table2):
    w_peak, D_peak = rotor_peak(rotor, table2)
    grid = np.linspace(0.3, 2.0, 200001)
    D_grid = dimensionless_amplitude(rotor, steady_state(rotor, table2, grid * rotor.omega_n)[:, 0])
    assert D_peak == pytest.approx(D_grid.max(), rel=1e-6) and D_peak >= D_grid.max()
    assert w_peak == pytest.approx(grid[np.argmax(D_grid)], abs=2e-5)
    single = den_hartog_single(rotor, 0.1, 0.1)
    mu = 2 * 0.1 * 0.1**2 / rotor.J  # Den Hartog's equal fixed points: D = sqrt(1 + 2/mu)
    assert rotor_peak(rotor, (single,))[1] == pytest.approx(np.sqrt(1 + 2 / mu), rel=0.01)
