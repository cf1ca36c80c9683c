"""The work a balancer run may ask for, at most, and the count of its samples: what the engine
refuses (:mod:`inputs`) and what the workflow checks in a configuration before any job
(:mod:`rotorvib.papers.b.config_checks`), in one place.  Importing it loads no compiled code."""

from __future__ import annotations

import math

#: A run's samples (``t_end / sample_dt + 1``) at most: a stored trajectory of this many rows of
#: a two-ball state takes 640 MB.
MAX_SAMPLES = 10_000_000
#: The work of a run at most, in radians of its fastest rate (:func:`inputs.fastest_rate`)
#: over ``t_end``: an explicit integrator takes at least one step per few radians, so this
#: bounds a run to some ten million steps (seconds), where paper B's run-up takes 4 000.
MAX_RADIANS = 1e7


def samples(t_end: float, sample_dt: float) -> int:
    """The number of samples of a run, ``floor(t_end / sample_dt) + 1``."""
    return int(math.floor(t_end / sample_dt + 1e-9)) + 1


def samples_problem(t_end: float, sample_dt: float) -> str | None:
    """Why a run of ``t_end`` sampled every ``sample_dt`` has too many samples, or None (the
    ratio is compared before it is counted: a subnormal ``sample_dt`` makes it infinite)."""
    ratio = t_end / sample_dt
    if not ratio < MAX_SAMPLES:
        return f"{ratio + 1:.3g} samples, at most {MAX_SAMPLES:.0e}"
    return None


def radians_problem(rate: float, t_end: float) -> str | None:
    """Why a run whose fastest rate is ``rate`` (1/s) cannot last ``t_end``, or None."""
    radians = rate * t_end
    if not radians <= MAX_RADIANS:
        return f"the run spans {radians:.3g} radians of its fastest rate, at most {MAX_RADIANS:.0e}"
    return None
