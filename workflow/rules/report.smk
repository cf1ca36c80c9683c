# The report's words: its landing page and the caption of every figure and table, written from
# the comparison table by rotorvib.report so that they cannot disagree with it. Snakemake reads
# them when it renders `snakemake --report` (Snakefile `report:`, each `report()` caption).


rule report_text:
    input:
        comparison="results/comparison.csv",
        discrepancies="results/discrepancies.csv",
        paper_values=PAPER_VALUES,
        papers="data/papers.yaml",
        tables=[
            table(paper, name, "csv")
            for paper in TABLES
            if paper != "all"
            for name in TABLES[paper]
        ],
    output:
        landing=REPORT_LANDING,
        figure_captions=captions(FIGURES, "figure"),
        table_captions=captions(TABLES, "table"),
    log:
        logs("report_text"),
    # Reads tables only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        figures={
            paper: {
                name: {k: d[k] for k in ("shows", "items")}
                for name, d in figures.items()
            }
            for paper, figures in FIGURES.items()
        },
        tables=TABLES,
    message:
        "The report's landing page and captions, from the comparison"
    script:
        "../scripts/report_text.py"
