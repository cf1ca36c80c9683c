# The side-by-side table of every value the papers state against the reproduction, and the
# discrepancy analysis of the numbers it misses (captions: rotorvib.papers.outputs.PROJECT_TABLES).
from rotorvib.papers.outputs import PROJECT_TABLES


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
            path=f"{RESULTS_DIR}/comparison.csv",
            **PROJECT_TABLES["comparison"],
        ),
        md=f"{RESULTS_DIR}/comparison.md",
        discrepancies_csv=report_table(
            "all",
            "discrepancies",
            path=f"{RESULTS_DIR}/discrepancies.csv",
            **PROJECT_TABLES["discrepancies"],
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
