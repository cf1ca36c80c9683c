# Paper C: dual dynamic vibration absorber on a torsional rotor.
# config key -> rule -> script -> library function -> dataset -> figure.


rule c_derivation_checks:
    output:
        csv=report(
            f"{C_TAB}/derivation_checks.csv",
            caption="../report/c_derivation_checks.rst",
            category="Paper C",
            subcategory="Tables",
        ),
        md=f"{C_TAB}/derivation_checks.md",
    log:
        "results/logs/c_derivation_checks.log",
    benchmark:
        "results/benchmarks/c_derivation_checks.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        module="rotorvib.dva.derivation",
        code=code("c_derivation"),
    script:
        "../scripts/derivation_checks.py"


rule c_ga:
    output:
        f"{C_DATA}/ga.nc",
    log:
        "results/logs/c_ga.log",
    benchmark:
        "results/benchmarks/c_ga.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=20,
        mem_mb=2000,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        bounds=C["bounds"],
        ga=C["ga"],
        code=code("io", "c_model", "c_ga"),
    script:
        "../scripts/c_ga.py"


rule c_frequency_response:
    input:
        ga=f"{C_DATA}/ga.nc",
    output:
        f"{C_DATA}/frequency_response.nc",
    log:
        "results/logs/c_frequency_response.log",
    benchmark:
        "results/benchmarks/c_frequency_response.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
        code=code("io", "c_model"),
    script:
        "../scripts/c_frequency_response.py"


rule c_mass_ratio:
    output:
        f"{C_DATA}/mass_ratio.nc",
    log:
        "results/logs/c_mass_ratio.log",
    benchmark:
        "results/benchmarks/c_mass_ratio.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
        family=C["mass_ratio_family"],
        code=code("io", "c_model"),
    script:
        "../scripts/c_mass_ratio.py"


rule c_time_response:
    output:
        f"{C_DATA}/time_response.nc",
    log:
        "results/logs/c_time_response.log",
    benchmark:
        "results/benchmarks/c_time_response.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=20,
        mem_mb=2000,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        den_hartog=C["den_hartog"],
        time=C["time_response"],
        code=code("io", "c_model"),
    script:
        "../scripts/c_time_response.py"


rule c_table2:
    input:
        ga=f"{C_DATA}/ga.nc",
    output:
        csv=report(
            f"{C_TAB}/table2.csv",
            caption="../report/c_table2.rst",
            category="Paper C",
            subcategory="Tables",
        ),
        md=f"{C_TAB}/table2.md",
    log:
        "results/logs/c_table2.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=500,
    params:
        code=code("c_claims"),
    script:
        "../scripts/c_table2.py"


rule c_reproduced_values:
    input:
        ga=f"{C_DATA}/ga.nc",
        fr=f"{C_DATA}/frequency_response.nc",
        mr=f"{C_DATA}/mass_ratio.nc",
        tr=f"{C_DATA}/time_response.nc",
        paper_values=PAPER_VALUES,
    output:
        "results/paper_c/reproduced.csv",
    log:
        "results/logs/c_reproduced_values.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        rotor=C["rotor"],
        claims=C["claims"],
        code=code("c_claims"),
    script:
        "../scripts/c_reproduced_values.py"


# --- figures: one rule each, datasets in, PNG out -----------------------------------------


rule c_fig3:
    input:
        tr=f"{C_DATA}/time_response.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/fig3.png",
            caption="../report/c_fig3.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_fig3.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=1000,
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="fig3",
        options={"t_at": C["claims"]["fig3_time"]},
        code=code("c_figures"),
    script:
        "../scripts/figure.py"


use rule c_fig3 as c_fig4 with:
    input:
        tr=f"{C_DATA}/time_response.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/fig4.png",
            caption="../report/c_fig4.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_fig4.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="fig4",
        options={},
        code=code("c_figures"),


use rule c_fig3 as c_linearisation with:
    input:
        tr=f"{C_DATA}/time_response.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/linearisation.png",
            caption="../report/c_linearisation.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_linearisation.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="linearisation",
        options={},
        code=code("c_figures"),


use rule c_fig3 as c_fig5 with:
    input:
        fr=f"{C_DATA}/frequency_response.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/fig5.png",
            caption="../report/c_fig5.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_fig5.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="fig5",
        options={},
        code=code("c_figures"),


use rule c_fig3 as c_fig6 with:
    input:
        mr=f"{C_DATA}/mass_ratio.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/fig6.png",
            caption="../report/c_fig6.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_fig6.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="fig6",
        options={"w_low": C["claims"]["fig6_w_low"]},
        code=code("c_figures"),


use rule c_fig3 as c_fig7 with:
    input:
        tr=f"{C_DATA}/time_response.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/fig7.png",
            caption="../report/c_fig7.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_fig7.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="fig7",
        options={},
        code=code("c_figures"),


use rule c_fig3 as c_ga_convergence with:
    input:
        ga=f"{C_DATA}/ga.nc",
        paper_values=PAPER_VALUES,
    output:
        report(
            f"{C_FIG}/ga_convergence.png",
            caption="../report/c_ga_convergence.rst",
            category="Paper C",
            subcategory="Figures",
        ),
    log:
        "results/logs/c_ga_convergence.log",
    params:
        paper="C",
        module="rotorvib.dva.figures",
        figure="ga_convergence",
        options={},
        code=code("c_figures"),
