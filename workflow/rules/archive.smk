# `snakemake -j2 archive`: one tarball of every dataset, table and figure, with a SHA-256
# manifest and a README on restoring it without recomputation.


rule archive:
    input:
        all_results(),
    output:
        "results/archive/rotorvib-results.tar.gz",
    log:
        "results/logs/archive.log",
    conda:
        "../envs/rotorvib.yaml"
    threads: 1
    resources:
        runtime=10,
        mem_mb=1000,
    params:
        code=code("archive"),
    script:
        "../scripts/archive.py"
