# Paper A: multiple scales and Lyapunov stability of the two-ball balancer (reconstructed
# model). Its figures are declared in rotorvib.papers.a.outputs.
A = config["paper_a"]


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
