# The side-by-side table of every value the papers state against the reproduction.


rule comparison:
    input:
        paper_values=PAPER_VALUES,
        reproduced=[
            "results/paper_a/reproduced.csv",
            "results/paper_b/reproduced.csv",
            "results/paper_c/reproduced.csv",
        ],
    output:
        csv=report(
            "results/comparison.csv",
            caption="../report/comparison.rst",
            category="Comparison",
        ),
        md="results/comparison.md",
    log:
        "results/logs/comparison.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=5,
        mem_mb=500,
    params:
        code=code("comparison"),
    script:
        "../scripts/comparison.py"
