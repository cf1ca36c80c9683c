"""The project's choices that paper B's rows rest on, as each row names them
(:attr:`rotorvib.comparison.reproduced.Reproduced.choices`): a configuration key and why it is a choice."""

from __future__ import annotations

R_CHOICE = "paper_b.machine.R (inferred from Table 2's forces: the paper gives no race radius)"
ZETA_CHOICE = ("paper_b.machine.zeta (stated for Figs 2-3 and 8-14 only: fixed for this one "
               "too; see zeta_inversion)")
TIME_CHOICE = "paper_b.claims.time_uncertainty (chosen from the integrator's convergence study)"
BETA_GRID = "paper_b.balance_studies.beta.range (the plotted beta grid, chosen)"
MASS_GRID = "paper_b.balance_studies.mass.range (the plotted mass grid, chosen)"
FIG2_GRID = "paper_b.stability_maps.fig2 (its beta and omega_bar ranges, chosen)"

#: The balance-time law's rows: the runs it is tested on and the machine's fixed values.
LAW_CHOICES = (R_CHOICE, "the runs of the studies the law is tested on (paper_b.balance_studies, "
               "basin, table1, calibration)")
#: The GA-optimum law's row: the neighbours of each optimum and the decay fit's window.
#: A change of the line's time too small to share out between its terms (ga_law_rows).
FLAT_KEY = "flat"
GA_LAW_CHOICES = (R_CHOICE, ZETA_CHOICE, "paper_b.ga_law.step (the neighbours, chosen)",
                  "paper_b.ga_law.settle, horizon, width (the decay fit's window, chosen)",
                  f"{FLAT_KEY} = paper_b.balance.sample_dt (a change of the line's time within "
                  "the sampling of the r(t) it is fitted to is flat, chosen; "
                  "paper_b.claims.time_uncertainty evaluated too)")
#: The continuation's rows: the traced ranges and the solver's tolerance.
BOUNDARY_CHOICES = ("paper_b.boundaries.beta, m_bar, zeta (the traced ranges, chosen)",
                    "paper_b.boundaries.omega_max (the highest traced speed, chosen)",
                    "paper_b.boundaries.tol (Newton's tolerance, chosen)")


def kinematics_choice(kinematics) -> str:
    """The disk-angle kinematics as a choice: the first is the reproduction, the others are
    evaluated too (``paper_b.kinematics``)."""
    first, *others = kinematics
    return (f"paper_b.kinematics = {first} (the disk angle: printed w t as eq. 37 is printed, "
            "consistent int w dt" + (f"; {', '.join(others)} evaluated too)" if others else ")"))
