# `snakemake -j2 archive`: one tarball of every dataset, table and figure, the HTML report, the
# run's record (commit and configuration), the licence and the citation file, with a SHA-256
# manifest, restore notes and an RO-Crate describing the run (rotorvib.io.crate).
from rotorvib.io.provenance import git_state

RUN_RECORD = {"config": "results/run/config.yaml", "commit": "results/run/commit.txt"}


rule run_record:
    output:
        **RUN_RECORD,
    log:
        logs("run_record"),
    localrule: True
    # A change of the configuration or of the commit rewrites the record.
    params:
        config=config,
        commit=git_state(),
    message:
        "The run's configuration and commit, as files"
    script:
        "../scripts/run_record.py"


rule report_html:
    input:
        all_results(),
        config=RUN_RECORD["config"],
    output:
        "results/report.html",
    log:
        logs("report_html"),
    # Snakemake's own report of the finished run, under the run's whole configuration; the
    # outer run holds the lock on the working directory, so this one takes none.
    localrule: True
    message:
        "The HTML report"
    shell:
        "snakemake --nolock --configfile {input.config} --report {output} > {log} 2>&1"


rule archive:
    input:
        results=all_results() + rules.report_html.output,
        configuration=list(RUN_RECORD.values()) + configuration_files(),
        code=["Snakefile", "LICENSE", "CITATION.cff"],
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
