"""Data variables with their CF metadata from a table: a dataset builder lists each variable's
long name and units once, ``{name: (long_name, units)}``, and its values apart."""

from __future__ import annotations


def described(values: dict[str, tuple], meta: dict[str, tuple[str, str | None]]) -> dict:
    """The data variables of an ``xarray.Dataset``: each ``values[name] = (dims, data)`` with
    the attributes ``long_name`` and ``units`` of ``meta[name] = (long_name, units)`` (units
    None: a label, which has none). Every variable must be described, and every description
    used (``KeyError`` naming the names otherwise)."""
    if missing := sorted(values.keys() - meta.keys()):
        raise KeyError(f"variables without a description: {missing}")
    if unused := sorted(meta.keys() - values.keys()):
        raise KeyError(f"descriptions of no variable: {unused}")
    return {name: (dims, data, {"long_name": meta[name][0],
                                **({"units": meta[name][1]} if meta[name][1] else {})})
            for name, (dims, data) in values.items()}
