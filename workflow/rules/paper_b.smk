# Paper B: damping ratio and ball mass of a two-ball automatic balancer.
# (So far: the symbolic check of its printed equations; the reproduction follows.)


rule b_derivation_checks:
    output:
        csv=report(
            "results/paper_b/tables/derivation_checks.csv",
            caption="../report/b_derivation_checks.rst",
            category="Paper B",
            subcategory="Tables",
        ),
        md="results/paper_b/tables/derivation_checks.md",
    log:
        "results/logs/b_derivation_checks.log",
    benchmark:
        "results/benchmarks/b_derivation_checks.tsv"
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=2000,
    params:
        module="rotorvib.abb.derivation",
        code=code("b_derivation"),
    script:
        "../scripts/derivation_checks.py"
