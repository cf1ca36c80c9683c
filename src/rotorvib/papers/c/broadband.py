"""Beyond paper C: the absorber the paper should have optimised.

Paper C minimises ``|Theta(omega_n)|`` at one frequency (section 4) and lands on its bounds
with split peaks.  Here the same eight design variables, within the same bounds, are tuned for
two objectives by NSGA-II:

* the peak of ``D(w) = |Theta(w)| k_t / Gamma0`` over a band ``w_lo <= w <= w_hi`` around
  resonance (eq. 20 sampled on the band), and
* the added mass ``2 (m1 + m2)`` (each absorber set has two bodies).

The design compared is the front's lowest peak at no more added mass than Table 2.  It is set
beside no absorber, Table 2, the single-frequency optimum of the genetic algorithm and Den
Hartog's single absorber of Table 2's mass, by their frequency responses (peaks refined over all
frequencies) and their exact linear responses from rest at resonance; Den Hartog's absorber is
also evaluated at every mass of the front, the curve the dual absorber has to beat.
"""

from __future__ import annotations

from functools import partial

import numpy as np
import xarray as xr

from rotorvib.checks import nonnegative_array
from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.io.progress import Progress
from rotorvib.io.variables import described
from rotorvib.methods.forked import map_forked
from rotorvib.methods.optima import ParetoFront
from rotorvib.models.absorber.frequency_response import (amplitude, bare_rotor_amplitude,
                                                         dimensionless_amplitude, rotor_peak,
                                                         theta_eq20)
from rotorvib.models.absorber.parameters import (DUAL_NAMES, AbsorberSet, Rotor, design_bounds,
                                                 dual_from_vector, dual_to_vector)
from rotorvib.models.absorber.time_response import linear_response
from rotorvib.models.absorber.tuning import den_hartog_single
from rotorvib.papers.c.studies import REFERENCE as STUDIES_REFERENCE

REFERENCE = f"{STUDIES_REFERENCE}; section 4 (bounds), beyond the paper"
_claim = partial(Reproduced.claim, "C")
DESIGNS = {"table2": "Table 2 (paper)",
           "single_frequency": "GA optimum of |Theta(omega_n)| (section 4)",
           "den_hartog": "Den Hartog single absorber, Table 2's mass",
           "broadband": "broadband optimum, at most Table 2's mass"}


def added_mass(x) -> np.ndarray:
    """Added mass ``2 (m1 + m2)`` (kg) of dual-absorber design vectors ``x[..., 8]``, each
    entry finite and >= 0."""
    x = nonnegative_array("x", x, "a design value")
    if x.shape[-1:] != (8,):
        raise ValueError(f"x: shape {x.shape}, expected (..., 8): m1, m2, k1, k2, c1, c2, d1, d2")
    return 2 * (x[..., 0] + x[..., 1])


#: Designs times band frequencies that :func:`band_peak` evaluates at a time. Eq. (20) over a
#: population and the band makes a dozen complex temporaries of that many values; at 8192 each
#: is 128 KiB, which the allocator serves from its heap again and again. Larger ones it maps
#: from the kernel and returns to it at every call: over the whole band at once (200 designs x
#: 601 frequencies, 1.9 MB each) the broadband search spent about half as much system time on
#: the fresh pages as user time on everything else.
BAND_CHUNK = 8192


