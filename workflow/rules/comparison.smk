# The side-by-side table of every value the papers state against the reproduction, and the
# discrepancy analysis of the numbers it misses.


rule comparison:
    input:
        paper_values=PAPER_VALUES,
        reproduced=[
            rules.a_reproduced_values.output[0],
            rules.b_reproduced_values.output[0],
            rules.c_reproduced_values.output[0],
        ],
        discrepancies=[
            rules.b_discrepancies.output[0],
            rules.c_discrepancies.output[0],
        ],
    output:
        csv=report_table(
            "all",
            "comparison",
            "Every value and claim the papers state (data/paper_values.csv) beside the "
            "reproduced value, with the relative error, the verdict and the explanation "
            "of each difference.",
            path=f"{RESULTS_DIR}/comparison.csv",
        ),
        md=f"{RESULTS_DIR}/comparison.md",
        discrepancies_csv=report_table(
            "all",
            "discrepancies",
            "Each printed number the reproduction misses, tested against alternative "
            "readings of the paper (definitions, variants, parameter slips, units, "
            "rounding): the value each hypothesis gives and whether it reproduces the "
            "printed one (within the MATCH tolerance); an inversion gives the single "
            "parameter value that would.",
            path=f"{RESULTS_DIR}/discrepancies.csv",
        ),
        discrepancies_md=f"{RESULTS_DIR}/discrepancies.md",
    log:
        logs("comparison"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Comparison of every stated value with the reproduction, and its discrepancy analysis"
    script:
        "../scripts/comparison.py"
