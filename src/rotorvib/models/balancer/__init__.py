"""Jeffcott rotor with an n-ball automatic balancer: compiled engine, parameters, simulation API,
stability of the balanced state, series expansion.

Importing the package first empties its numba cache if any of its modules changed since the
cache was written (:mod:`rotorvib.methods.numba_cache`)."""

from pathlib import Path

from rotorvib.methods.numba_cache import drop_if_stale

drop_if_stale(Path(__file__).parent)
