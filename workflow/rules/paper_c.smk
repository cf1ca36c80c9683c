# Paper C: dual dynamic vibration absorber on a torsional rotor. Its figures and tables are
# declared in rotorvib.papers.c.outputs.
C = config["paper_c"]


rule c_derivation_checks:
    output:
        csv=table("c", "derivation_checks", "csv"),
        md=table("c", "derivation_checks", "md"),
    log:
        logs("c_derivation_checks"),
    benchmark:
        benchmarks("c_derivation_checks")
    priority: COMPUTES
    localrule: True
    params:
        module="rotorvib.papers.c.derivation",
    message:
        "Paper C: checking the printed equations symbolically"
    script:
        "../scripts/derivation_checks.py"


rule c_ga:
    output:
        dataset("c", "ga"),
    log:
        logs("c_ga"),
    benchmark:
        benchmarks("c_ga")
    priority: COMPUTES
    localrule: True
    resources:
        runtime=20,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        bounds=C["bounds"],
        ga=C["ga"],
    message:
        "Paper C: genetic-algorithm tuning of the dual absorber"
    script:
        "../scripts/c_ga.py"


rule c_frequency_response:
    input:
        ga=rules.c_ga.output[0],
    output:
        dataset("c", "frequency_response"),
    log:
        logs("c_frequency_response"),
    benchmark:
        benchmarks("c_frequency_response")
    priority: COMPUTES
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
    message:
        "Paper C: frequency responses of Fig 5"
    script:
        "../scripts/c_frequency_response.py"


rule c_mass_ratio:
    output:
        dataset("c", "mass_ratio"),
    log:
        logs("c_mass_ratio"),
    benchmark:
        benchmarks("c_mass_ratio")
    priority: COMPUTES
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
        family=C["mass_ratio_family"],
    message:
        "Paper C: mass-ratio family of Fig 6"
    script:
        "../scripts/c_mass_ratio.py"


rule c_distance:
    output:
        dataset("c", "distance"),
    log:
        logs("c_distance"),
    benchmark:
        benchmarks("c_distance")
    priority: COMPUTES
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
        offsets=C["distance_study"]["offsets"],
    message:
        "Paper C: the absorbers' distance from the disk centre"
    script:
        "../scripts/c_distance.py"


rule c_spin:
    output:
        dataset("c", "spin"),
    log:
        logs("c_spin"),
    benchmark:
        benchmarks("c_spin")
    priority: COMPUTES
    # closed forms and small linear solves: runs where Snakemake runs
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        grid=C["frequency_response"],
        spin=C["spin"],
    message:
        "Paper C (beyond the paper): Table 2's absorber on a spinning rotor"
    script:
        "../scripts/c_spin.py"


rule c_time_response:
    output:
        dataset("c", "time_response"),
    log:
        logs("c_time_response"),
    benchmark:
        benchmarks("c_time_response")
    priority: COMPUTES
    localrule: True
    resources:
        runtime=20,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        den_hartog=C["den_hartog"],
        time=C["time_response"],
    message:
        "Paper C: time responses of Figs 3, 4 and 7"
    script:
        "../scripts/c_time_response.py"


rule c_broadband:
    input:
        ga=rules.c_ga.output[0],
    output:
        dataset("c", "broadband"),
    log:
        logs("c_broadband"),
    benchmark:
        benchmarks("c_broadband")
    priority: COMPUTES
    localrule: True
    threads: BATCH_THREADS
    resources:
        batch=1,
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        bounds=C["bounds"],
        grid=C["frequency_response"],
        time=C["time_response"],
        broadband=C["broadband"],
    message:
        "Paper C (beyond the paper): NSGA-II front of the broadband absorber"
    script:
        "../scripts/c_broadband.py"


rule c_uncertainty:
    output:
        dataset("c", "uncertainty"),
    log:
        logs("c_uncertainty"),
    benchmark:
        benchmarks("c_uncertainty")
    priority: COMPUTES
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        uncertainty=C["uncertainty"],
    message:
        "Paper C (beyond the paper): Sobol indices and band of Table 2's objective"
    script:
        "../scripts/c_uncertainty.py"


rule c_broadband_table:
    input:
        bb=rules.c_broadband.output[0],
    output:
        csv=table("c", "broadband", "csv"),
        md=table("c", "broadband", "md"),
    log:
        logs("c_broadband_table"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Paper C (beyond the paper): the broadband absorber beside the others"
    script:
        "../scripts/c_broadband_table.py"


rule c_table2:
    input:
        ga=rules.c_ga.output[0],
    output:
        csv=table("c", "table2", "csv"),
        md=table("c", "table2", "md"),
    log:
        logs("c_table2"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Paper C: Table 2 beside the genetic-algorithm optimum"
    script:
        "../scripts/c_table2.py"


rule c_reproduced_values:
    input:
        ga=rules.c_ga.output[0],
        fr=rules.c_frequency_response.output[0],
        mr=rules.c_mass_ratio.output[0],
        distance=rules.c_distance.output[0],
        tr=rules.c_time_response.output[0],
        bb=rules.c_broadband.output[0],
        uncertainty=rules.c_uncertainty.output[0],
        spin=rules.c_spin.output[0],
        paper_values=PAPER_VALUES,
    output:
        reproduced_file("c"),
    log:
        logs("c_reproduced_values"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        rotor=C["rotor"],
        claims=C["claims"],
        close=CLOSE,
        rtol=C["time_response"]["rtol"],
    message:
        "Paper C: measuring the paper's stated values and claims on the datasets"
    script:
        "../scripts/c_reproduced_values.py"


rule c_discrepancies:
    input:
        reproduced=rules.c_reproduced_values.output[0],
        paper_values=PAPER_VALUES,
    output:
        dataset("c", "discrepancies"),
    log:
        logs("c_discrepancies"),
    benchmark:
        benchmarks("c_discrepancies")
    priority: COMPUTES
    localrule: True
    params:
        rotor=C["rotor"],
        table2=C["table2"],
        bounds=C["bounds"],
        ga=C["ga"],
        fig3_time=C["claims"]["fig3_time"],
        parameters=config["discrepancies"]["paper_c"],
        inversion=config["discrepancies"]["inversion"],
    message:
        "Paper C: the printed numbers the reproduction misses, under hypotheses and inverted"
    script:
        "../scripts/c_discrepancies.py"
