# The report: its words (the landing page and the caption of every figure and table) and its
# HTML pages (the summary, every table), written from the comparison by rotorvib.pipeline.report so that
# they cannot disagree with it; then the files it shows. Snakemake reads them when it renders
# `snakemake --report` (Snakefile `report:`, the `report()` flags of rule report_results).


rule report_text:
    input:
        comparison=f"{RESULTS_DIR}/comparison.csv",
        discrepancies=f"{RESULTS_DIR}/discrepancies.csv",
        paper_values=PAPER_VALUES,
        tables=[d["csv"] for paper in TABLES for d in TABLES[paper].values()],
        drawn=[
            figure_file(paper, name, "json")
            for paper in FIGURES
            for name in FIGURES[paper]
        ],
    output:
        landing=PLAN.landing,
        summary=PLAN.summary_page,
        figure_captions=PLAN.captions("figure"),
        table_captions=PLAN.captions("table"),
        table_pages=PLAN.table_pages(),
    log:
        logs("report_text"),
    # Reads tables only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        # the run's papers as data/papers.yaml cites them, read here as the configuration is
        # (strictly): no job reads YAML
        papers={
            letter: entry
            for letter, entry in load_yaml(source("data/papers.yaml")).items()
            if letter.lower() in PAPERS
        },
        figures={
            paper: {
                name: {k: d[k] for k in ("shows", "items")}
                for name, d in figures.items()
            }
            for paper, figures in FIGURES.items()
        },
        tables=TABLES,
        # the rule, script and function that made each, and the rules of its datasets
        made_by={
            kind: {
                paper: {
                    name: PLAN.made_by(rule_making, FIGURE_GROUPS, paper, name, kind)
                    for name in outputs
                }
                for paper, outputs in declared.items()
            }
            for kind, declared in (("figure", FIGURES), ("table", TABLES))
        },
    message:
        "The report's landing page, summary, captions and table pages, from the comparison"
    script:
        "../scripts/report_text.py"


# The files the report shows, copied, so that their result pages show no job parameters: a
# script job's parameters carry code fingerprints and configuration hashes (common.smk), which
# Snakemake's report would print under each caption. This job has none, and runs no library
# code (a `run:` block, whose own code Snakemake watches).
import shutil

_SHOWN = PLAN.report_entries()


rule report_results:
    input:
        [source for source, _ in _SHOWN.values()],
    output:
        [report(path, **arguments) for path, (_, arguments) in _SHOWN.items()],
    log:
        logs("report_results"),
    localrule: True
    message:
        "The files the report shows"
    run:
        for source, path in zip(input, output):
            shutil.copyfile(source, path)
