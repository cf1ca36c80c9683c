"""Which support damping ratio zeta, if any, reproduces paper B's printed times together.

Paper B states zeta = 0.01 for Figs 2-3, 8-10 and 12-14, not for Fig 7, Table 1 or Table 2,
whose times the reproduction computes at the configured zeta; a balance time is roughly
proportional to 1/zeta (the whirl decays at the rate of the support damping), so each printed
time alone can be met by some zeta. This study runs every printed time's case over a range of
zeta under each kinematics and reads it under both balance-time definitions, the threshold
crossing of r and the envelope through the peaks of r(t) (Table 2's decay time is the bearing
force's: one definition). A model (kinematics, definition) reproduces printed time ``t_p`` at
zeta when ``abs(t(zeta) - t_p) <= tol(t_p)``, with

    tol(t_p) = max(MATCH_TOL * abs(t_p), half a unit of the last printed digit of t_p),

and reproduces them all where one zeta does so for every case: where the worst normalised
error, the largest ``abs(t(zeta) - t_p) / tol`` over the cases, is at most 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from rotorvib.comparison.choices import VARIANT_JOIN
from rotorvib.comparison.reproduced import Margin, Reproduced
from rotorvib.comparison.verdicts import MATCH_TOL
from rotorvib.io.coords import label_coord, labels
from rotorvib.comparison.paper_values import decimals
from rotorvib.papers.b.choices import R_CHOICE, kinematics_choice
from rotorvib.papers.b.attributes import dataset_attrs
from rotorvib.papers.b.setup import KINEMATICS_LONG_NAME, Setup, parameter_coord
from rotorvib.papers.b.studies import grid_dataset

#: The balance-time definitions and the run metric each reads (a force decay time is always
#: the force's).
DEFINITIONS = {"threshold": "balance_time", "envelope": "envelope_time"}
FORCE_METRIC = "force_decay_time"


@dataclass(frozen=True)
class TimeCase:
    """One printed time: its paper-values ``key``, value and tolerance (s), and its run: the
    operating ``speed``, ``beta``, ball ``mass``, ``eps_bar`` and the initial conditions
    ``ics`` (name -> ball angles, deg) it is the mean over; ``force``: a bearing force's decay
    time rather than a balance time."""

    key: str
    printed: float
    tolerance: float
    speed: float
    beta: float
    mass: float
    eps_bar: float
    ics: tuple[tuple[str, tuple[float, ...]], ...]
    force: bool = False


def printed_tolerance(text: str) -> float:
    """``tol`` of the module docstring for a value printed as ``text`` (e.g. ``"4.70"``:
    max(0.047, 0.005); ``"4"``: 0.5)."""
    return max(MATCH_TOL * abs(float(text)), 0.5 * 10.0 ** -decimals(text))


def printed_cases(paper_b: dict, printed: dict[str, str]) -> list[TimeCase]:
    """The printed times of Fig 7, Table 1 and Table 2 with their runs, from the ``paper_b``
    config section and ``printed`` (paper-values quantity -> the value as printed). Table 1's
    time is the mean over IC1-IC3 at its printed optimum mass; Fig 7 and Table 2 run as the
    configuration runs them."""
    ics = {name: tuple(angles) for name, angles in paper_b["initial_conditions"].items()}
    f7, t1, t2 = (paper_b["time_responses"]["fig7"], paper_b["table1"], paper_b["table2"])
    M = paper_b["machine"]["M"]

    def case(key, **run):
        return TimeCase(key, float(printed[key]), printed_tolerance(printed[key]), **run)

    cases = [case("fig7_balance_time", speed=paper_b["speed"]["omega"], beta=f7["beta"],
                  mass=f7["m_bar"] * M, eps_bar=f7["eps_bar"],
                  ics=(("Fig 7", tuple(f7["phi0"])),))]
    for speed in t1["speeds"]:
        s = f"{speed:.0f}"
        if f"table1_mean_time_{s}" in printed:
            cases.append(case(f"table1_mean_time_{s}", speed=speed, beta=t1["beta"],
                              mass=float(printed[f"table1_m_opt_{s}"]), eps_bar=t1["eps_bar"],
                              ics=tuple(ics.items())))
    for row, (beta, mass) in enumerate(t2["cases"], 1):
        cases.append(case(f"table2_decay_{row}", speed=t2["speed"], beta=beta, mass=mass,
                          eps_bar=t2["eps_bar"], ics=((t2["ic"], ics[t2["ic"]]),), force=True))
    return cases


def runs_of(cases: list[TimeCase]) -> list[tuple[int, int]]:
    """Every (case, initial condition) pair, in order: the runs at one zeta."""
    return [(c, i) for c, case in enumerate(cases) for i in range(len(case.ics))]


def inversion_dataset(setup: Setup, cases: list[TimeCase], *, kinematics, zetas,
                      runs=None) -> xr.Dataset:
    """Each case's time over ``zetas`` under each kinematics and definition (the mean over
    its initial conditions; NaN where a run is censored), its printed value and tolerance,
    and which model reproduces which time where (:func:`with_verdicts`)."""
    pairs = runs_of(cases)

    def make_inputs(kinematics, zeta, run):
        c, i = pairs[run]
        case = cases[c]
        return setup.run_inputs(mass=case.mass, eps_bar=case.eps_bar, beta=case.beta,
                                phi0_deg=case.ics[i][1], kinematics=kinematics,
                                speed=case.speed, zeta=zeta)

    axes = {"kinematics": kinematics, "zeta": zetas, "run": list(range(len(pairs)))}
    coords = {**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
              **parameter_coord("zeta", zetas),
              "run": ("run", np.arange(len(pairs), dtype=np.int32),
                      {"long_name": "run: a printed time's case and initial condition",
                       "units": "1"})}
    metrics = grid_dataset(setup, axes, coords, make_inputs, {})
    owner = np.array([c for c, _ in pairs])
    times = []
    for metric in DEFINITIONS.values():
        per_run = [metrics[FORCE_METRIC if cases[c].force else metric].isel(run=k)
                   for k, (c, _) in enumerate(pairs)]
        runs_ = xr.concat(per_run, "run")
        times.append(xr.concat([runs_.isel(run=np.flatnonzero(owner == c)).mean("run",
                                                                               skipna=False)
                                for c in range(len(cases))], "case"))
    time = xr.concat(times, "definition").transpose("kinematics", "definition", "zeta", "case")
    ds = xr.Dataset(
        {"time": (time.dims, time.values,
                  {"long_name": "the case's time (mean over its initial conditions; NaN if a "
                                "run is censored)", "units": "s"}),
         "printed": ("case", [c.printed for c in cases],
                     {"long_name": "the paper's printed time", "units": "s"}),
         "tolerance": ("case", [c.tolerance for c in cases],
                       {"long_name": "largest difference that reproduces the printed time: "
                                     "max(1 % of it, half its last printed digit)",
                        "units": "s"})},
        coords={**label_coord("kinematics", kinematics, KINEMATICS_LONG_NAME),
                **label_coord("definition", list(DEFINITIONS),
                              "balance-time definition: threshold crossing of r or the "
                              "envelope through its peaks (a force decay time is the force's)"),
                **parameter_coord("zeta", zetas),
                **label_coord("case", [c.key for c in cases], "printed time (paper-values key)"),
                "case_force": ("case", np.array([c.force for c in cases], np.int8),
                               {"long_name": "1: a bearing force's decay time (Table 2)",
                                "units": "1"})},
        attrs=dataset_attrs("support damping that reproduces the printed times",
                            "Fig 7's balance time, Table 1's mean balance times and Table 2's "
                            "force decay times against the support damping ratio zeta, under "
                            "each kinematics and balance-time definition",
                            "Fig 7, Tables 1-2 (zeta not stated)"))
    return with_verdicts(ds)


def with_verdicts(ds: xr.Dataset) -> xr.Dataset:
    """Add the normalised error ``|t - t_p| / tol`` (inf where censored), its worst case per
    model and zeta, the zeta of least worst error per model (``best_zeta``, on the grid) and
    each case's own best zeta."""
    error = np.abs(ds.time - ds.printed) / ds.tolerance
    error = error.fillna(np.inf)
    worst = error.max("case")
    best = worst.argmin("zeta")
    own = error.argmin("zeta")
    return ds.assign(
        error=(error.dims, error.values,
               {"long_name": "|time - printed| / tolerance (inf if censored)", "units": "1"}),
        worst_error=(worst.dims, worst.values,
                     {"long_name": "largest normalised error over the cases", "units": "1"}),
        best_zeta=(best.dims, ds.zeta.values[best.values],
                   {"long_name": "zeta of the least worst error on the grid", "units": "1"}),
        least_worst_error=(best.dims, worst.min("zeta").values,
                           {"long_name": "the least worst error over zeta", "units": "1"}),
        case_zeta=(own.dims, ds.zeta.values[own.values],
                   {"long_name": "zeta of the case's least error on the grid", "units": "1"}))


