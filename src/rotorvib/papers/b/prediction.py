"""Beyond paper B: the balance time predicted without integrating, and a design rule for the
ball mass and damping.

The balance-time law of :mod:`rotorvib.papers.b.law`,

    t_b = t_pk + ln(F_pk / (k r_thr)) / sigma,

takes the passage's peak bearing force ``F_pk`` and its time ``t_pk`` from an integration.
Here both come from the rotor's passage through its critical speed with the balls held at
their initial angles, exact for such balls by Duhamel's integral of the rotor's linear
equation (:mod:`rotorvib.models.balancer.passage`), and ``sigma``
from the linearised balanced state, as in the law: no equation of motion is integrated.
:func:`closed_form_law` evaluates it on every balanced run of the law's dataset;
:func:`design_rule` searches a grid of ball masses and damping ratios for the least mean
predicted balance time over given initial ball angles, with the band the law's measured
errors put around it; :func:`prediction_rows` states how well it predicts.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from rotorvib.comparison import Margin, Reproduced
from rotorvib.io.variables import described
from rotorvib.methods.bands import percentile_spread
from rotorvib.models.balancer.layout import METRICS
from rotorvib.models.balancer.passage import passage_peak
from rotorvib.papers.b.choices import LAW_CHOICES
from rotorvib.papers.b.law import balance_time_law, error_text, slow_decay_rate
from rotorvib.papers.b.attributes import dataset_attrs
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


@dataclass(frozen=True)
class DesignRule:
    """The design rule's answer: the mean predicted balance time over the initial ball angles
    on the grid (``mean_time[mass, beta]``, s), the recommended ball mass (kg) and damping
    ratio, the predicted time there and the band ``(low, high)`` the law's measured relative
    errors put around it (the integrated time lies in it as often as in the errors'
    percentiles)."""

    masses: np.ndarray
    betas: np.ndarray
    mean_time: np.ndarray
    mass: float
    beta: float
    time: float
    band: tuple[float, float]


def design_rule(setup: Setup, *, masses, betas, eps_bar, phi0_deg, kinematics, neutral: float,
                share: float, error_band=(0.0, 0.0), speed=None) -> DesignRule:
    """The ball mass and damping ratio of the grid ``masses`` x ``betas`` with the least mean
    predicted balance time over the initial ball angles ``phi0_deg`` (rows, degrees), for the
    machine, run-up and threshold of ``setup`` (:func:`predicted_balance_time`); a design
    that does not balance (no decaying balanced state) is never recommended. ``error_band``:
    relative errors ``(low, high)`` of the law (e.g. its 10th and 90th percentiles over the
    integrated runs); the band is ``time / (1 + high)`` to ``time / (1 + low)``. Evaluates
    one passage per mass and the eigenvalues of the grid: milliseconds."""
    masses, betas = np.asarray(masses, float), np.asarray(betas, float)
    mean = np.array([np.mean(predicted_balance_time(
        setup, mass=m, beta=betas, eps_bar=eps_bar, phi0_deg=phi0_deg, kinematics=kinematics,
        neutral=neutral, share=share, speed=speed), axis=0) for m in masses])
    if not np.isfinite(mean).any():
        raise ValueError("no design of the grid balances: no ball mass and damping to "
                         "recommend (is the ball mass below half the unbalance, eq. 34?)")
    i, j = np.unravel_index(np.nanargmin(mean), mean.shape)
    low, high = error_band
    time = float(mean[i, j])
    return DesignRule(masses, betas, mean, float(masses[i]), float(betas[j]), time,
                      (time / (1 + high), time / (1 + low)))


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
        f"with the passage in closed form (no integration) the law's error over "
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


def design_dataset(setup: Setup, law: xr.Dataset, *, masses, betas, eps_bar, ics: dict,
                   kinematics: str, speed: float, neutral: float, share: float,
                   band_percentiles=(10.0, 90.0)) -> xr.Dataset:
    """The design rule (:func:`design_rule`) for the machine and run-up of ``setup`` at
    ``eps_bar`` and ``speed``, the balls starting from each initial condition of ``ics``
    (name -> angles, degrees), its band from the closed-form law's signed errors over the
    law's runs (``band_percentiles``), and the check: the recommended design integrated from
    each initial condition (one run-up each). The grid is cut to the ball masses and damping
    ratios the law's runs span: the rule does not extrapolate the law."""
    errors = law.relative_error_closed.values
    band = tuple(float(np.nanpercentile(errors, q)) for q in band_percentiles)
    domain = {"mass": setup.M * np.array([law.m_bar.min(), law.m_bar.max()]),
              "beta": np.array([law.beta.min(), law.beta.max()])}
    masses, betas = (_within(np.asarray(grid, float), domain[name])
                     for name, grid in (("mass", masses), ("beta", betas)))
    rule = design_rule(setup, masses=masses, betas=betas, eps_bar=eps_bar,
                       phi0_deg=list(ics.values()), kinematics=kinematics, neutral=neutral,
                       share=share, error_band=band, speed=speed)
    metrics = setup.runs([setup.run_inputs(mass=rule.mass, eps_bar=eps_bar, beta=rule.beta,
                                           phi0_deg=angles, kinematics=kinematics, speed=speed)
                          for angles in ics.values()], progress=False)
    integrated = np.where(metrics[:, METRICS.index("balanced")] == 1,
                          metrics[:, METRICS.index("balance_time")], np.nan)
    edges = [name for name, value, grid in (("mass", rule.mass, rule.masses),
                                            ("beta", rule.beta, rule.betas))
             if value in (grid.min(), grid.max())]
    return xr.Dataset(
        described({
            "mean_time": (("mass", "beta"), rule.mean_time),
            "recommended_mass": ((), rule.mass), "recommended_beta": ((), rule.beta),
            "recommended_time": ((), rule.time),
            "band_low": ((), rule.band[0]), "band_high": ((), rule.band[1]),
            "integrated_time": ("ic", integrated),
        }, DESIGN_VARIABLES),
        coords={"mass": ("mass", rule.masses, {"long_name": "ball mass m", "units": "kg"}),
                "beta": ("beta", rule.betas, {"long_name": "ball damping ratio beta",
                                              "units": "1"}),
                "ic_name": ("ic", list(ics), {"long_name": "initial ball angles, eq. (39)"})},
        attrs=dataset_attrs(
            "a design rule for the ball mass and damping",
            "Beyond the paper: the ball mass and damping with the least mean balance time over "
            "the initial conditions, predicted without integrating (closed-form passage, decay "
            "rate of the linearised balanced state), with the band of the law's "
            f"{band_percentiles[0]:g}th-{band_percentiles[1]:g}th percentile errors, and the "
            "recommendation integrated from each initial condition",
            "Tables 1-2, section 9")
        | {"eps_bar": eps_bar, "speed_rad_s": speed, "kinematics": kinematics,
           "band_percentiles": list(band_percentiles),
           "domain": "; ".join(f"{name} {lo:g} to {hi:g}" for name, (lo, hi) in domain.items()),
           "recommended_on_grid_edge": ", ".join(edges) or "none"})


