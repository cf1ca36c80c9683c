"""Coordinates of the pipeline's datasets: numeric axes with CF metadata and label axes.

A label axis (kinematics, initial condition, named run) is a dimension ``<axis>`` with a string
coordinate ``<axis>_name``; :func:`pick` selects on it by label.
"""

from __future__ import annotations

import numpy as np
import xarray as xr


def grid(spec: dict) -> np.ndarray:
    """The points of a configured range ``{min, max, n}`` (config/schema.yaml ``$defs/range``):
    ``n`` evenly spaced from ``min`` to ``max``, both included."""
    return np.linspace(spec["min"], spec["max"], spec["n"])


def axis_coord(name: str, values, long_name: str, units: str) -> dict:
    """``{name: (name, values, attrs)}``: a numeric coordinate for ``xr.Dataset(coords=...)``."""
    return {name: (name, np.asarray(values, dtype=float), {"long_name": long_name,
                                                            "units": units})}


def label_coord(axis: str, names, long_name: str) -> dict:
    """``{axis_name: (axis, names, attrs)}``: the string labels of a label axis."""
    return {f"{axis}_name": (axis, np.array(names, dtype=object), {"long_name": long_name})}


def labels(ds: xr.Dataset, axis: str) -> list[str]:
    """The labels of label axis ``axis``, in order."""
    return [str(name) for name in ds[f"{axis}_name"].values]


def pick(ds: xr.Dataset, **selection) -> xr.Dataset:
    """Select label axes by label, e.g. ``pick(ds, kinematics="printed", ic="IC1")``."""
    return ds.isel({axis: labels(ds, axis).index(label) for axis, label in selection.items()})
