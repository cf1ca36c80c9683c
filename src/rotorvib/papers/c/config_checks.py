"""Paper C's configuration checks beyond the schema (:func:`problems`), each named by its key
within ``paper_c``; the workflow runs them when it reads the configuration, before any job
(:mod:`rotorvib.pipeline.config_checks`, which writes the messages)."""

from __future__ import annotations

import numpy as np

from rotorvib.checks import sobol_design_problem
from rotorvib.papers.config_problems import seed_spread_problem, tolerance_problem
from rotorvib.models.absorber.frequency_response import natural_frequencies
from rotorvib.models.absorber.parameters import Rotor, dual_absorber, undamped


def fig6_problems(c: dict) -> list[tuple[str, str]]:
    """Paper C's Fig 6 claims compare curves of the mass-ratio family: each ratio they name
    (``claims.fig6_mu``) must be one of ``mass_ratio_family.mu``."""
    family = np.asarray(c["mass_ratio_family"]["mu"], float)
    roles = c["claims"]["fig6_mu"]
    return [("mass_ratio_family.mu", f"must contain {m:g}, the mass ratio of "
                                     f"paper_c.claims.fig6_mu.{role} (Fig 6's claims compare it)")
            for role, values in roles.items() for m in np.atleast_1d(values)
            if not np.isclose(family, m).any()]


def distance_problems(c: dict) -> list[tuple[str, str]]:
    """The distance study moves both absorber sets of Table 2 by each offset: none may move a
    set to the disk centre or through it, and one must be 0 (Table 2 itself, which the claim
    sets the moved designs against)."""
    offsets = c["distance_study"]["offsets"]
    found = [] if 0 in offsets else [("distance_study.offsets", f"{offsets} must contain 0 "
                                      "(Table 2's own distances, the claim's reference)")]
    nearest = min(c["table2"]["d1"], c["table2"]["d2"])
    if nearest + min(offsets) > 0:
        return found
    return found + [("distance_study.offsets", f"{min(offsets):g} m moves the set at "
                     f"{nearest:g} m (paper_c.table2) to or through the disk centre; each "
                     f"offset must exceed {-nearest:g} m")]


def frequency_range_problems(c: dict) -> list[tuple[str, str]]:
    """Fig 5's undamped peaks are Table 2's undamped natural frequencies nearest w = 1 on
    either side (:func:`rotorvib.papers.c.claims.undamped_peaks`): the frequency range must
    hold one on each side, a grid step or more inside it, for the sampled curve to show it."""
    fr = c["frequency_response"]
    try:
        rotor = Rotor(**c["rotor"])
        natural = natural_frequencies(rotor, undamped(dual_absorber(**c["table2"])))
    except ValueError:
        return []                              # the values' own checks name them
    step = (fr["w_max"] - fr["w_min"]) / (fr["n_points"] - 1)
    below = natural[(natural > fr["w_min"] + step) & (natural < 1)]
    above = natural[(natural > 1) & (natural < fr["w_max"] - step)]
    if below.size and above.size:
        return []
    said = ", ".join(f"{w:.4g}" for w in natural)
    return [("frequency_response", f"[{fr['w_min']:g}, {fr['w_max']:g}] must hold an undamped "
             f"natural frequency of Table 2 on each side of w = 1 (Fig 5's peaks); with "
             f"paper_c.rotor and paper_c.table2 they are {said}: widen the range")]


def spin_problems(c: dict) -> list[tuple[str, str]]:
    """Paper C's spin study follows Table 2's absorber up to 99 % of its first spring loss,
    sqrt(2 k / m) of a set: every machine speed the spin claim is evaluated at must lie below."""
    t2 = c["table2"]
    loss = min(np.sqrt(2 * t2[f"k{j}"] / t2[f"m{j}"]) for j in (1, 2)) * 30 / np.pi
    speeds = {"spin.realistic_rpm": [c["spin"]["realistic_rpm"]],
              "spin.alternative_rpm": c["spin"]["alternative_rpm"]}
    return [(key, f"{rpm:g} rpm is beyond the spins followed, up to {0.99 * loss:.6g} rpm (99 % "
                  "of Table 2's first spring loss sqrt(2k/m))")
            for key, values in speeds.items() for rpm in values if rpm > 0.99 * loss]


def problems(c: dict) -> list[tuple[str, str]]:
    """Every problem of the ``paper_c`` section of a configuration that satisfies the schema,
    as ``(key within paper_c, what is wrong)``: a Sobol design that cannot be run, a search
    seed repeated among its spread seeds, a tolerance finer than double precision, a Fig 6
    claim about a curve the mass-ratio family does not draw, a distance offset through the
    disk centre or none at 0, a machine speed beyond the absorbers' spring loss, a frequency
    range without Fig 5's two undamped peaks."""
    found = []
    if problem := sobol_design_problem(c["uncertainty"]["n_base"],
                                       c["uncertainty"]["convergence"]):
        found.append(("uncertainty", problem))
    if problem := seed_spread_problem(c["broadband"]["nsga"], "paper_c.broadband.nsga"):
        found.append(("broadband.nsga.spread_seeds", problem))
    if problem := tolerance_problem(c["time_response"]["rtol"]):
        found.append(("time_response.rtol", problem))
    return (found + fig6_problems(c) + distance_problems(c) + spin_problems(c)
            + frequency_range_problems(c))
