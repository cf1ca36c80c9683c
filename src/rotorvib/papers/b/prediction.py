"""Beyond paper B: the balance time predicted without integrating.

The balance-time law of :mod:`rotorvib.papers.b.law`,

    t_b = t_pk + ln(F_pk / (k r_thr)) / sigma,

takes the passage's peak bearing force ``F_pk`` and its time ``t_pk`` from an integration.
Here both come from the rotor's passage through its critical speed with the balls held at
their initial angles, exact for such balls by Duhamel's integral of the rotor's linear
equation (:mod:`rotorvib.models.balancer.passage`), and ``sigma``
from the linearised balanced state, as in the law: no equation of motion is integrated.
:func:`closed_form_law` evaluates it on every balanced run of the law's dataset;
:func:`predicted_balance_time` gives it for any design (:mod:`rotorvib.papers.b.design`
screens designs with it); :func:`prediction_rows` states how well it predicts.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.variables import described
from rotorvib.methods.bands import percentile_spread
from rotorvib.models.balancer.passage import passage_peak
from rotorvib.papers.b.choices import LAW_CHOICES
from rotorvib.papers.b.law import balance_time_law, error_text, slow_decay_rate
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.stability_maps import growth_rate

#: The closed-form law's variables in the law's dataset: (long name, units).
CLOSED_FORM_VARIABLES = {
    "t_peak_closed": ("time of the peak whirl of the critical-speed passage, balls held at "
                      "their initial angles (Duhamel's integral, no integration)", "s"),
    "force_peak_closed": ("peak bearing force of the critical-speed passage, balls held at "
                          "their initial angles", "N"),
    "predicted_closed": ("balance time by the law with the closed-form passage (no "
                         "integration)", "s"),
    "relative_error_closed": ("relative error of the closed-form law, (law - integration) / "
                              "integration", "1"),
}


def passage(setup: Setup, *, mass, eps_bar, phi0_deg, kinematics, speed=None, R=None,
            zeta=None):
    """The closed-form critical-speed passage of one balancer (its ball damping plays no part:
    the balls are held at ``phi0_deg``, shape ``(..., balls)``), from the rotor's initial
    whirl (eq. 36: from rest at ``setup.r0`` in the direction ``setup.theta0``)."""
    b = setup.balancer(mass=mass, eps_bar=eps_bar, beta=0.0, R=R, zeta=zeta)
    return passage_peak(b, setup.profile(kinematics, speed), np.radians(phi0_deg),
                        setup.r0 * np.exp(1j * setup.theta0))


def closed_form_law(setup: Setup, law: xr.Dataset) -> xr.Dataset:
    """The law's dataset (:func:`rotorvib.papers.b.law.law_dataset`) with the closed-form
    passage of every run and the balance time the law predicts from it at the law's decay rate
    (its first whirl share): :data:`CLOSED_FORM_VARIABLES`. Runs sharing a balancer, speed and
    kinematics share one passage; their ball angles set each one's unbalance."""
    t_peak = np.full(law.sizes["run"], np.nan)
    force = np.full(law.sizes["run"], np.nan)
    keys = np.stack([law[k].values for k in ("m_bar", "eps_bar", "omega_bar", "zeta", "R")],
                    axis=1)
    kinematics = law.kinematics_name.values
    wn = np.sqrt(setup.k / setup.M)
    for kin in np.unique(kinematics):
        of_kin = np.flatnonzero(kinematics == kin)
        unique, group = np.unique(keys[of_kin], axis=0, return_inverse=True)
        for j, (m_bar, eps_bar, omega_bar, zeta, R) in enumerate(unique):
            runs = of_kin[group.ravel() == j]
            p = passage(setup, mass=m_bar * setup.M, eps_bar=eps_bar,
                        phi0_deg=law.phi0.values[runs], kinematics=str(kin),
                        speed=omega_bar * wn, R=R, zeta=zeta)
            t_peak[runs], force[runs] = p.time, np.ravel(p.force)
    sigma = law.sigma.values[0] if "share" in law.sigma.dims else law.sigma.values
    predicted = balance_time_law(t_peak, force, setup.k * setup.criterion.r_threshold, sigma)
    error = (predicted - law.balance_time.values) / law.balance_time.values
    return law.assign(described({
        "t_peak_closed": ("run", t_peak), "force_peak_closed": ("run", force),
        "predicted_closed": ("run", predicted), "relative_error_closed": ("run", error),
    }, CLOSED_FORM_VARIABLES))