def band_peak(rotor: Rotor, x, w) -> np.ndarray:
    """Largest ``D`` over the sampled band ``w`` (ratios to ``omega_n``) for each design vector
    of ``x[..., 8]`` (eq. 20 with the true determinant), :data:`BAND_CHUNK` (design,
    frequency) pairs at a time."""
    x, omega = np.asarray(x, float), np.asarray(w) * rotor.omega_n
    designs = x.reshape(-1, x.shape[-1])
    peaks = np.empty(len(designs))
    rows = max(1, BAND_CHUNK // omega.size)
    for start in range(0, len(designs), rows):
        theta = theta_eq20(rotor, designs[start:start + rows, None, :], omega)
        peaks[start:start + rows] = dimensionless_amplitude(rotor, theta).max(axis=-1)
    return peaks.reshape(x.shape[:-1])[()]


def broadband_front(rotor: Rotor, bounds: dict, w, **nsga) -> ParetoFront:
    """NSGA-II front of (band peak of D over ``w``, added mass) within the paper's bounds;
    ``nsga``: ``pop_size``, ``n_gen``, ``seed``, ``sbx_eta``, ``pm_eta`` (and ``progress``,
    :func:`rotorvib.methods.ga.pareto_front`)."""
    from rotorvib.methods.ga import pareto_front  # pymoo: loaded by the search's job only

    lower, upper = design_bounds(bounds)
    return pareto_front(lambda x: np.column_stack([band_peak(rotor, x, w), added_mass(x)]), 2,
                        lower, upper, **nsga)


def broadband_fronts(rotor: Rotor, bounds: dict, w, seeds, workers: int = 1,
                     **nsga) -> list[ParetoFront]:
    """:func:`broadband_front` for each of ``seeds`` (the same search otherwise), in order,
    by up to ``workers`` forked processes (:func:`rotorvib.methods.forked.map_forked`): each
    front is the one its seed gives alone, whatever the number of workers. Each search logs
    its generations (:class:`rotorvib.io.progress.Progress`)."""
    return map_forked(partial(_front_of_seed, rotor, bounds, w, nsga), list(seeds), workers)


def _front_of_seed(rotor: Rotor, bounds: dict, w, nsga: dict, seed: int) -> ParetoFront:
    """:func:`broadband_front` with ``seed``, its generations logged (a picklable task of
    :func:`broadband_fronts`)."""
    progress = Progress(f"broadband NSGA-II, seed {seed}: generations", nsga["n_gen"])
    return broadband_front(rotor, bounds, w, **nsga, seed=seed, progress=progress)


class NoDesignAtMass(ValueError):
    """A Pareto front without a design as light as asked: its search stopped before reaching
    that mass (a longer search, more generations or a larger population, reaches it)."""


def pick_at_mass(front: ParetoFront, mass: float) -> np.ndarray:
    """The front's design with the lowest band peak among those adding at most ``mass``;
    :class:`NoDesignAtMass` if none does."""
    fits = front.f[:, 1] <= mass * (1 + 1e-12)
    if not fits.any():
        raise NoDesignAtMass(f"no design of the front adds at most {mass:g} kg (lightest "
                             f"{front.f[:, 1].min():g} kg)")
    return front.x[fits][np.argmin(front.f[fits, 0])]


def den_hartog_peaks(rotor: Rotor, masses, d: float) -> np.ndarray:
    """Peak of D over all frequencies of Den Hartog's single absorber adding each of ``masses``
    (kg, two bodies of half of it each) at radius ``d``."""
    return np.array([rotor_peak(rotor, (den_hartog_single(rotor, m=m / 2, d=d),))[1]
                     for m in np.asarray(masses, float)])


def _designs(rotor: Rotor, table2, x_single, d_single: float, x_broadband) -> dict:
    mass = table2[0].m + table2[1].m
    return {"table2": tuple(table2), "single_frequency": dual_from_vector(x_single),
            "den_hartog": (den_hartog_single(rotor, m=mass, d=d_single),),
            "broadband": dual_from_vector(x_broadband)}


#: Nelder-Mead's relative tolerance on the peak of :func:`free_spring_dual` (its uncertainty).
FREE_SPRING_TOL = 1e-9


def free_spring_dual(rotor: Rotor, mass: float, d: float, band_w) -> tuple[AbsorberSet, ...]:
    """The dual absorber of Den Hartog's body mass ``mass`` (two sets of ``mass / 2`` at radius
    ``d``) whose springs and dampers, free of the paper's bounds, give the least peak of ``D``
    over the band ``band_w``: Nelder-Mead on their logarithms from Den Hartog's tuning of each
    half, the two staggered by 5 % in frequency (deterministic)."""
    from scipy.optimize import minimize  # here: the other broadband jobs need no optimizer

    half = den_hartog_single(rotor, m=mass / 2, d=d)

    def sets(p):
        k1, k2, c1, c2 = np.exp(p)
        return (AbsorberSet(m=mass / 2, k=k1, c=c1, d=d),
                AbsorberSet(m=mass / 2, k=k2, c=c2, d=d))

    start = np.log([half.k * 0.95**2, half.k * 1.05**2, half.c, half.c])
    best = minimize(lambda p: amplitude(rotor, sets(p), band_w).max(), start,
                    method="Nelder-Mead", options={"xatol": 1e-10, "fatol": FREE_SPRING_TOL,
                                                   "maxiter": 20000, "maxfev": 40000})
    if not best.success:
        raise ArithmeticError(f"the free-spring dual absorber's search failed: {best.message}")
    return sets(best.x)


#: The variables of :func:`broadband_dataset`: (long name, units).
BROADBAND_VARIABLES = {
    "front_band_peak": ("largest D over the band, Pareto front", "1"),
    "front_added_mass": ("added mass 2 (m1 + m2), Pareto front", "kg"),
    "front_x": ("design of the Pareto front (units: kg, N m-1, N s m-1, m by kind)", "1"),
    "front_den_hartog_peak": ("largest D of Den Hartog's single absorber of the same added mass",
                              "1"),
    "D": ("dimensionless torsional amplitude D = |Theta| k_t / Gamma0", "1"),
    "D_none": ("D without absorber, 1/|1 - w^2|", "1"),
    "band_peak": ("largest D over the band (sampled)", "1"),
    "peak": ("largest D over all frequencies (refined)", "1"),
    "peak_w": ("frequency ratio of the largest D", "1"),
    "added_mass": ("added mass of the absorber bodies", "kg"),
    "parameters": ("design (m, k, c, d of set 1 and set 2; NaN: no second set; units: kg, N m-1, "
                   "N s m-1, m by kind)", "1"),
    "broadband_peak_by_seed": ("largest D over all frequencies of the broadband design, from "
                               "each seed of NSGA-II (the first is the design shown)", "1"),
    "free_spring_peak": ("largest D over all frequencies of a dual absorber of Den Hartog's mass "
                         "and radius with springs and dampers free of the bounds", "1"),
    "free_spring_parameters": ("that design (m, k, c, d of set 1 and set 2; units: kg, N m-1, "
                               "N s m-1, m by kind)", "1"),
    "lower_bound_k": ("least spring stiffness the bounds allow", "N m-1"),
    "omega_n": ("natural frequency of the rotor without absorber", "rad s-1"),
    "theta": ("disk twist angle from rest under Gamma0 cos(omega_n t), exact linear response of "
              "eq. (14)", "rad"),
}


def broadband_dataset(rotor: Rotor, table2, x_single, d_single: float, front: ParetoFront,
                      band_w, w, t, k_min: float, spread_fronts=()) -> xr.Dataset:
    """The front, and each design of :data:`DESIGNS`: D over ``w``, the band peak over
    ``band_w``, the peak over all frequencies (refined), the added mass and theta(t) from rest
    under ``Gamma0 cos(omega_n t)`` at times ``t`` (exact linear response); ``k_min`` is the
    bounds' least spring stiffness.  ``spread_fronts``, the
    fronts of the same NSGA-II from other seeds, give ``broadband_peak_by_seed``: the
    broadband design's peak from every seed, the first ``front``'s."""
    mass_t2 = float(added_mass(dual_to_vector(table2)))
    x_broadband = pick_at_mass(front, mass_t2)
    by_seed = np.array([rotor_peak(rotor, dual_from_vector(pick_at_mass(f, mass_t2)))[1]
                        for f in (front, *spread_fronts)])
    designs = _designs(rotor, table2, x_single, d_single, x_broadband)
    free = free_spring_dual(rotor, table2[0].m + table2[1].m, d_single, band_w)
    D = np.stack([amplitude(rotor, s, w) for s in designs.values()])
    band = np.array([amplitude(rotor, s, band_w).max() for s in designs.values()])
    peaks = np.array([rotor_peak(rotor, s) for s in designs.values()])
    theta = np.stack([linear_response(rotor, s, rotor.omega_n, t)[:, 0]
                      for s in designs.values()])
    mass = np.array([sum(2 * a.m for a in s) for s in designs.values()])
    parameters = np.full((len(designs), len(DUAL_NAMES)), np.nan)
    for i, sets in enumerate(designs.values()):
        for j, s in enumerate(sets):
            parameters[i, [j, 2 + j, 4 + j, 6 + j]] = [s.m, s.k, s.c, s.d]
    one = {"units": "1"}
    return xr.Dataset(
        described({
            "front_band_peak": ("front", front.f[:, 0]),
            "front_added_mass": ("front", front.f[:, 1]),
            "front_x": (("front", "parameter"), front.x),
            "front_den_hartog_peak": ("front", den_hartog_peaks(rotor, front.f[:, 1], d_single)),
            "D": (("design", "w"), D),
            "D_none": ("w", bare_rotor_amplitude(w)),
            "band_peak": ("design", band),
            "peak": ("design", peaks[:, 1]),
            "peak_w": ("design", peaks[:, 0]),
            "added_mass": ("design", mass),
            "parameters": (("design", "parameter"), parameters),
            "broadband_peak_by_seed": ("seed", by_seed),
            "free_spring_peak": ((), rotor_peak(rotor, free)[1]),
            "free_spring_parameters": ("parameter", [getattr(s, kind) for kind in "mkcd"
                                                     for s in free]),
            "lower_bound_k": ((), float(k_min)),
            "omega_n": ((), rotor.omega_n),
            "theta": (("design", "t"), theta),
        }, BROADBAND_VARIABLES),
        coords={"design_name": ("design", np.array(list(DESIGNS.values()), dtype=object),
                                {"long_name": "absorber design"}),
                "design_key": ("design", np.array(list(DESIGNS), dtype=object),
                               {"long_name": "absorber design (key)"}),
                "parameter_name": ("parameter", np.array(DUAL_NAMES, dtype=object),
                                   {"long_name": "design variable of the dual absorber"}),
                "w": ("w", np.asarray(w, float), {
                    "long_name": "forcing frequency ratio omega/omega_n", **one}),
                "band_w": ("band_w", np.asarray(band_w, float), {
                    "long_name": "frequency ratios of the band objective", **one}),
                "t": ("t", np.asarray(t, float), {"long_name": "time since the start of the "
                                                  "forcing", "units": "s"})},
        attrs={"title": "Paper C, beyond the paper: the broadband absorber",
               "summary": "NSGA-II front of the peak of D over a band against the added mass, "
                          "and the front's design at Table 2's mass beside no absorber, Table "
                          "2, the single-frequency optimum and Den Hartog's absorber",
               "references": REFERENCE},
    )


def late_amplitude(ds: xr.Dataset) -> np.ndarray:
    """Largest ``|theta|`` of each design over the last forcing period of the time response."""
    t = ds.t.values
    return np.abs(ds.theta.values[:, t >= t[-1] - 2 * np.pi / float(ds.omega_n)]).max(axis=1)


def comparison_table(ds: xr.Dataset) -> list[dict]:
    """One row per design: its parameters (set 2 empty for a single set), added mass, peaks of
    D and late amplitude at resonance."""
    late = late_amplitude(ds)
    rows = []
    for i, name in enumerate(ds.design_name.values):
        row = {"design": str(name), "added_mass_kg": float(ds.added_mass[i])}
        row.update({str(p): (None if np.isnan(v) else float(v))
                    for p, v in zip(ds.parameter_name.values, ds.parameters.values[i])})
        row.update({"band_peak_D": float(ds.band_peak[i]), "peak_D": float(ds.peak[i]),
                    "peak_w": float(ds.peak_w[i]), "late_theta_rad": float(late[i])})
        rows.append(row)
    return rows


#: What the broadband rows rest on: the band, the GA's bounds (Table 2's, the paper's) and seeds.
CHOICES = ("paper_c.broadband.band (the frequency range the peak is taken over, chosen)",
           "paper_c.broadband.den_hartog_d (the single absorber's radius, chosen)",
           "paper_c.bounds (the paper's, section 4: k >= its lower bound)",
           "paper_c.broadband.nsga.seed, spread_seeds (chosen)")


def front_below_text(added_mass, below) -> str:
    """Which designs of the front lie below Den Hartog's curve, by added mass: "from m kg" only
    where every design at least that heavy does, else how many and their range."""
    added_mass, below = np.asarray(added_mass, float), np.asarray(below, bool)
    if not below.any():
        return "no design of the front is below Den Hartog's curve"
    lightest = added_mass[below].min()
    if below[added_mass >= lightest].all():
        return (f"every design of the front from {lightest:.3g} kg up is below Den Hartog's "
                f"curve ({int(below.sum())} of {below.size})")
    return (f"{int(below.sum())} of the front's {below.size} designs are below Den Hartog's "
            f"curve, between {lightest:.3g} and {added_mass[below].max():.3g} kg, not all "
            "the designs between")


def broadband_rows(ds: xr.Dataset) -> list[Reproduced]:
    """Is the broadband optimum's peak below Table 2's, the single-frequency optimum's and Den
    Hartog's absorber of the same mass?"""
    peak = dict(zip((str(k) for k in ds.design_key.values), ds.peak.values.astype(float)))
    mass = dict(zip((str(k) for k in ds.design_key.values), ds.added_mass.values.astype(float)))
    bb = peak["broadband"]
    seeds = ds.broadband_peak_by_seed.values

    def margin(value: float) -> Margin:
        return Margin(value, float(np.ptp(seeds)) / 2 / bb, "relative",
                      f"half the range of the broadband peak over {seeds.size} NSGA-II seeds")

    free = float(ds.free_spring_peak)
    k_free = ds.free_spring_parameters.values[2:4]
    k_min = float(ds.lower_bound_k)
    front, dh = ds.front_band_peak.values, ds.front_den_hartog_peak.values
    where = front_below_text(ds.front_added_mass.values, front < dh)
    return [
        _claim("broadband_below_table2",
               margin((min(peak["table2"], peak["single_frequency"]) - bb) / bb),
               f"largest D over all frequencies: {bb:.4g} (broadband, {mass['broadband']:.3g} kg) "
               f"against {peak['table2']:.4g} (Table 2, {mass['table2']:.3g} kg) and "
               f"{peak['single_frequency']:.4g} (GA optimum of |Theta(omega_n)|, "
               f"{mass['single_frequency']:.3g} kg)", choices=CHOICES),
        _claim("broadband_below_den_hartog",
               {f"paper_c.bounds.k >= {k_min:g} N/m (the paper's)":
                    margin((peak["den_hartog"] - bb) / bb),
                "springs and dampers free of the bounds":
                    Margin((peak["den_hartog"] - free) / free, FREE_SPRING_TOL, "relative",
                           "Nelder-Mead's tolerance on the peak")},
               f"largest D {bb:.4g} (broadband dual) against {peak['den_hartog']:.4g} (Den "
               f"Hartog single absorber of {mass['den_hartog']:.3g} kg); {where}. The verdict "
               f"rests on the bound every spring >= {k_min:g} N/m: with "
               f"springs and dampers free, a dual absorber of Den Hartog's mass and radius "
               f"reaches {free:.4g} (k = {k_free[0]:.4g}, {k_free[1]:.4g} N/m)",
               choices=CHOICES),
    ]
