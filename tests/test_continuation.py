"""Pseudo-arclength continuation (rotorvib.methods.continuation) on curves known in closed
form."""

import numpy as np
import pytest

from rotorvib.methods.continuation import trace, turning_points

STEPS = {"step": 0.05, "min_step": 1e-8, "max_step": 0.2}


def test_circle_is_traced_through_its_folds():
    """g = x^2 + y^2 - 1 from (1, 0) upwards: every point on the circle to the tolerance; the
    curve turns back in y at (0, 1) and in x at (-1, 0), and ends on the bound y = -0.5."""
    curve = trace(lambda z: z[0] ** 2 + z[1] ** 2 - 1, (1.0, 0.0), (0.0, 1.0),
                  bounds=((-2, 2), (-0.5, 2)), tol=1e-12, **STEPS)
    x, y = curve.points.T
    np.testing.assert_allclose(np.hypot(x, y), 1.0, atol=1e-11)
    assert curve.stop == "reached the bounds"
    assert y[-1] == pytest.approx(-0.5, abs=0.02)   # the step shortened onto the bound
    folds_x = turning_points(curve.tangents[:, 0])
    folds_y = turning_points(curve.tangents[:, 1])
    assert len(folds_x) == 1 and abs(y[folds_x[0]]) < 0.2 and x[folds_x[0]] < -0.98
    assert len(folds_y) == 1 and y[folds_y[0]] > 0.98
    # the tangent never flips between neighbours: the sense of tracing is kept at the folds
    assert (np.sum(curve.tangents[1:] * curve.tangents[:-1], axis=1) > 0.9).all()


def test_start_is_corrected_onto_the_curve_and_a_missing_curve_refused():
    curve = trace(lambda z: z[1] - z[0] ** 3, (0.5, 0.3), (1.0, 0.0),
                  bounds=((-1, 1), (-2, 2)), **STEPS)
    np.testing.assert_allclose(curve.points[:, 1], curve.points[:, 0] ** 3, atol=1e-9)
    assert curve.points[-1, 0] == pytest.approx(1.0, abs=0.05)
    with pytest.raises(ValueError, match="no point of the curve"):
        trace(lambda z: 1.0 + z[0] ** 2 + z[1] ** 2, (0.5, 0.0), (1.0, 0.0),
              bounds=((-1, 1), (-1, 1)), **STEPS)
    with pytest.raises(ValueError, match="singular point"):
        trace(lambda z: 1.0 + z[0] ** 2 + z[1] ** 2, (0.0, 0.0), (1.0, 0.0),
              bounds=((-1, 1), (-1, 1)), **STEPS)
    with pytest.raises(ValueError, match="min_step"):
        trace(lambda z: z[1], (0.0, 0.0), (1.0, 0.0), bounds=((-1, 1), (-1, 1)),
              step=1.0, min_step=1e-8, max_step=0.2)


def test_turning_points_ignore_components_near_zero():
    assert turning_points(np.array([1.0, 0.5, -0.5, -1.0])).tolist() == [1]
    assert turning_points(np.array([1e-5, -1e-5, 2e-5])).size == 0
    assert turning_points(np.array([0.5, 1e-9, -0.5])).tolist() == [0]
