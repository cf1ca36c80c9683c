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
        csv=report(
            "results/comparison.csv",
            caption="../report/comparison.rst",
            category="Comparison",
        ),
        md="results/comparison.md",
        discrepancies_csv="results/discrepancies.csv",
        discrepancies_md="results/discrepancies.md",
    log:
        logs("comparison"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Comparison of every stated value with the reproduction, and its discrepancy analysis"
    script:
        "../scripts/comparison.py"
