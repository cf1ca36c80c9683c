# rotorvib: reproduction of three rotor-dynamics papers (see README.md).
# `snakemake -j2` builds everything (rule all); `snakemake -j2 archive` packs the results.
from snakemake.utils import min_version

from rotorvib.pipeline.run_summary import failure_text, left_out, success_text

min_version("9.0")


# The defaults beside this Snakefile, wherever Snakemake runs (`--directory`) and whichever file
# it was given (workflow/Snakefile includes this one); a module given its own `config:` skips
# them and merges that over them (workflow/rules/common.smk).
configfile: f"{workflow.current_basedir}/config/config.yaml"


include: "workflow/rules/common.smk"


# The shard wildcards of every batch study's shard rule (shard_file, common.smk): shard k of n.
wildcard_constraints:
    shard=r"\d+",
    shards=r"\d+",


# Each paper of the configuration (PAPERS, common.smk) has its rules in its own file.
for _paper in PAPERS:

    include: f"workflow/rules/paper_{_paper}.smk"


include: "workflow/rules/figures.smk"
include: "workflow/rules/comparison.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/archive.smk"


# The report's landing page is written from the comparison by rule report_text (report.smk).
# (A module's is its caller's: Snakemake skips this line in a module, docs/user-guide.md.)
report: in_working_folder(PLAN.landing)


rule all:
    default_target: True
    input:
        PLAN.all_results(),
    # a message instead of the job's input list (every result: kilobytes) on the console
    message:
        "Every result of the three papers, the comparison and the report"


# What the console says when the run ends (rotorvib.pipeline.run_summary): where the results are,
# the papers the configuration leaves out and the report's command; or each failed job, its log
# and the first lines of its error. Both read the run's working folder (WORKING_FOLDER, common.smk):
# when they run, Snakemake is back in the folder the command started in.
onsuccess:
    print(
        success_text(
            RESULTS_DIR,
            PAPERS,
            left_out=left_out(
                PAPERS, load_yaml(WORKFLOW_ROOT / "config/schema.yaml")
            ),
            configfiles=workflow.config_settings.configfiles,
            config_args=workflow.config_settings.config_args or (),
            root=WORKING_FOLDER,
            elsewhere=(
                None
                if WORKING_FOLDER == WORKFLOW_ROOT
                else (WORKING_FOLDER, WORKFLOW_ROOT / "profiles/report.css")
            ),
        )
    )


onerror:
    print(failure_text(log, root=WORKING_FOLDER))


# The rules for rule authors, once every rule is read (rotorvib.pipeline.plan.rule_problems);
# every script rule's `code` parameter: the fingerprint of the library code it runs; then the
# configuration hash each of its input datasets must carry.
check_rules()
add_code_fingerprints(workflow.rules)
add_input_checks(workflow.rules)