def matching_zetas(ds: xr.Dataset, kinematics: str, definition: str, case: str) -> np.ndarray:
    """The grid's zetas at which the model reproduces the case."""
    at = ds.error.sel(kinematics_name=kinematics, definition_name=definition, case_name=case)
    return ds.zeta.values[at.values <= 1.0]


def zeta_rows(ds: xr.Dataset) -> list[Reproduced]:
    """Does one zeta reproduce every printed time, under some kinematics and definition?  The
    margin under each model is ``1 - least worst error`` (positive: one zeta reproduces all);
    its uncertainty is how much the worst error moves between neighbouring grid zetas at the
    best one (the optimum may lie between them)."""
    holds, parts = {}, []
    step = float(np.max(np.diff(ds.zeta.values)))
    for kin in labels(ds, "kinematics"):
        for definition in labels(ds, "definition"):
            worst = ds.worst_error.sel(kinematics_name=kin, definition_name=definition).values
            k = int(np.argmin(worst))
            around = worst[max(k - 1, 0):k + 2]
            finite = around[np.isfinite(around)]
            spread = float(np.ptp(finite)) if finite.size == around.size else np.inf
            least = float(worst[k])
            holds[f"{kin}{VARIANT_JOIN}{definition}"] = Margin(
                1.0 - least, spread if np.isfinite(least) else np.nan, "normalised error",
                f"zeta grid step {step:.2g}: the worst error's change next to its least")
            own = ds.case_zeta.sel(kinematics_name=kin, definition_name=definition).values
            parts.append(f"{kin}, {definition}: least worst error {least:.3g} tolerances at "
                         f"zeta = {float(ds.zeta[k]):.4g}; each time alone is best met at "
                         f"zeta {own.min():.4g}-{own.max():.4g}")
    cases = ", ".join(labels(ds, "case"))
    return [Reproduced.claim(
        "B", "zeta_reproduces_printed_times", holds,
        f"the printed times ({cases}) rerun over zeta = {float(ds.zeta.min()):.4g}-"
        f"{float(ds.zeta.max()):.4g}; a time is reproduced within max(1 %, half its last "
        "printed digit): " + "; ".join(parts),
        choices=(R_CHOICE, kinematics_choice(labels(ds, "kinematics")),
                 "paper_b.zeta_inversion.zeta (the zeta grid, chosen)",
                 f"comparison.MATCH_TOL = {MATCH_TOL:g} (or half the printed last digit) as "
                 "what reproduces a time",
                 "Table 1's cases at its printed optimum mass; Fig 7 and Table 2 as configured"))]