def _within(grid: np.ndarray, bounds) -> np.ndarray:
    """The points of ``grid`` within ``bounds`` (the law's tested range: the rule does not
    extrapolate); ``ValueError`` if none is."""
    inside = grid[(grid >= bounds[0] * (1 - 1e-12)) & (grid <= bounds[1] * (1 + 1e-12))]
    if not inside.size:
        raise ValueError(f"no point of the grid {grid.min():g}-{grid.max():g} lies in the range "
                         f"{bounds[0]:g}-{bounds[1]:g} the law was tested on")
    return inside


#: The design rule's variables: (long name, units).
DESIGN_VARIABLES = {
    "mean_time": ("mean predicted balance time over the initial conditions (closed-form law)",
                  "s"),
    "recommended_mass": ("recommended ball mass (least mean predicted balance time)", "kg"),
    "recommended_beta": ("recommended ball damping ratio", "1"),
    "recommended_time": ("mean predicted balance time of the recommended design", "s"),
    "band_low": ("low end of the band the law's errors put around the recommended time", "s"),
    "band_high": ("high end of the band the law's errors put around the recommended time", "s"),
    "integrated_time": ("balance time of the recommended design, integrated (NaN: not balanced "
                        "by t_end)", "s"),
}


def design_rows(design: xr.Dataset) -> list[Reproduced]:
    """Beyond the paper: does the integrated mean balance time of the design the rule
    recommends lie in the band the rule gives for it? The margin is the integrated mean's
    distance inside the band's nearer end, relative to it (negative outside; undetermined
    when a run from one of the initial conditions does not balance)."""
    integrated = design.integrated_time.values
    low, high = float(design.band_low), float(design.band_high)
    mean = float(np.mean(integrated))
    design_text = (f"m = {1e3 * float(design.recommended_mass):.3g} g, beta = "
                   f"{float(design.recommended_beta):.3g} at eps_bar = {design.attrs['eps_bar']:g}"
                   f", {design.attrs['speed_rad_s']:g} rad/s, {design.attrs['kinematics']} "
                   "kinematics")
    edge = design.attrs["recommended_on_grid_edge"]
    where = (f". The grid is searched where the law was tested ({design.attrs['domain']}; "
             "below beta 0.1 the balls of a linearly stable design may never settle, which "
             "the linear law cannot see)"
             + ("" if edge == "none" else
                f"; the recommendation lies on the searched grid's edge in {edge}, so the "
                "optimum may lie beyond it"))
    holds = (None if not np.isfinite(mean) else
             Margin(min(mean - low, high - mean) / mean, 0.0, "relative",
                    f"{integrated.size} integrated run-ups (exact)"))
    return [Reproduced.claim(
        "B", "design_rule_checked", holds,
        f"the rule recommends {design_text}: mean balance time {float(design.recommended_time):.3g}"
        f" s predicted, band {low:.3g}-{high:.3g} s ({design.attrs['band_percentiles'][0]:g}th-"
        f"{design.attrs['band_percentiles'][1]:g}th percentile errors of the closed-form law); "
        f"integrated from {', '.join(design.ic_name.values)}: "
        + ", ".join(f"{t:.3g} s" if np.isfinite(t) else "not balanced by t_end"
                    for t in integrated)
        + (f", mean {mean:.3g} s" if np.isfinite(mean) else "") + where,
        choices=LAW_CHOICES + ("paper_b.design_rule (the searched grid, machine point and band "
                               "percentiles, chosen)",))]
