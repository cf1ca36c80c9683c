"""Argument checks shared by the model parameter classes."""

from __future__ import annotations

import numpy as np


def require(obj, positive=(), nonnegative=()) -> None:
    """``ValueError`` naming the first field of ``obj`` that is not a finite number > 0 (those in
    ``positive``) or >= 0 (those in ``nonnegative``)."""
    for names, ok, word in ((positive, lambda v: v > 0, "> 0"),
                            (nonnegative, lambda v: v >= 0, ">= 0")):
        for name in names:
            value = getattr(obj, name)
            if not (np.isfinite(value) and ok(value)):
                raise ValueError(f"{type(obj).__name__}.{name} = {float(value)!r}: must be a finite "
                                 f"number {word}")
