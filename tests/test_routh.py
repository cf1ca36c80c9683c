"""Routh's criterion (rotorvib.methods.routh) against the roots, and its operation counts."""

import numpy as np
import pytest

from rotorvib.methods import routh
from rotorvib.models.balancer import stability


def test_routh_decides_as_the_roots_do_on_random_polynomials():
    """Real polynomials of degree 1-8 built from random roots (complex ones in conjugate
    pairs), leading coefficient of either sign: stable exactly when every root has a negative
    real part."""
    rng = np.random.default_rng(7)
    for _ in range(2000):
        n = int(rng.integers(1, 9))
        pairs = rng.normal(size=n // 2) + 1j * rng.normal(size=n // 2)
        real = rng.normal(size=n - 2 * (n // 2))
        roots = np.concatenate([pairs, pairs.conj(), real])
        coefficients = np.poly(roots).real * rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 2.0)
        assert routh.stable(coefficients) == bool(np.all(roots.real < 0)), roots


def test_the_array_in_multiple_precision_is_the_array_in_doubles():
    """``dtype=object`` with ``mpmath.mpf`` coefficients: the same first column to 1e-12 as in
    doubles (random stable and unstable degree-8 polynomials), and the same decision."""
    import mpmath

    rng = np.random.default_rng(11)
    with mpmath.workdps(40):
        for _ in range(50):
            roots = np.concatenate([r := rng.normal(size=4) + 1j * rng.normal(size=4), r.conj()])
            coefficients = np.poly(roots).real
            exact = routh.first_column([mpmath.mpf(c) for c in coefficients], dtype=object)
            assert isinstance(exact[-1], mpmath.mpf)
            np.testing.assert_allclose(exact.astype(float), routh.first_column(coefficients),
                                       rtol=1e-12)
            assert routh.stable([mpmath.mpf(c) for c in coefficients], dtype=object) == \
                routh.stable(coefficients)


def test_a_root_on_the_imaginary_axis_is_not_stable():
    assert not routh.stable([1.0, 0.0, 1.0])                   # s^2 + 1: roots +/- i
    assert not routh.stable([1.0, 2.0, 0.0])                   # s (s + 2): a root at 0
    assert routh.stable([1.0, 2.0, 1.0])                       # (s + 1)^2
    np.testing.assert_array_equal(routh.stable([[1.0, 3.0, 2.0], [1.0, -3.0, 2.0]]),
                                  [True, False])               # broadcast over leading axes
    with pytest.raises(ValueError, match="degree"):
        routh.stable([1.0])


def test_operation_counts():
    """Degree 2 needs one entry below the first two rows (4 operations); degree 8 needs 16;
    the eigenvalues of an 8x8 matrix about 10 x 8^3."""
    assert routh.operations(2) == 4
    assert routh.operations(8) == 64
    assert routh.eigenvalue_operations(8) == 5120


def test_on_the_balancer_routh_agrees_with_the_roots_of_paper_a():
    """On a grid of paper A's (beta, Omega) plane the stable set by Routh's criterion on the
    characteristic polynomial is the stable set of its roots and of the 8x8 Jacobian."""
    beta, omega = np.meshgrid(np.linspace(0.01, 5.0, 40), np.linspace(0.5, 4.0, 60),
                              indexing="ij")
    args = (0.01, 1.0, 0.05, beta, omega)
    by_routh = routh.stable(stability.characteristic_coefficients(*args))
    np.testing.assert_array_equal(by_routh, stability.polynomial_roots(*args).real.max(-1) < 0)
    np.testing.assert_array_equal(by_routh, stability.max_real_part(*args) < 0)
    assert 0 < by_routh.mean() < 1
