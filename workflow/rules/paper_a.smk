# Paper A: multiple scales and Lyapunov stability of the two-ball balancer (reconstructed model).


rule a_responses:
    output:
        f"{A_DATA}/responses.nc",
    log:
        "results/logs/a_responses.log",
    benchmark:
        "results/benchmarks/a_responses.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        case=A["case"],
        offset=A["initial_offset"],
        betas=A["fig5_6"]["betas"],
        tau_end=A["tau_end"],
        tau_step=A["tau_step"],
        rk=A["rk"],
        code=code("io", "a_model"),
    script:
        "../scripts/a_responses.py"


rule a_stability:
    output:
        f"{A_DATA}/stability_region.nc",
    log:
        "results/logs/a_stability.log",
    benchmark:
        "results/benchmarks/a_stability.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        case=A["case"],
        fig7=A["fig7"],
        code=code("io", "a_model"),
    script:
        "../scripts/a_stability.py"


rule a_error_study:
    output:
        f"{A_DATA}/error_study.nc",
    log:
        "results/logs/a_error_study.log",
    benchmark:
        "results/benchmarks/a_error_study.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        case=A["case"],
        offset=A["initial_offset"],
        study=A["error_study"],
        tau_step=A["tau_step"],
        rk=A["rk"],
        code=code("io", "a_model"),
    script:
        "../scripts/a_error_study.py"


rule a_slow_flow:
    output:
        f"{A_DATA}/slow_flow.nc",
    log:
        "results/logs/a_slow_flow.log",
    benchmark:
        "results/benchmarks/a_slow_flow.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        case=A["case"],
        flow=A["slow_flow"],
        code=code("io", "a_model"),
    script:
        "../scripts/a_slow_flow.py"


rule a_figure:
    input:
        unpack(
            lambda wc: {
                name: f"{A_DATA}/{dataset}.nc"
                for name, dataset in A_FIGURES[wc.fig][1].items()
            }
        ),
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{A_FIG}/{{fig}}.png",
            caption="../report/a_figure.rst",
            category="Paper A",
            subcategory="Figures",
        ),
    log:
        "results/logs/a_figure_{fig}.log",
    wildcard_constraints:
        fig="|".join(A_FIGURES),
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        paper="A",
        module="rotorvib.abb.mms_figures",
        figure=lambda wc: A_FIGURES[wc.fig][0],
        options=lambda wc: A_FIGURES[wc.fig][2],
        code=code("a_figures"),
    script:
        "../scripts/figure.py"


rule a_reproduced_values:
    input:
        resp=f"{A_DATA}/responses.nc",
        region=f"{A_DATA}/stability_region.nc",
        err=f"{A_DATA}/error_study.nc",
        paper_values=PAPER_VALUES,
    output:
        "results/paper_a/reproduced.csv",
    log:
        "results/logs/a_reproduced_values.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        case=A["case"],
        code=code("a_claims"),
    script:
        "../scripts/a_reproduced_values.py"
