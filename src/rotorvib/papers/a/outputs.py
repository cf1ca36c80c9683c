"""Paper A's outputs (:mod:`rotorvib.papers.outputs`): its figures, as functions of the
configuration's ``paper_a`` section."""

from __future__ import annotations

from rotorvib.papers.outputs import figure

#: Datasets written that no figure draws.
UNDRAWN_DATASETS = ()
#: Markdown notes written beside the tables, not shown in the report.
NOTES = ()

#: The paper's equations and caption values were lost in extraction: the model is digest A's
#: reconstruction and every parameter is chosen (config/config.yaml, paper_a).
MODEL = " Reconstructed model; every parameter chosen (config paper_a)."


def figures(a: dict) -> dict[str, dict]:
    """Figs 2-7 and the figures beyond the paper, by name."""
    case = {"zoom": a["zoom"], "beta": a["case"]["beta"]}
    return {
        "fig2": figure(
            "fig2",
            {"resp": "responses"},
            "Radial response x/R of the rotor against dimensionless time: one-term and two-term "
            "multiple-scales solutions and Runge-Kutta, with a zoomed window and the error of "
            f"each multiple-scales solution against Runge-Kutta on a log scale.{MODEL}",
            **case,
        ),
        "fig3": figure(
            "fig3",
            {"resp": "responses"},
            "Tangential response y/R against dimensionless time: one-term and two-term "
            "multiple-scales solutions and Runge-Kutta, with a zoomed window and the error "
            f"panel.{MODEL}",
            **case,
        ),
        "fig4": figure(
            "fig4",
            {"resp": "responses"},
            "Angles of the two balls against dimensionless time by the three methods, with the "
            f"balanced angles +/-arccos(-1/(2 rho)).{MODEL}",
            items=["Section 3"],
            beta=a["case"]["beta"],
        ),
        "fig5": figure(
            "fig5",
            {"resp": "responses"},
            "The paper's claim that ball damping speeds the balancing up to an optimum and slows "
            "it beyond: the rotor amplitude for three ball-damping ratios beta on a log scale, "
            "beside the decay rate of the slowest mode of the linearised balanced state for each "
            f"beta.{MODEL}",
            betas=a["fig5_6"]["betas"],
        ),
        "fig6": figure(
            "fig6",
            {"resp": "responses"},
            f"Ball angles for the same three ball-damping ratios beta, one column each.{MODEL}",
            betas=a["fig5_6"]["betas"],
        ),
        "fig7": figure(
            "fig7",
            {"region": "stability_region"},
            "Stable region of the balanced state in the (speed, damping) plane by multiple scales "
            f"and by Lyapunov's first method.{MODEL}",
        ),
        "error_study": figure(
            "error_study",
            {"err": "error_study"},
            "Beyond the paper: the largest error of the one-term and two-term solutions against "
            "Runge-Kutta as the initial distance from the balanced state shrinks, the two-term "
            "one with the constants of the eight nonlinear equations and with linear ones (the "
            "one-term constants plus a homogeneous part cancelling the second-order term at "
            f"tau = 0), with the expected orders.{MODEL}",
            items=["Error study"],
        ),
        "slow_flow": figure(
            "slow_flow",
            {"flow": "slow_flow"},
            "Beyond the paper: the stability boundary of the small-mu slow flow against the exact "
            f"one from the eigenvalues of the full linearisation.{MODEL}",
        ),
    }


def tables(a: dict) -> dict[str, dict]:
    """Paper A shows no table."""
    return {}
