# `snakemake -j2 archive`: one tarball of every dataset, table and figure, the licence and the
# citation file, with a SHA-256 manifest and a README on restoring it without recomputation.


rule archive:
    input:
        all_results(),
        "LICENSE",
        "CITATION.cff",
    output:
        "results/archive/rotorvib-results.tar.gz",
    log:
        logs("archive"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Packing every result into one archive"
    script:
        "../scripts/archive.py"
