"""Beyond paper B: a design rule for the ball mass and damping, predicted, then verified by
integration, and checked on an integrated grid.

The rule has two stages.  The *screen* evaluates the balance time the law predicts without
integrating (:func:`rotorvib.papers.b.prediction.predicted_balance_time`: the frozen-ball
passage and the decay rate of the linearised balanced state) on a grid of ball masses and
damping ratios, in milliseconds, and keeps the ``verify`` masses of least predicted time.  The
prediction cannot choose beta: with the balls held still the passage does not depend on it,
and a design whose balls lock into a non-synchronous whirl is linearly stable all the same.
So the *verification* integrates those masses with every beta of the grid from every initial
condition (a few hundred run-ups: seconds) and recommends the design of least integrated mean
time among those that balance from all of them.  The ball mass keeps a margin above the
existence bound ``m >= eps_bar M / 2`` (eq. 34), the least mass it allows always screened: a
machine whose unbalance is larger than assumed would have no balanced state at all.

:func:`design_dataset` runs the rule under each kinematics on each machine and integrates a
check grid there; :func:`design_rows` states whether the recommendation is within ``within`` of
the grid's best mean balance time, under each (a DEPENDS names where it fails).
"""

from __future__ import annotations

import time as clock
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.variables import described
from rotorvib.models.balancer.layout import metric
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.choices import LAW_CHOICES
from rotorvib.papers.b.prediction import predicted_balance_time
from rotorvib.papers.b.setup import Setup


@dataclass(frozen=True)
class DesignRule:
    """The rule's answer.  The screen: the mean predicted balance time over the initial
    conditions on the masses screened (the grid's above the margin and the least mass it
    allows) and the grid's betas (``mean_time[mass, beta]``, s; NaN where a design has no
    decaying balanced state).  The verification: the ``candidates`` (rows ``(mass, beta)``: the
    masses of least predicted time with every beta), each integrated from every initial
    condition (``verified_time[candidate, ic]``, s; NaN: not balanced by
    ``t_end``; ``verified_outcome`` how each run ends,
    :data:`~rotorvib.models.balancer.outcomes.OUTCOMES`).  The recommendation: the verified candidate of least integrated mean time that
    balances from every initial condition (NaN when none does), its predicted mean time
    ``predicted`` and integrated one ``time``; ``seconds`` the rule took."""

    masses: np.ndarray
    betas: np.ndarray
    mean_time: np.ndarray
    candidates: np.ndarray
    verified_time: np.ndarray
    verified_outcome: np.ndarray
    mass: float
    beta: float
    predicted: float
    time: float
    seconds: float


def integrated_metrics(setup: Setup, designs, *, eps_bar, phi0_deg, kinematics,
                       speed=None) -> np.ndarray:
    """The metrics rows (:data:`~rotorvib.models.balancer.layout.METRICS`) of each design (rows
    ``(mass, beta)``) integrated from each initial condition of ``phi0_deg`` (rows, degrees):
    shape ``(designs, ics, metrics)``."""
    designs, phi0_deg = np.atleast_2d(designs), np.atleast_2d(phi0_deg)
    metrics = setup.runs([setup.run_inputs(mass=m, eps_bar=eps_bar, beta=b, phi0_deg=angles,
                                           kinematics=kinematics, speed=speed)
                          for m, b in designs for angles in phi0_deg], progress=False)
    return metrics.reshape(len(designs), len(phi0_deg), -1)


def balance_times(metrics: np.ndarray) -> np.ndarray:
    """The balance time (s) of each metrics row, NaN where the run does not balance by the
    criterion's ``t_end``."""
    return np.where(metric(metrics, "balanced") == 1, metric(metrics, "balance_time"), np.nan)


def integrated_times(setup: Setup, designs, **run) -> np.ndarray:
    """:func:`balance_times` of :func:`integrated_metrics`: shape ``(designs, ics)``."""
    return balance_times(integrated_metrics(setup, designs, **run))


