# Paper B: damping ratio and ball mass of a two-ball automatic balancer.


rule b_derivation_checks:
    output:
        csv=report(
            "results/paper_b/tables/derivation_checks.csv",
            caption="../report/b_derivation_checks.rst",
            category="Paper B",
            subcategory="Tables",
        ),
        md="results/paper_b/tables/derivation_checks.md",
    log:
        "results/logs/b_derivation_checks.log",
    benchmark:
        "results/benchmarks/b_derivation_checks.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        module="rotorvib.abb.derivation",
        code=code("b_derivation"),
    script:
        "../scripts/derivation_checks.py"


rule b_stability:
    output:
        f"{B_DATA}/stability_{{fig}}.nc",
    log:
        "results/logs/b_stability_{fig}.log",
    benchmark:
        "results/benchmarks/b_stability_{fig}.tsv"
    wildcard_constraints:
        fig="fig2|fig3",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        machine=B["machine"],
        map=lambda wc: B["stability_maps"][wc.fig],
        code=code("io", "b_model"),
    script:
        "../scripts/b_stability.py"


rule b_balance_grid:
    output:
        f"{B_DATA}/balance_{{axis}}.nc",
    log:
        "results/logs/b_balance_{axis}.log",
    benchmark:
        "results/benchmarks/b_balance_{axis}.tsv"
    wildcard_constraints:
        axis="beta|mass",
    conda:
        "../envs/rotorvib.yaml"
    threads: 2
    resources:
        runtime=30,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        ics=B["initial_conditions"],
        grids=B["grids"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_balance_grid.py"


rule b_time_responses:
    output:
        f"{B_DATA}/time_responses.nc",
    log:
        "results/logs/b_time_responses.log",
    benchmark:
        "results/benchmarks/b_time_responses.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        ics=B["initial_conditions"],
        responses=B["time_responses"],
        table2=B["table2"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_time_responses.py"


rule b_ga:
    output:
        f"{B_DATA}/ga.nc",
    log:
        "results/logs/b_ga.log",
    benchmark:
        "results/benchmarks/b_ga.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 2
    resources:
        runtime=60,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        ics=B["initial_conditions"],
        eps_bars=B["grids"]["eps_bar"],
        ga=B["ga"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_ga.py"


rule b_table1_runs:
    output:
        f"{B_DATA}/table1.nc",
    log:
        "results/logs/b_table1_runs.log",
    benchmark:
        "results/benchmarks/b_table1_runs.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 2
    resources:
        runtime=30,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        ics=B["initial_conditions"],
        table1=B["table1"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_table1.py"


rule b_forces:
    output:
        f"{B_DATA}/forces.nc",
    log:
        "results/logs/b_forces.log",
    benchmark:
        "results/benchmarks/b_forces.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 2
    resources:
        runtime=30,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        ics=B["initial_conditions"],
        table2=B["table2"],
        calibration=B["calibration"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_forces.py"


rule b_basin:
    output:
        f"{B_DATA}/basin.nc",
    log:
        "results/logs/b_basin.log",
    benchmark:
        "results/benchmarks/b_basin.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 2
    resources:
        runtime=60,
        mem_mb=2000,
    params:
        setup=B_SETUP,
        kinematics=B["kinematics"],
        basin=B["basin"],
        code=code("io", "b_model"),
    script:
        "../scripts/b_basin.py"


rule b_figure:
    input:
        unpack(
            lambda wc: {
                name: f"{B_DATA}/{dataset}.nc"
                for name, dataset in B_FIGURES[wc.fig][1].items()
            }
        ),
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{B_FIG}/{{fig}}.png",
            caption="../report/b_figure.rst",
            category="Paper B",
            subcategory="Figures",
        ),
    log:
        "results/logs/b_figure_{fig}.log",
    wildcard_constraints:
        fig="|".join(B_FIGURES),
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        paper="B",
        module="rotorvib.abb.figures",
        figure=lambda wc: B_FIGURES[wc.fig][0],
        options=lambda wc: B_FIGURES[wc.fig][2],
        code=code("b_figures"),
    script:
        "../scripts/figure.py"


rule b_tables:
    input:
        table1=f"{B_DATA}/table1.nc",
        forces=f"{B_DATA}/forces.nc",
        beta=f"{B_DATA}/balance_beta.nc",
        mass=f"{B_DATA}/balance_mass.nc",
        ga=f"{B_DATA}/ga.nc",
    output:
        table1=report(
            f"{B_TAB}/table1.csv",
            caption="../report/b_table1.rst",
            category="Paper B",
            subcategory="Tables",
        ),
        table1_md=f"{B_TAB}/table1.md",
        table2=report(
            f"{B_TAB}/table2.csv",
            caption="../report/b_table2.rst",
            category="Paper B",
            subcategory="Tables",
        ),
        table2_md=f"{B_TAB}/table2.md",
        kinematics=f"{B_TAB}/kinematics.md",
    log:
        "results/logs/b_tables.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        R=B["machine"]["R"],
        code=code("b_claims"),
    script:
        "../scripts/b_tables.py"


rule b_reproduced_values:
    input:
        st2=f"{B_DATA}/stability_fig2.nc",
        st3=f"{B_DATA}/stability_fig3.nc",
        tr=f"{B_DATA}/time_responses.nc",
        beta=f"{B_DATA}/balance_beta.nc",
        mass=f"{B_DATA}/balance_mass.nc",
        ga=f"{B_DATA}/ga.nc",
        table1=f"{B_DATA}/table1.nc",
        forces=f"{B_DATA}/forces.nc",
        paper_values=PAPER_VALUES,
    output:
        "results/paper_b/reproduced.csv",
    log:
        "results/logs/b_reproduced_values.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        R=B["machine"]["R"],
        ga=B["ga"],
        beta_band=B["claims"]["beta_opt_range"],
        code=code("b_claims"),
    script:
        "../scripts/b_reproduced_values.py"
