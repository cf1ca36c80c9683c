"""Paper B under both kinematics side by side: how far each conclusion moves between the
paper's printed disk angle and the consistent one (results/paper_b/tables/kinematics.md)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from rotorvib.io.coords import pick
from rotorvib.papers.b.row_values import table1_rows, table2_rows
from rotorvib.papers.b.curves import argmin, mean_over_ics


def kinematics_note(beta: xr.Dataset, mass: xr.Dataset, t1: xr.Dataset, forces: xr.Dataset,
                    ga: xr.Dataset, R: float) -> str:
    """Markdown: how much the conclusions move between the printed and consistent kinematics."""
    kins = [str(k) for k in beta.kinematics_name.values]
    lines = ["# Paper B: printed against consistent kinematics", "",
             "The paper's equations (7)-(9) take the disk angle as w(t) t during the run-up; the "
             "consistent kinematics integrate w. Both agree once the speed is constant (t >= "
             "0.5 s), but the state reached at the end of the run-up differs.", ""]
    if len(kins) < 2:
        return "\n".join(lines + ["Only one kinematics was run; nothing to compare."]) + "\n"
    header = "| quantity | " + " | ".join(kins) + " |"
    lines += [header, "|---|" + "---|" * len(kins)]

    def add(name, values, fmt="{:.3g}"):
        lines.append(f"| {name} | " + " | ".join(fmt.format(v) for v in values) + " |")

    for eps_i, eps in enumerate(beta.eps_bar.values):
        add(f"best beta (mean over ICs), eps_bar = {eps:g}",
            [argmin(mean_over_ics(pick(beta, kinematics=k).balance_time.isel(eps_bar=eps_i))
                          .values, beta.beta.values) for k in kins])
        add(f"best mass (kg, mean over ICs), eps_bar = {eps:g}",
            [argmin(mean_over_ics(pick(mass, kinematics=k).balance_time.isel(eps_bar=eps_i))
                          .values, mass.mass.values) for k in kins])
    add("median balance time over the balanced runs of the beta grid (s; censored runs below)",
        [float(np.nanmedian(pick(beta, kinematics=k).balance_time)) for k in kins])
    add("censored runs on the beta and mass grids",
        [int((pick(beta, kinematics=k).balanced == 0).sum() + (pick(mass, kinematics=k).balanced
                                                               == 0).sum()) for k in kins], "{}")
    for row in range(forces.case.size):
        add(f"Table 2 row {row + 1}: peak force (N)",
            [table2_rows(forces, R, k)[row]["force_max_N"] for k in kins], "{:.1f}")
    add("Table 1: optimum masses (kg) at the speeds",
        [", ".join(f"{r['m_opt_kg']:g}" if np.isfinite(r["m_opt_kg"]) else "-"
                   for r in table1_rows(t1, k))
         for k in kins], "{}")
    add("GA: optimum betas", [", ".join(f"{v:.2f}" for v in pick(ga, kinematics=k).beta_opt
                                        .values.ravel()) for k in kins], "{}")
    return "\n".join(lines) + "\n"
