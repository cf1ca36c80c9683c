# Paper A: multiple scales and Lyapunov stability of the two-ball balancer (reconstructed model).

A_CASE = {"zoom": A["zoom"], "beta": A["case"]["beta"]}
# The paper's equations and caption values were lost in extraction: the model is digest A's
# reconstruction and every parameter is chosen (config/config.yaml, paper_a).
A_MODEL = " Reconstructed model; every parameter chosen (config paper_a)."
FIGURES["a"] = {
    "fig2": figure(
        "fig2",
        {"resp": "responses"},
        "Radial response x/R of the rotor against dimensionless time: one-term and two-term "
        "multiple-scales solutions and Runge-Kutta, with a zoomed window and the error of "
        f"each multiple-scales solution against Runge-Kutta on a log scale.{A_MODEL}",
        **A_CASE,
    ),
    "fig3": figure(
        "fig3",
        {"resp": "responses"},
        "Tangential response y/R against dimensionless time: one-term and two-term "
        "multiple-scales solutions and Runge-Kutta, with a zoomed window and the error "
        f"panel.{A_MODEL}",
        **A_CASE,
    ),
    "fig4": figure(
        "fig4",
        {"resp": "responses"},
        "Angles of the two balls against dimensionless time by the three methods, with the "
        f"balanced angles +/-arccos(-1/(2 rho)).{A_MODEL}",
        items=["Section 3"],
        beta=A["case"]["beta"],
    ),
    "fig5": figure(
        "fig5",
        {"resp": "responses"},
        "The paper's claim that ball damping speeds the balancing up to an optimum and slows "
        "it beyond: the rotor amplitude for three ball-damping ratios beta on a log scale, "
        "beside the decay rate of the slowest mode of the linearised balanced state for each "
        f"beta.{A_MODEL}",
        betas=A["fig5_6"]["betas"],
    ),
    "fig6": figure(
        "fig6",
        {"resp": "responses"},
        f"Ball angles for the same three ball-damping ratios beta, one column each.{A_MODEL}",
        betas=A["fig5_6"]["betas"],
    ),
    "fig7": figure(
        "fig7",
        {"region": "stability_region"},
        "Stable region of the balanced state in the (speed, damping) plane by multiple scales "
        f"and by Lyapunov's first method.{A_MODEL}",
    ),
    "error_study": figure(
        "error_study",
        {"err": "error_study"},
        "Beyond the paper: the largest error of the one-term and two-term solutions against "
        "Runge-Kutta as the initial distance from the balanced state shrinks, the two-term "
        "one with the constants of the eight nonlinear equations and with linear ones (the "
        "one-term constants plus a homogeneous part cancelling the second-order term at "
        f"tau = 0), with the expected orders.{A_MODEL}",
        items=["Error study"],
    ),
    "slow_flow": figure(
        "slow_flow",
        {"flow": "slow_flow"},
        "Beyond the paper: the stability boundary of the small-mu slow flow against the exact "
        f"one from the eigenvalues of the full linearisation.{A_MODEL}",
    ),
}


RESULTS["a"] = results_of("a")


rule a_responses:
    output:
        dataset("a", "responses"),
    log:
        logs("a_responses"),
    benchmark:
        benchmarks("a_responses")
    priority: COMPUTES
    localrule: True
    params:
        case=A["case"],
        offset=A["initial_offset"],
        betas=A["fig5_6"]["betas"],
        tau_end=A["tau_end"],
        tau_step=A["tau_step"],
        rk=A["rk"],
    message:
        "Paper A: responses by Runge-Kutta and multiple scales (Figs 2-6)"
    script:
        "../scripts/a_responses.py"


rule a_stability:
    output:
        dataset("a", "stability_region"),
    log:
        logs("a_stability"),
    benchmark:
        benchmarks("a_stability")
    priority: COMPUTES
    localrule: True
    params:
        case=A["case"],
        fig7=A["fig7"],
    message:
        "Paper A: stable region by multiple scales and by Lyapunov (Fig 7)"
    script:
        "../scripts/a_stability.py"


rule a_error_study:
    output:
        dataset("a", "error_study"),
    log:
        logs("a_error_study"),
    benchmark:
        benchmarks("a_error_study")
    priority: COMPUTES
    localrule: True
    params:
        case=A["case"],
        offset=A["initial_offset"],
        study=A["error_study"],
        tau_step=A["tau_step"],
        rk=A["rk"],
    message:
        "Paper A: error of the multiple-scales solutions against the initial distance"
    script:
        "../scripts/a_error_study.py"


rule a_slow_flow:
    output:
        dataset("a", "slow_flow"),
    log:
        logs("a_slow_flow"),
    benchmark:
        benchmarks("a_slow_flow")
    priority: COMPUTES
    localrule: True
    params:
        case=A["case"],
        flow=A["slow_flow"],
    message:
        "Paper A: slow-flow stability boundary against the exact one"
    script:
        "../scripts/a_slow_flow.py"


rule a_reproduced_values:
    input:
        resp=rules.a_responses.output[0],
        region=rules.a_stability.output[0],
        err=rules.a_error_study.output[0],
        paper_values=PAPER_VALUES,
    output:
        reproduced_file("a"),
    log:
        logs("a_reproduced_values"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        case=A["case"],
        zoom=A["zoom"],
        close=CLOSE,
        rk=A["rk"],
    message:
        "Paper A: measuring the paper's claims on the datasets"
    script:
        "../scripts/a_reproduced_values.py"
