"""Paper A's claims measured on the datasets of :mod:`rotorvib.papers.a.studies`."""

from __future__ import annotations

from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison import Reproduced, supported

PAPER = "A"
_row = partial(Reproduced.of, PAPER)


def reproduce(*, resp: xr.Dataset, region: xr.Dataset, err: xr.Dataset, case_beta: float,
              paper_values: dict) -> list[Reproduced]:
    methods = [str(m) for m in resp.method_name.values]
    rk, one, two = (methods.index(m) for m in ("runge_kutta", "one_term", "two_term"))
    i = int(np.argmin(np.abs(resp.beta.values - case_beta)))
    final = float(resp.alpha1.values[i, rk, -1])
    rows = [_row("equilibrium_angle", final,
                 f"Runge-Kutta ball 1 angle at tau = {float(resp.tau[-1]):g}; the formula "
                 f"arccos(-1/(2 rho)) gives {float(resp.balanced_angle):.4f} deg at the chosen rho")]
    gap = np.nanmax(np.abs(region.critical_speed_mms.values - region.critical_speed_lyapunov.values))
    growth_gap = float(np.max(np.abs(region.growth_mms - region.growth_lyapunov)))
    rows.append(_row("stability_boundary_mms_vs_lyapunov", gap,
                     f"largest difference of the critical speed over zeta and beta on the grid; "
                     f"growth rates differ by at most {growth_gap:.1e}: both methods solve the "
                     "same eigenvalue problem (roots of the 4x4 lambda-matrix against the 8x8 "
                     "Jacobian), computed through separate code paths"))
    rows.append(_row("mms1_error_slope", float(err.slope_one_term),
                     "log-log slope of the one-term error against the initial distance (three "
                     "smallest distances); theory: O(delta^2)"))
    rows.append(_row("mms2_error_slope", float(err.slope_two_term),
                     "log-log slope of the two-term error; theory: O(delta^3)"))
    amp = np.abs(resp.u.values[i, rk]).max()
    e1 = np.abs(resp.u.values[i, one] - resp.u.values[i, rk]).max()
    e2 = np.abs(resp.u.values[i, two] - resp.u.values[i, rk]).max()
    rows.append(_row("two_term_close_to_rk", None,
                     f"{supported(e2 < e1 and e2 < 0.05 * amp)}: max error in x/R {e2:.2e} (two terms)"
                     f" and {e1:.2e} (one term) for an amplitude {amp:.2e}"))
    decay = -resp.eigenvalue_real.max("mode").values
    best = int(np.argmax(decay))
    rows.append(_row("beta_effect", None,
                     f"{supported(0 < best < len(decay) - 1)}: slowest decay rate "
                     + ", ".join(f"{d:.4f} (beta = {b:g})" for d, b in zip(decay, resp.beta.values))
                     + "; the fastest balance is at an intermediate beta"
                     if 0 < best < len(decay) - 1 else
                     f"{supported(False)}: slowest decay rate " + ", ".join(
                         f"{d:.4f} (beta = {b:g})" for d, b in zip(decay, resp.beta.values))))
    same = bool(np.array_equal(region.growth_mms.values < 0, region.growth_lyapunov.values < 0))
    rows.append(_row("identical_regions", None,
                     f"{supported(same)}: the stable sets of the two methods "
                     f"{'coincide' if same else 'differ'} on every grid point"))
    return rows
