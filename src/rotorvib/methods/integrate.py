"""Reference ODE integration with failure reporting.

A failed integration (solver failure, non-finite state) raises :class:`IntegrationError`; it is
never turned into numbers.
"""

from __future__ import annotations

import numbers

import numpy as np


class IntegrationError(RuntimeError):
    """An ODE integration did not reach its end time with a finite state."""


#: The smallest relative tolerance double precision can honour (scipy clamps below it).
RTOL_MIN = 100 * np.finfo(float).eps


def check_tolerances(rtol: float, atol: float) -> None:
    """Raise ``ValueError`` naming ``rtol`` or ``atol`` unless ``RTOL_MIN <= rtol < 1`` and
    ``atol >= 0``, both finite."""
    for name, value in (("rtol", rtol), ("atol", atol)):
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise ValueError(f"{name} = {value!r}: must be a real number")
    if not (np.isfinite(rtol) and RTOL_MIN <= rtol < 1):
        raise ValueError(f"rtol = {rtol!r}: must lie in [{RTOL_MIN:.3g}, 1) (double precision "
                         "cannot deliver a smaller relative error)")
    if not (np.isfinite(atol) and atol >= 0):
        raise ValueError(f"atol = {atol!r}: must be a finite number >= 0")


def integrate(rhs, y0, t_eval, *, rtol: float, atol: float, method: str = "DOP853",
              args: tuple = ()) -> np.ndarray:
    """Integrate ``y' = rhs(t, y, *args)`` from ``t_eval[0]``; return ``y`` at ``t_eval``, shape
    ``(len(t_eval), len(y0))``."""
    # Imported here: the compiled engine's jobs use only the checks above, and importing
    # scipy.integrate costs them about 0.8 s each.
    from scipy.integrate import solve_ivp

    check_tolerances(rtol, atol)
    t_eval = np.asarray(t_eval, dtype=float)
    y0 = np.asarray(y0, dtype=float)
    if t_eval.ndim != 1 or t_eval.size < 2 or not np.all(np.diff(t_eval) > 0):
        raise ValueError("t_eval: must be at least two increasing times")
    if not np.all(np.isfinite(y0)) or not np.all(np.isfinite(t_eval)):
        raise ValueError("y0 and t_eval must be finite")

    def guarded(t, y, *a):  # a NaN derivative would stall the step-size control for ever
        dy = rhs(t, y, *a)
        if not np.all(np.isfinite(dy)):
            raise IntegrationError(f"{method}: non-finite derivative at t = {t}")
        return dy

    sol = solve_ivp(guarded, (t_eval[0], t_eval[-1]), y0, method=method,
                    t_eval=t_eval, rtol=rtol, atol=atol, args=args)
    if sol.status != 0:
        reached = np.asarray(sol.t, dtype=float)
        raise IntegrationError(f"{method} failed at t = "
                               f"{reached[-1] if reached.size else t_eval[0]}: {sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise IntegrationError(f"{method} produced a non-finite state")
    return sol.y.T