def design_rule(setup: Setup, *, masses, betas, eps_bar, phi0_deg, kinematics, neutral: float,
                share: float, verify: int, mass_margin: float, speed=None) -> DesignRule:
    """The ball mass and damping ratio with the least mean integrated balance time over the
    initial ball angles ``phi0_deg`` (rows, degrees), for the machine, run-up and criterion of
    ``setup`` (module docstring).  The screen predicts the mean time of every design of
    ``masses`` x ``betas``, the masses below ``(1 + mass_margin)`` times the existence bound
    left out and that least mass added; the ``verify`` masses of least predicted time (over
    beta) are integrated with every beta of the grid, since the prediction does not resolve
    beta.  ``ValueError`` if no design of the grid is predicted to balance."""
    start = clock.perf_counter()
    lightest = (1 + mass_margin) * eps_bar * setup.M / 2
    masses, betas = np.unique(np.asarray(masses, float)), np.asarray(betas, float)
    masses = np.concatenate([[lightest], masses[masses > lightest * (1 + 1e-12)]])
    mean = np.array([np.mean(predicted_balance_time(
        setup, mass=m, beta=betas, eps_bar=eps_bar, phi0_deg=phi0_deg, kinematics=kinematics,
        neutral=neutral, share=share, speed=speed), axis=0) for m in masses])
    best = np.where(np.isfinite(mean), mean, np.inf).min(axis=1)
    if not np.isfinite(best).any():
        raise ValueError("no design of the grid balances: no ball mass and damping to "
                         "recommend (is the ball mass within the margin of half the "
                         "unbalance, eq. 34?)")
    chosen = np.argsort(best)[:min(verify, int(np.isfinite(best).sum()))]
    candidates = np.array([(masses[i], b) for i in chosen for b in betas])
    metrics = integrated_metrics(setup, candidates, eps_bar=eps_bar, phi0_deg=phi0_deg,
                                 kinematics=kinematics, speed=speed)
    verified, ends = balance_times(metrics), metric(metrics, "outcome")
    means = np.where(np.isfinite(verified).all(axis=1), verified.mean(axis=1), np.inf)
    pick = int(np.argmin(means))
    if not np.isfinite(means[pick]):
        return DesignRule(masses, betas, mean, candidates, verified, ends, np.nan, np.nan,
                          np.nan, np.nan, clock.perf_counter() - start)
    mass, beta = candidates[pick]
    predicted = mean[np.searchsorted(masses, mass), np.searchsorted(betas, beta)]
    return DesignRule(masses, betas, mean, candidates, verified, ends, float(mass), float(beta),
                      float(predicted), float(means[pick]), clock.perf_counter() - start)


#: The design dataset's variables: (dimensions' tail after (machine, kinematics), long name,
#: units).
DESIGN_VARIABLES = {
    "mean_time": (("mass", "beta"), "mean predicted balance time over the initial conditions "
                                    "(frozen-ball passage and linear decay, no integration)", "s"),
    "candidate_mass": (("candidate",), "ball mass of each verified candidate", "kg"),
    "candidate_beta": (("candidate",), "ball damping ratio of each verified candidate", "1"),
    "candidate_time": (("candidate", "ic"), "integrated balance time of each candidate (NaN: "
                                            "not balanced by t_end)", "s"),
    "recommended_mass": ((), "recommended ball mass (NaN: no candidate balances from every "
                             "initial condition)", "kg"),
    "recommended_beta": ((), "recommended ball damping ratio", "1"),
    "recommended_predicted": ((), "mean predicted balance time of the recommendation", "s"),
    "recommended_time": ((), "mean integrated balance time of the recommendation", "s"),
    "rule_runs": ((), "run-ups the rule integrated to verify its candidates", "1"),
    "check_time": (("check_mass", "check_beta", "ic"), "integrated balance time on the check "
                                                       "grid (NaN: not balanced by t_end)", "s"),
}


def design_dataset(setup: Setup, *, masses, betas, ics: dict, kinematics, machines: dict,
                   neutral: float, share: float, verify: int, mass_margin: float,
                   check: dict) -> xr.Dataset:
    """The design rule (:func:`design_rule`) under each of ``kinematics`` on each machine of
    ``machines`` (name -> ``{"zeta", "eps_bar", "speed"}``: paper B's machine with that support
    damping, eccentricity and operating speed), the balls starting from each initial condition
    of ``ics`` (name -> angles, degrees), and the check grid ``check["mass"]`` x
    ``check["beta"]`` integrated there from every initial condition."""
    angles = list(ics.values())
    out = {name: np.full((len(machines), len(kinematics)) + shape, np.nan)
           for name, shape in (("mean_time", (len(masses), len(betas))),
                               ("candidate_mass", (verify * len(betas),)),
                               ("candidate_beta", (verify * len(betas),)),
                               ("candidate_time", (verify * len(betas), len(ics))),
                               ("check_time", (len(check["mass"]), len(check["beta"]),
                                               len(ics))))}
    scalars = {name: np.full((len(machines), len(kinematics)), np.nan)
               for name in ("recommended_mass", "recommended_beta", "recommended_predicted",
                            "recommended_time", "rule_runs")}
    for a, machine in enumerate(machines.values()):
        here = replace(setup, zeta=machine["zeta"])
        common = {"eps_bar": machine["eps_bar"], "speed": machine["speed"]}
        for k, kin in enumerate(kinematics):
            rule = design_rule(here, masses=masses, betas=betas, phi0_deg=angles, kinematics=kin,
                               neutral=neutral, share=share, verify=verify,
                               mass_margin=mass_margin, **common)
            n = len(rule.candidates)
            on_grid = np.isin(masses, rule.masses)
            out["mean_time"][a, k][on_grid] = rule.mean_time[np.isin(rule.masses, masses)]
            out["candidate_mass"][a, k, :n], out["candidate_beta"][a, k, :n] = rule.candidates.T
            out["candidate_time"][a, k, :n] = rule.verified_time
            grid = np.stack(np.meshgrid(check["mass"], check["beta"], indexing="ij"), -1)
            out["check_time"][a, k] = integrated_times(
                here, grid.reshape(-1, 2), phi0_deg=angles, kinematics=kin, **common
            ).reshape(out["check_time"].shape[2:])
            for name, value in (("recommended_mass", rule.mass), ("recommended_beta", rule.beta),
                                ("recommended_predicted", rule.predicted),
                                ("recommended_time", rule.time),
                                ("rule_runs", rule.verified_time.size)):
                scalars[name][a, k] = value
    lead = ("machine", "kinematics")
    data = {name: (lead + DESIGN_VARIABLES[name][0], values)
            for name, values in {**out, **scalars}.items()}
    return xr.Dataset(
        described(data, {k: v[1:] for k, v in DESIGN_VARIABLES.items()}),
        coords={
            "machine": ("machine", list(machines), {"long_name": "machine"}),
            "kinematics": ("kinematics", list(kinematics), {"long_name": "disk kinematics"}),
            "mass": ("mass", np.asarray(masses, float), {"long_name": "ball mass m",
                                                         "units": "kg"}),
            "beta": ("beta", np.asarray(betas, float), {"long_name": "ball damping ratio beta",
                                                        "units": "1"}),
            "check_mass": ("check_mass", np.asarray(check["mass"], float),
                           {"long_name": "ball mass of the check grid", "units": "kg"}),
            "check_beta": ("check_beta", np.asarray(check["beta"], float),
                           {"long_name": "ball damping ratio of the check grid", "units": "1"}),
            "ic_name": ("ic", list(ics), {"long_name": "initial ball angles, eq. (39)"}),
            **{f"{key}_of_machine": ("machine", [float(m[key]) for m in machines.values()],
                                     {"long_name": label, "units": units})
               for key, label, units in (("zeta", "support damping ratio", "1"),
                                         ("eps_bar", "eccentricity ratio eps/R", "1"),
                                         ("speed", "operating speed", "rad/s"))}},
        attrs=dataset_attrs(
            "a design rule for the ball mass and damping, verified",
            "Beyond the paper: the ball mass and damping predicted without integrating (the "
            "screen), the masses of least predicted time integrated with every beta from every "
            "initial condition (the verification), the recommendation, and an integrated check "
            "grid, under each kinematics on each machine", "Tables 1-2, section 9")
        | {"verify": verify, "mass_margin": mass_margin, "within": check["within"]})


