# The side-by-side table of every value the papers state against the reproduction, and the
# discrepancy analysis of the numbers it misses.


rule comparison:
    input:
        paper_values=PAPER_VALUES,
        reproduced=[reproduced_file(paper) for paper in PAPERS],
        # the papers whose rules analyse the numbers missed
        discrepancies=[
            getattr(rules, name).output[0]
            for name in (f"{paper}_discrepancies" for paper in PAPERS)
            if name in {rule.name for rule in workflow.rules}
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
