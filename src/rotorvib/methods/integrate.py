"""Reference ODE integration with failure reporting.

A failed integration (solver failure, non-finite state) raises :class:`IntegrationError`; it is
never turned into numbers.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp


class IntegrationError(RuntimeError):
    """An ODE integration did not reach its end time with a finite state."""


def integrate(rhs, y0, t_eval, *, rtol: float, atol: float, method: str = "DOP853",
              args: tuple = ()) -> np.ndarray:
    """Integrate ``y' = rhs(t, y, *args)`` from ``t_eval[0]``; return ``y`` at ``t_eval``, shape
    ``(len(t_eval), len(y0))``."""
    t_eval = np.asarray(t_eval, dtype=float)
    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), np.asarray(y0, dtype=float), method=method,
                    t_eval=t_eval, rtol=rtol, atol=atol, args=args)
    if sol.status != 0:
        raise IntegrationError(f"{method} failed at t = {sol.t[-1] if sol.t.size else t_eval[0]}: "
                               f"{sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise IntegrationError(f"{method} produced a non-finite state")
    return sol.y.T
