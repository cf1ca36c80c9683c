"""Pseudo-arclength continuation of a curve ``g(x, y) = 0`` in a plane (Keller's method).

From a point ``z_k`` on the curve with unit tangent ``t_k`` (perpendicular to the gradient
``grad g(z_k)``), the predictor steps ``z_p = z_k + h t_k`` along the tangent and the
corrector solves, by Newton's method,

    g(z) = 0,        t_k . (z - z_p) = 0,

the point of the curve on the line through ``z_p`` normal to the tangent.  Because the curve is
parametrised by its arclength and not by ``x`` or ``y``, it passes folds (``x`` or ``y``
turning back) without a singular Jacobian; the new tangent is oriented to continue the old one
(``t_{k+1} . t_k > 0``).  The step grows after an easy correction and halves after a failed
one.  The gradient is taken by central differences.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class Curve:
    """Points (``k x 2``) and unit tangents of a traced curve, and why tracing stopped."""

    points: np.ndarray
    tangents: np.ndarray
    stop: str


def gradient(g: Callable[[np.ndarray], float], z: np.ndarray, h: float) -> np.ndarray:
    """``grad g(z)`` by central differences of width ``2 h``."""
    e = np.eye(2) * h
    return np.array([(g(z + e[i]) - g(z - e[i])) / (2 * h) for i in range(2)])


def tangent(grad: np.ndarray, previous: np.ndarray) -> np.ndarray:
    """The unit tangent ``(-g_y, g_x) / |grad g|`` of a curve ``g = 0``, in the sense of
    ``previous`` (their dot product is not negative)."""
    norm = np.hypot(*grad)
    if not norm > 0:
        raise ValueError(f"the gradient {tuple(grad)} gives no tangent: a singular point")
    t = np.array([-grad[1], grad[0]]) / norm
    return t if t @ previous >= 0 else -t


def _correct(g, z_pred, t, *, tol, h_fd, iterations=8):
    """Newton's method on ``g(z) = 0, t . (z - z_pred) = 0``; None if it does not converge."""
    z = z_pred.copy()
    for _ in range(iterations):
        value = g(z)
        if not np.isfinite(value):
            return None
        jac = np.vstack([gradient(g, z, h_fd), t])
        try:
            dz = np.linalg.solve(jac, [-value, -(t @ (z - z_pred))])
        except np.linalg.LinAlgError:
            return None
        z = z + dz
        if np.hypot(*dz) <= tol and abs(value) <= tol:
            return z
    return z if abs(g(z)) <= tol else None


def trace(g: Callable[[np.ndarray], float], start, direction, *, bounds, step: float,
          min_step: float, max_step: float, tol: float = 1e-10, h_fd: float = 1e-7,
          max_points: int = 10_000,
          accept: Callable[[np.ndarray], None] | None = None) -> Curve:
    """Trace ``g(z) = 0`` from ``start`` (a point on or near the curve) in the sense of
    ``direction`` (a 2-vector), inside ``bounds = ((x_min, x_max), (y_min, y_max))``.

    ``accept(z)`` is called on every accepted point (e.g. to follow an eigenvalue by
    continuity).  Tracing stops when the curve leaves the bounds (the last point is the one
    inside, the step shortened to end on the crossed bound), after ``max_points``, or
    when the step falls below ``min_step``; ``Curve.stop`` says which."""
    if not min_step <= step <= max_step:
        raise ValueError(f"step {step} must lie in [min_step, max_step] = "
                         f"[{min_step}, {max_step}]")
    lo, hi = np.asarray(bounds, dtype=float).T
    z = _correct(g, np.asarray(start, dtype=float), tangent(gradient(g, np.asarray(start, float),
                                                                    h_fd), direction),
                 tol=tol, h_fd=h_fd)
    if z is None:
        raise ValueError(f"no point of the curve near the start {tuple(start)}")
    t = tangent(gradient(g, z, h_fd), np.asarray(direction, dtype=float))
    points, tangents = [z], [t]
    if accept:
        accept(z)
    h, closing = step, 0
    while len(points) < max_points:
        new = _correct(g, z + h * t, t, tol=tol, h_fd=h_fd)
        if new is None or np.hypot(*(new - z)) > 2 * h:   # failed, or jumped to another branch
            h /= 2
            if h < min_step:
                return Curve(np.array(points), np.array(tangents), "step below min_step")
            continue
        outside = (new < lo) | (new > hi)
        if outside.any():
            # shorten the step to end on the bound it crosses (a few times: the corrector
            # moves the point off the predicted line)
            edge = np.where(new < lo, lo, hi)[outside]
            h *= 0.99 * np.min((edge - z[outside]) / (new - z)[outside])
            closing += 1
            if h < min_step or closing > 8:
                return Curve(np.array(points), np.array(tangents), "reached the bounds")
            continue
        z, t = new, tangent(gradient(g, new, h_fd), t)
        points.append(z)
        tangents.append(t)
        if accept:
            accept(z)
        h = h if closing else min(1.5 * h, max_step)
    return Curve(np.array(points), np.array(tangents), "max_points")


def turning_points(values: np.ndarray, floor: float = 1e-3) -> np.ndarray:
    """Indices ``i`` after which the sequence ``values`` (one tangent component along a curve)
    changes sign: a fold of the curve in that coordinate.  Components within ``floor`` of zero
    carry no sign (a curve running parallel to an axis is not folding); the fold is placed at
    the last signed point before the change."""
    values = np.asarray(values, dtype=float)
    signed = np.flatnonzero(np.abs(values) > floor)
    s = np.sign(values[signed])
    return signed[np.flatnonzero(s[:-1] * s[1:] < 0)]


def _turning_point(g, z0, axis: int, h: float, tol: float, iterations: int):
    """Newton's method on ``g(z) = 0, dg/dz_(1 - axis) (z) = 0`` from ``z0`` (derivatives by
    central differences of width ``2 h``); the point and the last step's length."""
    other = 1 - axis

    def residual(z):
        return np.array([g(z), gradient(g, z, h)[other]])

    z = np.asarray(z0, dtype=float).copy()
    step = np.inf
    for _ in range(iterations):
        f = residual(z)
        e = np.eye(2) * h
        jac = np.column_stack([(residual(z + e[i]) - residual(z - e[i])) / (2 * h)
                               for i in range(2)])
        dz = np.linalg.solve(jac, -f)
        z, step = z + dz, float(np.hypot(*dz))
        if step <= tol:
            break
    return z, step


def refine_turning_point(g: Callable[[np.ndarray], float], z0, axis: int, *,
                         h: float = 1e-5, tol: float = 1e-12,
                         iterations: int = 30) -> tuple[np.ndarray, float]:
    """The point near ``z0`` where the curve ``g = 0`` turns in coordinate ``axis``: its
    tangent ``(-g_y, g_x)`` has no component along ``axis``, so ``g = 0`` and
    ``dg/dz_(1 - axis) = 0`` (a fold in ``x`` for ``axis = 0``, an extremum of ``y`` along the
    curve for ``axis = 1``), solved by Newton's method from a traced point next to the turn
    (:func:`turning_points`).  Returns the point and an error bound: the larger of the last
    Newton step and the distance to the point found with differences twice as wide (the
    differences' own error)."""
    if axis not in (0, 1):
        raise ValueError(f"axis must be 0 or 1, not {axis!r}")
    z, step = _turning_point(g, z0, axis, h, tol, iterations)
    wide, _ = _turning_point(g, z0, axis, 2 * h, tol, iterations)
    return z, max(step, float(np.hypot(*(z - wide))))
