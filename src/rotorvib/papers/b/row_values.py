"""The numbers paper B's rows are made of: Tables 1 and 2 regenerated from their datasets, and
the values where a configuration leaves some without one: a decay that never comes, a reduction
from nothing, a run-up shorter than a sample, a speed the paper does not print.  Each such case
was found by the configuration fuzzer (tests/schema_fuzz.py), where it stopped the workflow;
here it becomes a row that says what it could not decide."""

from __future__ import annotations

import math
import re
from functools import partial

import numpy as np
import xarray as xr

from rotorvib.comparison.reproduced import Reproduced
from rotorvib.io.coords import pick
from rotorvib.papers.b.curves import mean_over_ics

_row = partial(Reproduced.of, "B")


def table1_at_paper_speeds(rows: list[Reproduced], paper: dict) -> list[Reproduced]:
    """Table 1's rows at the speeds the paper prints: a speed of the configuration's Table 1
    that the paper does not print has no row, and one the paper prints that the configuration
    does not run has a row without a value, saying so (found by the fuzzer: another speed in
    paper_b.table1.speeds stopped the comparison)."""
    made = {row.quantity for row in rows}
    return [row for row in rows if row.quantity in paper] + [
        _row(key, math.nan, "not reproduced: this configuration's Table 1 "
             "(paper_b.table1.speeds) does not run the paper's speed")
        for key in paper if re.fullmatch(r"table1_(m_opt|mean_time)_\d+", key)
        and key not in made]


def reduction(new: float, old: float) -> float:
    """``100 (1 - new / old)`` (%), NaN where ``old`` is 0 (found by the fuzzer: a balance
    threshold above every force makes Table 2's decay times 0) or either is NaN."""
    return math.nan if old == 0 else 100 * (1 - new / old)


def runup_end(alpha) -> int:
    """The index of the first sample after which the angular acceleration ``alpha`` (samples
    from t = 0) stays zero; a run-up shorter than the sample step is over by the first sample
    after t = 0 (found by the fuzzer: paper_b.speed.t_ramp = 0.0005 s had no such sample)."""
    accelerating = np.flatnonzero(np.asarray(alpha) != 0.0)
    return int(accelerating[-1]) + 1 if accelerating.size else min(1, len(alpha) - 1)


def optimum_lead(forces, decay_times) -> tuple[float, float]:
    """How far the last row (the optimum) leads every other in peak force and force decay time,
    ``min(F_i / F_opt, T_i / T_opt) - 1`` over the others, and its decay time.  A force that
    never decays by t_end (NaN) decays later than any that does: infinite here, so that it
    loses to a decaying row, and two such rows decide nothing (inf/inf is NaN)."""
    force = np.asarray(forces, float)
    decay = np.nan_to_num(np.asarray(decay_times, float), nan=np.inf)
    with np.errstate(invalid="ignore"):                  # inf/inf: NaN, as meant
        lead = np.min(np.concatenate([force[:-1] / force[-1], decay[:-1] / decay[-1]])) - 1
    return float(lead), float(decay[-1])


def table1_rows(t1: xr.Dataset, kinematics: str) -> list[dict]:
    """Optimum mass (minimum mean balance time over the ICs) and that mean, per speed."""
    t = pick(t1, kinematics=kinematics)
    mean, envelope = mean_over_ics(t.balance_time), mean_over_ics(t.envelope_time)
    rows = []
    for i, speed in enumerate(t1.speed.values):
        curve = mean.isel(speed=i).values
        best = int(np.nanargmin(curve)) if np.isfinite(curve).any() else None
        rows.append({"speed_rad_s": float(speed),   # NaN where every mass has a censored run
                     "m_opt_kg": np.nan if best is None else float(t1.mass.values[best]),
                     "mean_balance_time_s": np.nan if best is None else float(curve[best]),
                     "mean_envelope_time_s": np.nan if best is None
                     else float(envelope.values[i, best]),
                     "censored_masses": int(np.sum(~np.isfinite(curve)))})
    return rows


def table2_rows(forces: xr.Dataset, R: float, kinematics: str) -> list[dict]:
    """Table 2 regenerated: per row, beta, m, the peak bearing force, its decay time and the
    balance time at the race radius ``R`` (nearest calibration radius) under ``kinematics``."""
    at = pick(forces, kinematics=kinematics).sel(R=R, method="nearest")
    return [{"row": int(c), "beta": float(at.case_beta[i]), "m_kg": float(at.case_mass[i]),
             "force_max_N": float(at.force_max[i]), "force_decay_time_s":
             float(at.force_decay_time[i]), "balance_time_s": float(at.balance_time[i])}
            for i, c in enumerate(at.case.values)]


#: The columns of Tables 1-2 the paper prints, and the key of each row's printed value in
#: data/paper_values.csv.
PRINTED = {
    "table1": {"m_opt_kg": "table1_m_opt_{speed_rad_s:g}",
               "mean_balance_time_s": "table1_mean_time_{speed_rad_s:g}"},
    "table2": {"force_max_N": "table2_fmax_{row}", "force_decay_time_s": "table2_decay_{row}"},
}


def beside_printed(rows: list[dict], table: str, printed: dict[str, str]) -> list[dict]:
    """Each row of Table 1 or 2 (``table``) with the paper's value before each column it
    prints, as printed (``printed``: paper B's values as printed, by key; empty where it prints
    none): ``force_max_N`` gets ``force_max_paper_N`` before it."""
    out = []
    for row in rows:
        wide = {}
        for name, value in row.items():
            if key := PRINTED[table].get(name):
                base, _, unit = name.rpartition("_")
                wide[f"{base}_paper_{unit}"] = printed.get(key.format(**row), "")
            wide[name] = value
        out.append(wide)
    return out
