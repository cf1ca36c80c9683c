"""What a sensitivity study's dataset (:func:`rotorvib.methods.sensitivity.study_dataset`) says
of a value: how far it lies inside a quantity's band, how well the sample pins that band's
edges (bootstrap), and a sentence with the input that drives the quantity most.

Apart from :mod:`rotorvib.methods.sensitivity` because it needs no SALib (and so no
``scipy.stats``, about half a second to import where nothing else has imported scipy's
submodules): the jobs that state claims read the studies' datasets with it, and only the study
jobs compute them.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

#: A total index is reported only where the half-width of its 95 % interval is at most this:
#: a wider interval says too little about the input at the sample size (the index lies in
#: [0, 1]); the study states such an index as unresolved.
RESOLVED_HALF_WIDTH = 0.1


def percentile_spread(y, percentiles, *, resamples: int, seed: int) -> np.ndarray:
    """Standard deviation of each of ``percentiles`` of the sample ``y`` (its values; NaN
    marks a point without one) over ``resamples`` bootstrap resamples: how well a finite sample
    pins a band's edges, or its median; NaN for each where no point has a value (every run
    censored)."""
    y = np.asarray(y, float)
    y = y[np.isfinite(y)]
    if y.size == 0:
        return np.full(len(percentiles), np.nan)
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, y.size, (resamples, y.size))
    return np.percentile(y[draws], percentiles, axis=1).std(axis=1)


def sample_margin(y, percentiles, value: float, *, resamples: int,
                  seed: int) -> tuple[float, float]:
    """How far ``value`` lies inside the band between the outer ``percentiles`` of the sample
    ``y`` (NaN: a point without a value) -- ``min(value - low, high - value)``, negative
    outside -- and that margin's uncertainty: twice the bootstrap standard deviation of the
    nearer edge (:func:`percentile_spread`); NaN for both where no point has a value."""
    y = np.asarray(y, float)
    finite = y[np.isfinite(y)]
    if finite.size == 0:
        return math.nan, math.nan
    lo, hi = np.percentile(finite, [percentiles[0], percentiles[-1]])
    spread = percentile_spread(finite, [percentiles[0], percentiles[-1]], resamples=resamples,
                               seed=seed)
    nearer = 0 if value - lo <= hi - value else 1
    return float(min(value - lo, hi - value)), float(2 * spread[nearer])


def band_margin(ds: xr.Dataset, quantity: str, value: float, y=None) -> tuple[float, float]:
    """:func:`sample_margin` of ``value`` in ``quantity``'s band of the study ``ds`` (its
    percentiles, resamples and seed), over the study's sample or the values ``y`` of the same
    quantity (another prior's)."""
    q = list(ds.quantity_name.values).index(quantity)
    return sample_margin(ds.y.values[q] if y is None else y, ds.percentile.values, value,
                         resamples=int(ds.attrs["sobol_resamples"]),
                         seed=int(ds.attrs["sobol_seed"]))


def band_statement(ds: xr.Dataset, quantity: str, value: float) -> tuple[tuple[float, float], str]:
    """``value``'s margin inside the outer percentiles of ``quantity``'s band with its
    uncertainty (:func:`band_margin`), and a sentence with the band, the nominal value and the
    input of largest total index (with its interval) at the largest sample, said to be
    unresolved where its interval is wider than :data:`RESOLVED_HALF_WIDTH`."""
    q = list(ds.quantity_name.values).index(quantity)
    band, units = ds.band.values[q], str(ds.quantity_units.values[q])
    lo, hi = band[0], band[-1]
    st, conf = ds.ST.values[q, -1], ds.ST_conf.values[q, -1]
    p = ds.percentile.values
    valued, points = int(ds.n_valued[q]), ds.sizes["sample"]
    if valued == 0:
        return band_margin(ds, quantity, value), (
            f"{value:.4g} {units}, but none of the {points} input points has a value (no run "
            "balances by t_end): there is no band to compare it with")
    if valued < points:
        driver = "no Sobol index (it needs a value at every point)"
    elif np.all(np.isnan(st)):
        driver = "it does not vary over them (no Sobol index)"
    else:
        top = int(np.nanargmax(st))
        index = (f"{ds.input_name.values[top]} ({st[top]:.2f} +/- {conf[top]:.2f}, "
                 f"{int(ds.n_base[-1])} base points)")
        driver = (f"largest total Sobol index: {index}" if conf[top] <= RESOLVED_HALF_WIDTH
                  else f"the largest total Sobol index, {index}, is not resolved within "
                       f"+/- {RESOLVED_HALF_WIDTH:g}")
    over = ("the input ranges" if valued == points else
            f"the {valued} of {points} input points where it has a value (the others never "
            "balance by t_end)")
    return band_margin(ds, quantity, value), (
        f"{value:.4g} {units} against the {p[0]:g}-{p[-1]:g} % band {lo:.4g}-{hi:.4g} {units} "
        f"(median {band[len(band) // 2]:.4g}, nominal {float(ds.nominal[q]):.4g}) over "
        f"{over}; {driver}")
