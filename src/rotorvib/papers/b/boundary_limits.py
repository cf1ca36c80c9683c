"""What the traced stability boundary of paper B's balanced state says at its ends
(:mod:`rotorvib.papers.b.boundaries` traces it): the approach to the critical speed as
``beta -> inf`` and the least beta that balances at any speed.  Reads datasets only."""

from __future__ import annotations

import numpy as np
import xarray as xr


def on_boundary(ds: xr.Dataset) -> xr.Dataset:
    """The points of a traced curve that bound the stable region."""
    return ds.isel(point=ds.on_boundary.values == 1)


def approach_coefficient(ds: xr.Dataset) -> tuple[float, float]:
    """``a`` of ``omega_onset - critical_speed ~ a / beta`` over the top decade of the
    (beta, omega_bar) boundary (least squares with a ``b / beta^2`` correction), and how far
    ``beta (omega_onset - critical_speed)`` at the top lies from it."""
    top = on_boundary(ds)
    top = top.isel(point=top.beta.values >= top.beta.values.max() / 10)
    beta, excess = top.beta.values, (top.omega_onset - top.critical_speed).values
    (a, _), *_ = np.linalg.lstsq(np.stack([1 / beta, 1 / beta**2], axis=1), excess, rcond=None)
    last = np.argmax(beta)
    return float(a), float(abs(beta[last] * excess[last] - a))


def lowest_beta(ds: xr.Dataset) -> tuple[float, float, float]:
    """The least beta on the (beta, omega_bar) boundary, the speed there, and how much beta
    still moves between half that speed and it (how well the asymptote is reached)."""
    edge = on_boundary(ds)
    i = int(np.argmin(edge.beta.values))
    omega = float(edge.omega_onset[i])
    half = int(np.argmin(np.abs(edge.omega_onset.values - omega / 2)))
    return float(edge.beta[i]), omega, float(abs(edge.beta[half] - edge.beta[i]))
