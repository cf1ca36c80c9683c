# `snakemake -j2 archive`: one tarball of every dataset, table and figure (PNG, SVG and what it
# draws), the report's words
# and pages, the run's record (commit and configuration), the licence and the citation file,
# with a SHA-256 manifest, restore notes and an RO-Crate describing the run (rotorvib.pipeline.crate);
# two builds of one commit and configuration give the same bytes (rotorvib.pipeline.archive). The HTML
# report is rebuilt from a restored archive by `snakemake --report`.
from rotorvib.io.provenance import code_state

RUN_RECORD = {
    "config": f"{RESULTS_DIR}/run/config.yaml",
    "commit": f"{RESULTS_DIR}/run/commit.txt",
}


rule run_record:
    output:
        **RUN_RECORD,
    log:
        logs("run_record"),
    localrule: True
    # A change of the configuration or of the library's commit rewrites the record.
    params:
        config=config,
        commit=code_state(),
    message:
        "The run's configuration and commit, as files"
    script:
        "../scripts/run_record.py"


rule archive:
    input:
        results=PLAN.all_results() + PLAN.figure_companions(),
        configuration=list(RUN_RECORD.values()) + configuration_files(),
        code=[source(name) for name in ("Snakefile", "LICENSE", "CITATION.cff")],
    output:
        archive=f"{RESULTS_DIR}/archive/rotorvib-results.tar.gz",
        # its SHA-256, to publish with it: a restore checks the archive against it
        digest=f"{RESULTS_DIR}/archive/rotorvib-results.tar.gz.sha256",
    log:
        logs("archive"),
    # Reads datasets only: runs where Snakemake runs, never as a cluster job.
    localrule: True
    message:
        "Packing every result into one archive"
    script:
        "../scripts/archive.py"