def predicted_balance_time(setup: Setup, *, mass, beta, eps_bar, phi0_deg, kinematics,
                           neutral: float, share: float, speed=None, R=None, zeta=None):
    """The balance time (s) the law predicts without integrating, for one ball mass (kg),
    each ball damping ratio of ``beta`` (broadcast) and each set of initial ball angles of
    ``phi0_deg`` (shape ``(..., balls)``, degrees): shape ``phi0.shape[:-1] + beta.shape``;
    NaN where the balanced state does not exist, is unstable (a mode grows faster than
    ``neutral``) or has no decaying mode carrying ``share`` of the whirl."""
    speed = setup.omega if speed is None else speed
    zeta = setup.zeta if zeta is None else zeta
    p = passage(setup, mass=mass, eps_bar=eps_bar, phi0_deg=np.asarray(phi0_deg, float),
                kinematics=kinematics, speed=speed, R=R, zeta=zeta)
    wn = np.sqrt(setup.k / setup.M)
    point = (mass / setup.M, eps_bar, zeta, np.asarray(beta, float), speed / wn)
    sigma = slow_decay_rate(*point, neutral=neutral, share=share) * wn
    # an unstable balanced state is never reached, whatever its decaying modes
    sigma = np.where(growth_rate(*point) > neutral, np.nan, sigma)
    per_run = (...,) + (None,) * np.ndim(sigma)          # the passage's runs, then beta
    return balance_time_law(np.asarray(p.time)[per_run], np.asarray(p.force)[per_run],
                            setup.k * setup.criterion.r_threshold, sigma)


def prediction_rows(law: xr.Dataset, close, *, resamples: int = 200,
                    seed: int = 0) -> list[Reproduced]:
    """Beyond the paper: does the law predict the median balanced run's balance time within
    the comparison's "close" with no integration at all (closed-form passage, decay rate of
    the linearisation)? The margin is ``close`` less the median absolute relative error, its
    uncertainty twice the bootstrap standard deviation of that median; the explanation gives
    the errors study by study, the integrated passage's for comparison, and where it fails."""
    errors = law.relative_error_closed.values
    valued = np.isfinite(errors)
    choices = LAW_CHOICES + ("the balls held at their initial angles through the passage (a "
                             "model choice of the closed form)", close.choice)
    if not valued.any():
        return [Reproduced.claim("B", "balance_law_closed_form", None,
                                 "undetermined: no balanced run with a decaying mode",
                                 choices=choices)]
    e = np.abs(errors[valued])
    median = float(np.median(e))
    spread = float(percentile_spread(e, [50.0], resamples=resamples, seed=seed)[0])
    holds = close.margins(lambda c: Margin(c - median, 2 * spread, "relative",
                                           f"bootstrap of the median over {e.size} runs"))
    source = law.source.values
    integrated = law.relative_error.values
    integrated = integrated[0] if integrated.ndim == 2 else integrated
    worst = max(dict.fromkeys(source), key=lambda s: np.nanmedian(np.abs(errors[source == s])))
    force = law.force_peak_closed.values / law.force_peak.values - 1
    times = law.balance_time.values
    quarter = np.digitize(times, np.nanpercentile(times[valued], [25, 50, 75]))
    return [Reproduced.claim(
        "B", "balance_law_closed_form", holds,
        f"with the passage of frozen balls (no integration) the law's error over "
        f"{e.size} balanced runs is {error_text(errors)}, against {error_text(integrated)} "
        f"with the integrated passage; by study: "
        + "; ".join(f"{s}: {error_text(errors[source == s])}" for s in dict.fromkeys(source))
        + f". Worst study: {worst}. Median signed error by quarter of the integrated balance "
          "time, fastest first: " + ", ".join(
              f"{np.median(errors[valued & (quarter == q)]):+.1%}" for q in range(4))
        + ": like the law with the integrated passage it over-predicts the runs that balance "
          "fastest. The passage's peak force, exact for balls held still (Duhamel's integral "
          "of the frozen-ball rotor under the run's own kinematics, checked against its "
          "integration), is off the integrated one by "
          f"{np.nanmedian(force):+.1%} at the median (10th-90th percentiles "
          f"{np.nanpercentile(force, 10):+.1%} to {np.nanpercentile(force, 90):+.1%}): that "
          "is the balls' motion during the passage, and the logarithm divides it by "
          "ln(F_pk / (k r_thr)) in the balance time. "
          f"Close means within {close:.0%}, the comparison's standard", choices=choices)]
