"""The balancer engine's codes and array layouts, importable without numba: the two forms and
their parameter rows, the speed profiles and disk kinematics, the statuses a run ends with and
the columns of its metrics row (read with :func:`metric`).

The compiled modules (``engine``, ``kinematics``, ``analysers``) take them from here, so that a
job that only sets runs up or reads their metrics imports no compiler.
"""

from __future__ import annotations

import numpy as np

# the two forms of the equations (engine)
FIXED, ROTATING = 0, 1
# parameter-array layouts
P_FIXED = ("M", "m", "R", "eps", "k", "c", "D", "n", "Omega", "T_ramp", "profile", "kinematics")
P_ROT = ("mu", "rho", "zeta", "beta", "n", "Omega", "T_ramp", "profile")

# speed profiles and the disk kinematics of the FIXED form (kinematics)
CONSTANT, RUNUP = 0, 1
PRINTED, CONSISTENT = 0, 1

# status codes of an integration: OK and ABOVE_BOUND (stopped once its balance time was known
# to exceed the bound its batch gave it, every metric unknown) end a run; the others are failures
OK, STEP_UNDERFLOW, NON_FINITE, MAX_STEPS, ABOVE_BOUND = 0, 1, 2, 3, 4
STATUS_TEXT = {OK: "ok", STEP_UNDERFLOW: "step size underflow", NON_FINITE: "non-finite state",
               MAX_STEPS: "maximum number of steps reached",
               ABOVE_BOUND: "stopped above its balance-time bound"}
#: the engine's stop status of a run that goes on
RUNNING = -1

# metrics returned by the integrators (one row per run)
METRICS = ("status", "n_steps", "balance_time", "balanced", "envelope_time", "envelope_balanced",
           "force_max", "force_max_time", "force_decay_time", "force_decayed", "t_stop", "r_end",
           "outcome")
N_METRICS = len(METRICS)
#: column of each metric, by name
COLUMN = {name: i for i, name in enumerate(METRICS)}


def metric(metrics: np.ndarray, name: str) -> np.ndarray:
    """The column ``name`` (one of :data:`METRICS`) of a metrics row or table."""
    return metrics[..., COLUMN[name]]