def design_rows(design: xr.Dataset) -> list[Reproduced]:
    """Beyond the paper: is the recommended design's integrated mean balance time within
    ``within`` of the best mean of the integrated check grid, under each kinematics on each
    machine (a variant each, so that a failure anywhere is a DEPENDS naming it)?  Margin:
    ``within - (t_rec / t_best - 1)``; a recommendation that does not exist (no candidate
    balances from every initial condition) fails."""
    within = float(design.attrs["within"])
    holds, parts = {}, []
    for machine in design.machine.values:
        m = design.sel(machine=machine)
        said = (f"{machine} (zeta = {float(m.zeta_of_machine):g}, eps_bar = "
                f"{float(m.eps_bar_of_machine):g}, {float(m.speed_of_machine):g} rad/s)")
        for kin in m.kinematics.values:
            d = m.sel(kinematics=kin)
            check = d.check_time.values
            means = np.where(np.isfinite(check).all(axis=-1), check.mean(axis=-1), np.nan)
            best = np.unravel_index(np.nanargmin(means), means.shape)
            t_best, t_rec = float(means[best]), float(d.recommended_time)
            gap = t_rec / t_best - 1 if np.isfinite(t_rec) else np.inf
            holds[f"{machine}, {kin}"] = Margin(within - gap, 0.0, "relative",
                                                f"{check.size} integrated check runs (exact)")
            recommended = (f"m = {1e3 * float(d.recommended_mass):.3g} g, beta = "
                           f"{float(d.recommended_beta):.3g}, {t_rec:.3g} s integrated "
                           f"({float(d.recommended_predicted):.3g} s predicted), {gap:+.1%} "
                           "from the grid's best" if np.isfinite(t_rec) else
                           "none (no candidate balances from every initial condition)")
            parts.append(f"{said}, {kin} kinematics: recommended {recommended}; the grid's "
                         f"best m = {1e3 * float(d.check_mass[best[0]]):.3g} g, beta = "
                         f"{float(d.check_beta[best[1]]):.3g}, {t_best:.3g} s; "
                         f"{int(np.isnan(means).sum())} of {means.size} grid designs do not "
                         "balance from every initial condition")
    return [Reproduced.claim(
        "B", "design_rule_checked", holds,
        f"the {design.attrs['verify']} masses of least predicted time integrated with every "
        f"beta of the grid from {', '.join(design.ic_name.values)}, masses at least "
        f"{1 + design.attrs['mass_margin']:g} times the existence bound, the recommendation "
        f"against an integrated grid (within {within:.0%} of its best mean): " + "; ".join(parts),
        choices=LAW_CHOICES + ("paper_b.design_rule (the searched grid, the candidates "
                               "verified, the mass margin, the check grid and its tolerance, "
                               "the second machine, chosen)",))]
