"""Round-off-sized numbers in the comparison's texts are printed as the power of ten that bounds
them, so the text does not move with the machine's arithmetic (benchmarks/kernels.py)."""

import math

import pytest

from rotorvib.io.tables import order_bound


@pytest.mark.parametrize("x, text", [(1.9e-15, "1e-14"), (1.8e-15, "1e-14"), (1e-15, "1e-15"),
                                     (9.3e-10, "1e-09"), (1.3e-10, "1e-09"), (0.0, "0"),
                                     (2.0, "1e+01")])
def test_the_bound_is_the_power_of_ten_at_or_above(x, text):
    assert order_bound(x) == text
    assert x <= float(text) < 10 * x or x == 0


@pytest.mark.parametrize("x", [-1e-16, math.nan, math.inf])
def test_no_bound_of_what_is_not_a_size(x):
    with pytest.raises(ValueError, match="must be finite and >= 0"):
        order_bound(x)
