# Paper C: dual dynamic vibration absorber on a torsional rotor.
FIGURES["c"] = {
    "fig3": figure(
        "fig3",
        {"tr": "time_response"},
        "Twist of the rotor without absorber driven at its natural frequency from rest "
        "(nonlinear equations (8)-(10), which reduce to J theta'' + k_t theta = Gamma), with "
        "the exact envelope Gamma0 t/(2 J omega_n) and the paper's stated amplitude (red star).",
        t_at=C["claims"]["fig3_time"],
    ),
    "fig4": figure(
        "fig4",
        {"tr": "time_response"},
        "Response at resonance without absorber, with a classical single absorber of the same "
        "total mass tuned by Den Hartog's rules (stand-in for the unavailable ref. [8] "
        "absorber) and with the Table 2 dual absorber.",
    ),
    "fig5": figure(
        "fig5",
        {"fr": "frequency_response"},
        "Dimensionless amplitude D = |Theta| k_t/Gamma0 against w = omega/omega_n without "
        "absorber, for Table 2 with zero damping and with its damping, for Table 2 with the "
        "printed determinant, and for the optimum our GA finds; each curve's largest peak "
        "marked, the paper's objective as D (red star).",
    ),
    "fig6": figure(
        "fig6",
        {"mr": "mass_ratio"},
        "Frequency response for mass ratios mu = m2/m1 (k2 = mu k1 keeps set 2 tuned as in "
        "Table 2; other parameters from Table 2).",
        w_low=C["claims"]["fig6_w_low"],
    ),
    "distance": figure(
        "distance",
        {"ds": "distance"},
        "The abstract's study of the absorbers' distance from the disk centre (its figure did "
        "not survive extraction): D(w) for Table 2 with both sets moved by the same offset.",
        items=["Abstract"],
    ),
    "spin": figure(
        "spin",
        {"ds": "spin"},
        "Beyond the paper: Table 2's absorber on a rotor spinning at Omega, which the paper's "
        "model leaves out (springs softened to 2k - m Omega^2): each set's tuning and D at "
        "resonance over the spin, and the frequency response at rest and at a realistic spin.",
        items=["Spin"],
    ),
    "fig7": figure(
        "fig7",
        {"tr": "time_response"},
        "Displacements of absorber sets 1 and 2 of the Table 2 design at resonance (nonlinear "
        "equations).",
    ),
    "ga_convergence": figure(
        "ga_convergence",
        {"ga": "ga"},
        "Convergence of the genetic algorithm (best and mean |Theta(omega_n)| per "
        "generation), with Table 2 evaluated by eq. (20) and the paper's reported objective.",
        items=["Section 4"],
    ),
    "linearisation": figure(
        "linearisation",
        {"tr": "time_response"},
        "Beyond the paper: difference between the nonlinear equations (8)-(10) and the "
        "linear set (14) for the three cases of Fig 4 (the paper linearises without showing "
        "the effect).",
    ),
    "uncertainty": figure(
        "uncertainty",
        {"unc": "uncertainty"},
        "Beyond the paper: how sure Table 2's objective is. Sobol indices (first-order and "
        "total, 95 % bootstrap intervals) of |Theta(omega_n)| with every Table 2 value within "
        "its manufacturing tolerance, their convergence with the sample, and the objective's "
        "distribution with the printed value.",
        items=["Uncertainty"],
    ),
    "broadband": figure(
        "broadband",
        {"bb": "broadband"},
        "Beyond the paper: the absorber optimised for the peak of D over a band around "
        "resonance (NSGA-II, two objectives: that peak and the added mass, within the bounds "
        "of section 4), at no more added mass than Table 2, beside Table 2, the GA optimum of "
        "|Theta(omega_n)| and Den Hartog's single absorber of Table 2's mass: frequency "
        "responses, exact linear time responses from rest at resonance, and the Pareto front "
        "with Den Hartog's absorber of each mass.",
        items=["Broadband absorber"],
    ),
}


RESULTS["c"] = results_of(
    "c",
    ["discrepancies"],  # the datasets no figure draws (drawn_datasets adds the others)
    ["derivation_checks", "table2", "broadband"],
)


rule c_derivation_checks:
    output:
        csv=report_table(
            "c",
            "derivation_checks",
            "Equations (1)-(20) re-derived with sympy (Lagrange's equations from the kinetic "
            "and potential energies and the generalised forces) and compared with the "
            "printed ones. A FAIL row gives the difference from the printed equation; "
            "every result downstream uses the derived equations.",
            items=["eq. 20"],
            path=table("c", "derivation_checks", "csv"),
        ),
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
        csv=report_table(
            "c",
            "broadband",
            "Beyond the paper: each absorber design with its parameters (m, k, c, d of "
            "each set), added mass, largest D over the band and over all frequencies, and "
            "its largest |theta| over the last forcing period at resonance.",
            items=["Broadband absorber"],
            path=table("c", "broadband", "csv"),
        ),
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
        csv=report_table(
            "c",
            "table2",
            "The paper's optimum dual absorber (Table 2) beside the optimum our genetic "
            "algorithm finds with the paper's bounds, population and generations, both "
            "evaluated with eq. (20).",
            items=["Section 4"],
            path=table("c", "table2", "csv"),
        ),
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
