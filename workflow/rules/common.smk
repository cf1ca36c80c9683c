# What the rules share that needs Snakemake's objects: the configuration, read strictly and
# checked before the rules are read; the plan of the run's files (rotorvib.pipeline.plan, with
# the paths, the papers' outputs, the report's entries and the figure grouping), handed the rule
# graph; and the rules for rule authors, checked once every rule is read (check_rules). The
# parameters every script rule gets then are rotorvib.pipeline.rule_params's.
import json
import os
from functools import cache
from pathlib import Path

from snakemake.exceptions import WorkflowError

from rotorvib.pipeline.config import ConfigError, load_yaml
from rotorvib.pipeline.plan import (
    BESIDE_THE_COMPILE,
    COMPUTES,
    LONGEST_CHAIN,
    Plan,
    rule_problems,
)
from rotorvib.pipeline.report_pages import read_docutils_settings_last
from rotorvib.pipeline.rule_params import add_code_fingerprints, add_input_checks
from rotorvib.pipeline.run_config import run_config
from rotorvib.pipeline.snakemake_rules import (
    caller_config,
    declared,
    module_config_given,
    producer,
)

# The workflow's own folder (this file is workflow/rules/common.smk in it): its schema and the
# papers' data are read from there, so that it runs from another working directory
# (`--directory`) or as a module of another workflow.
WORKFLOW_ROOT = Path(str(workflow.current_basedir)).resolve().parents[1]
# The run's working folder (`--directory`, or the caller's), as Snakemake reads the rules in it:
# when the run ends (onsuccess), Snakemake is back in the folder the command started in.
WORKING_FOLDER = Path.cwd().resolve()

# Snakemake's rendering of the report's words reads the workflow's docutils.conf (no include,
# no raw HTML) wherever it runs, a caller's folder included (rotorvib.pipeline.report_pages).
read_docutils_settings_last(WORKFLOW_ROOT / "docutils.conf")


def source(relative):
    """A file of the workflow's own folder: as ``relative`` when Snakemake runs in that folder
    (the paths the job records and the archive hold), else as an absolute path."""
    if Path.cwd().resolve() == WORKFLOW_ROOT:
        return relative
    return str(WORKFLOW_ROOT / relative)


# The configuration, read again strictly from the files and entries Snakemake read (YAML 1.2:
# rotorvib.pipeline.run_config) and checked, before any rule is read.
try:
    _read = run_config(
        workflow.config_settings,
        workflow.configfiles,
        WORKFLOW_ROOT,
        (config, caller_config(workflow)) if module_config_given(workflow) else None,
    )
except ConfigError as error:
    raise WorkflowError(str(error)) from None
config.clear()
config.update(_read)

# The papers, from the configuration's paper_<p> sections (each has its rules in
# workflow/rules/paper_<p>.smk and its package rotorvib.papers.<p>).
PAPERS = sorted(
    key.removeprefix("paper_") for key in config if key.startswith("paper_")
)
# the comparison's reading of the papers' words ("close" and its alternatives), shared by
# every paper's claims (rotorvib.comparison.choices.Close)
CLOSE = config["comparison"]
# Threads of each batch rule (it declares `batch=1` among its resources, and shares a batch of
# runs out over threads, rotorvib.models.balancer.simulate, or searches over processes,
# rotorvib.methods.forked), half the cores Snakemake is given: -j2 runs two single-threaded
# jobs side by side, a larger -j hands each batch job several cores (profiles/slurm sets its
# own, written from the rules by rotorvib.pipeline.slurm_profile). A command given no cores
# (--rulegraph, --lint) plans with one.
try:
    BATCH_THREADS = max(1, int(workflow.cores) // 2)
except (WorkflowError, TypeError):
    BATCH_THREADS = 1
# Where every output goes: results/ for the paper configuration, its own folder for another
# (config key `results`; the reduced configuration writes to results/reduced).
RESULTS_DIR = config["results"]
PAPER_VALUES = source("data/paper_values.csv")
PLAN = Plan(
    {paper: config[f"paper_{paper}"] for paper in PAPERS},
    RESULTS_DIR,
    WORKING_FOLDER,
)
# The plan's paths and declarations, as the rule files name them.
dataset, shard_file, shards_of, table = (
    PLAN.dataset,
    PLAN.shard_file,
    PLAN.shards_of,
    PLAN.table,
)
figure_file, reproduced_file, logs, benchmarks = (
    PLAN.figure_file,
    PLAN.reproduced_file,
    PLAN.logs,
    PLAN.benchmarks,
)
report_table, in_working_folder = PLAN.report_table, PLAN.in_working_folder
FIGURES, TABLES = PLAN.figures, PLAN.tables
RESULTS = {paper: PLAN.results_of(paper) for paper in PAPERS}


@cache
def rule_making(path):
    """The rule that makes ``path`` as the plan reads it (rotorvib.pipeline.plan.Maker; None for
    a file of the workflow's own), looked for once a path. Rules are only ever added after the
    others, so the first that makes a path stays the first. Looked for each time, a dry run of
    the reduced configuration forked from a prepared Snakemake took 0.57 s instead of 0.49 s.
    """
    maker = producer(workflow.rules, path)
    return None if maker is None else declared(workflow, maker, WORKFLOW_ROOT)


def check_rules():
    """The rules for rule authors (rotorvib.pipeline.plan.rule_problems), checked once every
    rule is read; and, where the environment names a file (ROTORVIB_RULES_JSON), every rule as
    the plan reads it written there (python -m rotorvib.pipeline.slurm_profile and the tests
    read the rules from it, not from the rule files' text)."""
    rules = [declared(workflow, rule, WORKFLOW_ROOT) for rule in workflow.rules]
    if problems := rule_problems(rules):
        raise WorkflowError("\n".join(problems))
    if written := os.environ.get("ROTORVIB_RULES_JSON"):
        Path(written).write_text(json.dumps([vars(rule) for rule in rules], indent=1))


def configuration_files():
    """The configuration files the run read that lie in the working directory, as relative
    paths (the whole merged configuration is a file of the archive in any case, archive.smk).
    """
    here = Path.cwd()
    paths = {Path(f).resolve() for f in workflow.configfiles}
    return sorted(str(p.relative_to(here)) for p in paths if p.is_relative_to(here))
