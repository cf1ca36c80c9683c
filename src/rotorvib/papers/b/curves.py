"""Measures on paper B's balance times: censored runs, curves against a parameter, shares of
initial positions, and the margins of claims on them.

A censored run (not balanced by ``t_end``) is NaN in the datasets; orderings treat it as longer
than any balanced run (:func:`as_longest`), never as a number.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin


def timed(value: float, uncertainty: float) -> Margin:
    """A margin in seconds between balance times, known to ``uncertainty`` (s)."""
    return Margin(value, uncertainty, "s", "balance times to the integration's accuracy "
                                           "(paper_b.claims.time_uncertainty)")


def seconds_text(seconds: float, never: str = "not balanced by t_end") -> str:
    """A time for a row's text: ``4.90 s``, or ``never`` for a censored run (NaN), which is no
    number of seconds."""
    return f"{seconds:.2f} s" if np.isfinite(seconds) else never


def as_longest(times) -> np.ndarray:
    """Balance times with a censored run (NaN: not balanced by t_end) as +inf, longer than any
    balanced one, so that orderings stay defined."""
    times = np.asarray(times, float)
    return np.where(np.isnan(times), np.inf, times)


def largest_fall(curve) -> float:
    """The largest drop of a balance-time curve between two neighbouring balanced runs (0 when
    it never falls between them; a censored run is no time to fall from)."""
    steps = np.diff(np.asarray(curve, float))
    steps = steps[np.isfinite(steps)]
    return float(max(0.0, -steps.min())) if steps.size else 0.0


def rise(curve) -> float:
    """How much longer the last balance time of a curve is than the first (``as_longest`` for
    censored runs; NaN when both are censored)."""
    c = as_longest(curve)
    with np.errstate(invalid="ignore"):
        return float(c[-1] - c[0])


def rise_text(rise_s: float) -> str:
    """A :func:`rise` for a row's text: ``+0.42 s``, or in words where a censored end makes it
    no number of seconds (``-inf``: censored at the bottom only; ``+inf``: at the top only;
    NaN: at both)."""
    if np.isfinite(rise_s):
        return f"{rise_s:+.3g} s"
    if np.isnan(rise_s):
        return "censored at both ends"
    return "censored at the bottom" if rise_s < 0 else "censored at the top"


def dip_depth(curve) -> float:
    """How far a curve's lowest interior point lies below both its ends, ``min(c_0, c_end) -
    min(interior)``: positive for a curve that first falls and then grows; negative, by how far
    the interior stays above it, where the lowest point is an end (never clamped at 0, which
    would read as "too close to tell")."""
    c = as_longest(curve)
    if c.size < 3:
        raise ValueError(f"a dip needs an interior point: {c.size} points given")
    with np.errstate(invalid="ignore"):
        return float(min(c[0], c[-1]) - c[1:-1].min())


def within(values, band) -> float:
    """How far every value lies inside ``band`` (negative: outside by that much)."""
    lo, hi = band
    values = np.asarray(values, float)
    return float(np.min(np.minimum(values - lo, hi - values)))


def within_studied(values, band, studied) -> tuple[float, str]:
    """How far every value lies inside ``band`` (negative: outside by that much), measured only
    to the band's edges that lie inside the ``studied`` range (a grid's ends, a search's
    bounds): an edge the study shares can be failed by no value it can give, so a margin to it
    says nothing. Returns the margin (infinite when no edge of the band can be failed) and a
    sentence naming the edges it is measured to."""
    lo, hi = band
    values = np.asarray(values, float)
    edges = [(values - lo, f"{lo:g}")] if lo > studied[0] else []
    edges += [(hi - values, f"{hi:g}")] if hi < studied[1] else []
    if not edges:
        return math.inf, (f"the band [{lo:g}, {hi:g}] holds the whole studied range "
                          f"[{studied[0]:g}, {studied[1]:g}]: true by construction")
    shared = [f"{e:g}" for e, inside in ((lo, lo > studied[0]), (hi, hi < studied[1]))
              if not inside]
    text = f"margin to the band's edge {' and '.join(name for _, name in edges)}"
    if shared:
        text += (f"; its edge {' and '.join(shared)} is the studied range's own "
                 f"[{studied[0]:g}, {studied[1]:g}], which no value can cross")
    return float(np.min([np.min(m) for m, _ in edges])), text


def argmin(curve, axis_values) -> float:
    """The grid value of a curve's least point (NaN where the curve has no value)."""
    return float(axis_values[int(np.nanargmin(curve))]) if np.isfinite(curve).any() else math.nan


def roughness(curve) -> float:
    """The size of a sampled curve's own bumps: the largest departure of a point from the mean
    of its two neighbours (a curve smooth on the grid's scale departs by its curvature times
    the step squared; a bump, by its height). NaN points are skipped with their neighbours."""
    y = np.asarray(curve, float)
    bumps = np.abs(y[1:-1] - (y[:-2] + y[2:]) / 2)
    return float(np.nanmax(bumps)) if np.isfinite(bumps).any() else 0.0


def argmin_interval(curve, axis_values) -> tuple[float, float]:
    """The grid values whose point lies within the curve's :func:`roughness` of its least: the
    optimum the grid cannot tell apart, as ``(lowest, highest)`` (NaN where the curve has no
    value)."""
    y = np.asarray(curve, float)
    if not np.isfinite(y).any():
        return math.nan, math.nan
    near = np.asarray(axis_values, float)[y <= np.nanmin(y) + roughness(y)]
    return float(near.min()), float(near.max())


def mean_over_ics(ds: xr.DataArray) -> xr.DataArray:
    """Mean balance time over the initial conditions; NaN if any run is censored."""
    return ds.mean("ic", skipna=False)


def share_balanced_by(times, t) -> float:
    """The share of runs balanced by time ``t``: the empirical distribution function of the
    balance ``times`` at ``t``, a censored run (NaN: not balanced by the end) counting as
    longer than any time. Over a uniform grid of initial ball positions it is the chance that
    balls placed at random balance by ``t``; at an initial condition's own time, its
    percentile."""
    times = np.asarray(times, float).ravel()
    return float(np.count_nonzero(times <= t) / times.size)


def faster_share(times, t) -> float:
    """The share of runs of ``times`` no slower than an initial condition balanced at ``t``:
    :func:`share_balanced_by` for a balanced one, and for a censored one (NaN) the share
    balanced at all, since it is slower than every balanced run."""
    return share_balanced_by(times, t) if np.isfinite(t) else share_balanced_by(times, np.inf)
