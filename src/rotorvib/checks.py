"""Argument checks shared by the public entry points: each raises ``ValueError`` naming the
argument, its value and what is allowed, before any work is done."""

from __future__ import annotations

import numbers

import numpy as np


def number(name: str, value, *, minimum: float = 0.0, inclusive: bool = False,
           what: str = "") -> float:
    """``value`` as a float; ``ValueError`` naming ``name`` unless it is finite and above
    ``minimum`` (or equal to it, if ``inclusive``).  ``what`` adds a reason to the message."""
    ok = np.isfinite(value) and (value >= minimum if inclusive else value > minimum)
    if not ok:
        raise ValueError(f"{name} = {float(value)!r}: must be a finite number "
                         f"{'>=' if inclusive else '>'} {minimum:g}{what}")
    return float(value)


def require(obj, positive=(), nonnegative=()) -> None:
    """``ValueError`` naming the first field of ``obj`` that is not a finite number > 0 (those in
    ``positive``) or >= 0 (those in ``nonnegative``)."""
    for names, inclusive in ((positive, False), (nonnegative, True)):
        for name in names:
            number(f"{type(obj).__name__}.{name}", getattr(obj, name), inclusive=inclusive)


def finite_array(name: str, value, *, shape: tuple | None = None, dtype=float) -> np.ndarray:
    """``value`` as an array of ``dtype``; ``ValueError`` unless every entry is finite and, where
    ``shape`` is given, the shape matches (``None`` entries match any length)."""
    a = np.asarray(value, dtype=dtype)
    if shape is not None and (a.ndim != len(shape) or any(
            want is not None and got != want for got, want in zip(a.shape, shape))):
        want = "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"
        raise ValueError(f"{name}: shape {a.shape}, expected {want}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: {int(np.size(a) - np.isfinite(a).sum())} of {a.size} entries "
                         "are not finite")
    return a


def integer(name: str, value, minimum: int) -> int:
    """``value`` as an ``int``; ``ValueError`` unless it is an integer (not a float or bool)
    ``>= minimum``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} = {value!r}: must be an integer >= {minimum}")
    return int(value)


def sobol_design_problem(n_base, convergence) -> str | None:
    """Why a Saltelli design of ``n_base`` base points, shown at the sizes ``convergence``,
    cannot be run (None if it can): every size a power of 2, none above ``n_base``."""
    for size in [n_base, *convergence]:
        if size < 2 or size & (size - 1):
            return f"{size} base points: must be a power of 2 (a balanced Sobol sequence)"
    if max(convergence) > n_base:
        return f"convergence {list(convergence)}: every size must be at most n_base = {n_base}"
    return None
