# Every figure of every paper: one rule, driven by the FIGURES declarations of the papers' .smk
# files. A figure reads datasets only (and the papers' values); nothing is recomputed here.


rule figure:
    input:
        unpack(figure_inputs),
        paper_values=PAPER_VALUES,
    output:
        report(
            "results/paper_{paper}/figures/{name}.png",
            caption=f"../../{REPORT_TEXT['figure_captions']}",
            category=lambda wc: f"Paper {wc.paper.upper()}",
            subcategory="Figures",
            labels=lambda wc: report_labels(FIGURES[wc.paper], wc.name, "figure"),
        ),
    log:
        logs("figure_{paper}_{name}"),
    wildcard_constraints:
        paper="|".join(FIGURES),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    params:
        module=lambda wc: f"rotorvib.papers.{wc.paper}.figures",
        function=lambda wc: FIGURES[wc.paper][wc.name]["function"],
        options=lambda wc: FIGURES[wc.paper][wc.name]["options"],
    message:
        "Paper {wildcards.paper}: drawing figure {wildcards.name}"
    script:
        "../scripts/figure.py"
