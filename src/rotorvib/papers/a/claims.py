"""Paper A's claims measured on the datasets of :mod:`rotorvib.papers.a.studies`."""

from __future__ import annotations

from functools import partial

import numpy as np
import xarray as xr

from rotorvib.choices import Close

from rotorvib.comparison import Margin, Reproduced

PAPER = "A"
_row = partial(Reproduced.of, PAPER)
_claim = partial(Reproduced.claim, PAPER)


#: What every claim of paper A rests on: the digest's parameters (the paper's were lost).
CASE = "paper_a.case, paper_a.initial_offset (chosen by the digest: the paper's values are lost)"
GRID = "paper_a.fig7 (the (beta, Omega) grid and zetas, chosen by the digest)"


def _rk_basis(rk: dict) -> str:
    return f"Runge-Kutta ({rk['method']}) at rtol {rk['rtol']:g}"


def _differing(a, b) -> Margin:
    """Two stable sets are identical when no grid point differs: minus the count, exact."""
    return Margin(0.0 - np.count_nonzero(a != b), 0.0, "grid points",
                  "count of grid points whose stability differs (exact)")


def accuracy_rows(resp: xr.Dataset, i: int, window: float, close: Close,
                  rk: dict) -> list[Reproduced]:
    """Two-term error against Runge-Kutta relative to the local amplitude, over the first and
    the last ``window`` of tau (the paper: accurate at short and at long times); accurate
    means within the comparison's standard for "close"."""
    methods = [str(m) for m in resp.method_name.values]
    rk_i, two = methods.index("runge_kutta"), methods.index("two_term")
    tau = resp.tau.values
    errors = {}
    for name, sel in (("short", tau <= tau[0] + window), ("long", tau >= tau[-1] - window)):
        u = resp.u.values[i, :, sel]
        errors[name] = float(np.abs(u[:, two] - u[:, rk_i]).max() / np.abs(u[:, rk_i]).max())
    worst = max(errors.values())
    return [_claim("short_and_long_time_accuracy",
                   close.margins(lambda c: Margin(c - worst, rk["rtol"],
                                                  "relative to the amplitude", _rk_basis(rk))),
                   f"two-term error against Runge-Kutta relative to the largest |x/R| in the "
                   f"window: {errors['short']:.1e} for tau <= {tau[0] + window:g}, "
                   f"{errors['long']:.1e} for tau >= {tau[-1] - window:g} (accurate means "
                   f"within {close:.0%}, the comparison's standard for close)",
                   choices=(close.choice, CASE, "paper_a.zoom (the short window, chosen)"))]


def more_terms_rows(region: xr.Dataset) -> list[Reproduced]:
    """The two-term solution's exponents are lambda_j and lambda_j + lambda_k, so its largest
    growth rate is max(g, 2 g) for the one-term growth rate g: the same sign everywhere."""
    g = region.growth_mms.values
    return [_claim("more_terms_same_region", _differing(np.maximum(g, 2 * g) < 0, g < 0),
                   f"on all {g.size} points of Fig 7's grid the two-term exponents (lambda_j and "
                   "lambda_j + lambda_k) decay exactly where the one-term ones do: a second term "
                   "cannot move the stability region, which is the spectrum of J. True by "
                   "construction: the row checks the code, and cannot fail for the paper's claim",
                   choices=(GRID,))]


def reproduce(*, resp: xr.Dataset, region: xr.Dataset, err: xr.Dataset, case_beta: float,
              window: float, close: Close, rk: dict, paper_values: dict) -> list[Reproduced]:
    """All paper A rows; ``window`` is the length in tau of the short- and long-time windows
    of the accuracy claim, ``close`` the comparison's standard for "close" (a relative
    difference), ``rk`` the Runge-Kutta settings of the responses."""
    methods = [str(m) for m in resp.method_name.values]
    rk_i, one, two = (methods.index(m) for m in ("runge_kutta", "one_term", "two_term"))
    i = int(np.argmin(np.abs(resp.beta.values - case_beta)))
    final = float(resp.alpha1.values[i, rk_i, -1])
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
    ratio = err.error_two_term_linear.values / err.error_two_term.values
    rows.append(_row("mms2_linear_error_slope", float(err.slope_two_term_linear),
                     "log-log slope of the two-term error with linear constants (one-term "
                     "constants plus a homogeneous part cancelling the second-order term at "
                     "tau = 0); theory: O(delta^3), as with the eight nonlinear equations. Its "
                     "error over theirs: " + ", ".join(
                         f"{r:.3g} (delta = {d:g})" for r, d in zip(ratio, err.delta.values))))
    amp = np.abs(resp.u.values[i, rk_i]).max()
    e1 = np.abs(resp.u.values[i, one] - resp.u.values[i, rk_i]).max()
    e2 = np.abs(resp.u.values[i, two] - resp.u.values[i, rk_i]).max()
    rows.append(_claim("two_term_close_to_rk",
                       close.margins(lambda c: Margin(c - e2 / amp, rk["rtol"],
                                                      "relative to the amplitude",
                                                      _rk_basis(rk))),
                       f"max error in x/R {e2:.2e} (two terms) and {e1:.2e} (one term) for an "
                       f"amplitude {amp:.2e}: {e2 / amp:.1e} of it (very close means within "
                       f"{close:.0%}, the comparison's standard for close)",
                       choices=(close.choice, CASE)))
    decay = -resp.eigenvalue_real.max("mode").values
    best = int(np.argmax(decay))
    rounding = 1e-12 * float(np.abs(decay).max())
    rows.append(_claim("beta_effect",
                       Margin(float(decay[1:-1].max() - max(decay[0], decay[-1])), rounding,
                              "1/tau", "eigenvalues of J at the betas of Figs 5-6 (rounding)"),
                       "slowest decay rate " + ", ".join(
                           f"{d:.4f} (beta = {b:g})" for d, b in zip(decay, resp.beta.values))
                       + "; the fastest balance is at an intermediate beta only if the largest "
                         f"rate is neither at the smallest nor at the largest beta (it is at "
                         f"beta = {float(resp.beta[best]):g})",
                       choices=(CASE, "paper_a.fig5_6.betas (chosen by the digest)")))
    u0 = np.hypot(resp.u.values[i, rk_i, 0], resp.v.values[i, rk_i, 0])
    u_end = np.hypot(resp.u.values[i, rk_i, -1], resp.v.values[i, rk_i, -1])
    angle_gap = [abs(abs(float(resp[a].values[i, rk_i, j])) - float(resp.balanced_angle))
                 for a in ("alpha1", "alpha2") for j in (0, -1)]
    slowest = float(resp.eigenvalue_real.values[i].max())
    rows.append(_claim("decays_to_balanced_state",
                       Margin(-slowest, 1e-12 * float(np.abs(resp.eigenvalue_real.values[i]).max()),
                              "1/tau", "slowest decay rate of J (rounding)"),
                       f"beta = {float(resp.beta[i]):g}: slowest eigenvalue real part "
                       f"{slowest:.4f} (< 0: the balanced state attracts); |(u, v)| falls from "
                       f"{u0:.2e} to {u_end:.2e} by tau = {float(resp.tau[-1]):g}; the balls end "
                       f"{angle_gap[1]:.3f} and {angle_gap[3]:.3f} deg from "
                       f"+/-{float(resp.balanced_angle):.1f} deg (started {angle_gap[0]:.1f} and "
                       f"{angle_gap[2]:.1f} deg away)",
                       choices=(CASE,)))
    mms, lyap = region.growth_mms.values < 0, region.growth_lyapunov.values < 0
    rows.append(_claim("identical_regions", _differing(mms, lyap),
                       f"the stable sets of the two methods "
                       f"{'coincide' if np.array_equal(mms, lyap) else 'differ'} on every grid "
                       f"point ({mms.size} points); their growth rates differ by at most "
                       f"{growth_gap:.1e}. True by construction: both are the spectrum of the "
                       "same Jacobian (roots of the 4x4 lambda-matrix, eigenvalues of the 8x8), "
                       "so the row checks two code paths, not a property of the balancer",
                       choices=(GRID,)))
    return rows + accuracy_rows(resp, i, window, close, rk) + more_terms_rows(region)
