# Helpers shared by all rules: configuration validation (before any job), paths, the figure
# declaration, the code fingerprint every script rule receives and the configuration hash each
# of its input datasets must carry.
from functools import cache
from importlib import import_module
from pathlib import Path
from types import SimpleNamespace

from snakemake.exceptions import WorkflowError

from rotorvib.pipeline.config import ConfigError, check_config, load_yaml
from rotorvib.pipeline.config_sources import (
    command_line_overrides,
    merge,
    module_config,
    workflow_config,
)
from rotorvib.pipeline.job import INPUT_PRODUCERS_PARAM, job_config
from rotorvib.io.provenance import config_hash
from rotorvib.pipeline.fingerprint import code_fingerprint
from rotorvib.pipeline.report import categories, entry_label, names_in, subcategory
from rotorvib.pipeline.report_pages import read_docutils_settings_last
from rotorvib.pipeline.slurm_profile import batch_rules
from rotorvib.pipeline.snakemake_rules import (
    add_params,
    caller_config,
    module_config_given,
    producer,
    rule_name,
    script_path,
    wildcards,
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


def in_working_folder(path):
    """A file of this run (under Snakemake's working folder: the caller's, for a module or
    ``--directory``) as an absolute path, for the report's texts, which Snakemake reads
    relative to the rule file's folder, the workflow's own (there, a module's report failed to
    load its captions, or took them from the module's clone)."""
    return str(WORKING_FOLDER / path)


def source(relative):
    """A file of the workflow's own folder: as ``relative`` when Snakemake runs in that folder
    (the paths the job records and the archive hold), else as an absolute path."""
    if Path.cwd().resolve() == WORKFLOW_ROOT:
        return relative
    return str(WORKFLOW_ROOT / relative)


def _strict_reading():
    """The configuration as this package reads it (rotorvib.pipeline.strict_yaml: YAML 1.2,
    strict), replacing Snakemake's reading (YAML 1.1, a duplicate key's last value kept), from
    the same files in the same order: the Snakefile's `configfile:`, each --configfile, then
    the --config entries read from their text (`config_args`, Snakemake's settings field that
    holds the entries as typed, and that it hands to every job it spawns), not from its parsed
    values, in which a duplicate key is already gone."""
    settings = workflow.config_settings
    given = [Path(f).resolve() for f in settings.configfiles]
    return workflow_config(
        [f for f in workflow.configfiles if Path(f).resolve() not in given],
        settings.configfiles,
        command_line_overrides(settings.config_args or ()),
        replace_base=settings.replace_workflow_config,
    )


try:
    if module_config_given(workflow):
        # A module of another workflow given its own `config:`: that configuration, read again
        # from the caller's files where it came from them, over the shipped defaults
        # (config/config.yaml).
        _read = merge(
            load_yaml(WORKFLOW_ROOT / "config/config.yaml"),
            module_config(config, caller_config(workflow), _strict_reading),
        )
    else:
        _read = _strict_reading()
    config.clear()
    config.update(check_config(_read, load_yaml(WORKFLOW_ROOT / "config/schema.yaml")))
except ConfigError as error:
    raise WorkflowError(str(error)) from None

# The papers, from the configuration's paper_<p> sections (each has its rules in
# workflow/rules/paper_<p>.smk and its package rotorvib.papers.<p>).
PAPERS = sorted(
    key.removeprefix("paper_") for key in config if key.startswith("paper_")
)
# the comparison's reading of the papers' words ("close" and its alternatives), shared by
# every paper's claims (rotorvib.comparison.Close)
CLOSE = config["comparison"]
# Threads of a job that shares a batch of runs out over threads (paper B's batch studies,
# rotorvib.models.balancer.simulate) or its searches over processes (paper C's broadband
# fronts, rotorvib.methods.forked): half the cores Snakemake is given, so that -j2 runs two
# single-threaded jobs side by side as it always did and a larger -j hands each batch job
# several cores (the SLURM profile sets its own with set-threads, written for each rule that
# declares these by rotorvib.pipeline.slurm_profile). A command given no cores (--rulegraph,
# --lint) plans with one.
try:
    BATCH_THREADS = max(1, int(workflow.cores) // 2)
except (WorkflowError, TypeError):
    BATCH_THREADS = 1
# The rules that declare them (found in the rule files, as the SLURM profile's are).
BATCH_RULES = frozenset(
    rule_name(workflow, name)
    for name in batch_rules(WORKFLOW_ROOT / "workflow" / "rules")
)
# Where every output goes: results/ for the paper configuration, its own folder for another
# (config key `results`; the reduced configuration writes to results/reduced).
RESULTS_DIR = config["results"]


def reproduced_file(paper):
    """The reproduced values of a paper's stated quantities."""
    return f"{RESULTS_DIR}/paper_{paper}/reproduced.csv"


# Scheduling: every job runs one thread (a batch study's second thread gains less than a second
# job beside it on a few cores; profiles/slurm gives paper B's batch studies more), and
# long jobs start first so that short ones fill the gaps at the end (`priority`): paper B's
# genetic algorithm, the longest job (on an empty cache it compiles the engine, and an engine
# job started meanwhile waits for it, rotorvib.methods.numba_cache), beside its symbolic checks,
# the longest job that needs no compiled engine; paper B's run-up studies, which head the
# longest chain of jobs (their reproduced values, the discrepancy analysis, the comparison, the
# report), that chain and every job it waits for (tests/test_layout.py derives them from the
# rule graph); then every other job that computes; then the figures and tables (no priority).
BESIDE_THE_COMPILE, LONGEST_CHAIN, COMPUTES = 3, 2, 1

# Where a job runs under a cluster executor (profiles/slurm): where Snakemake runs
# (`localrule: True`) unless it is a shard of one of paper B's batch studies, or its Pareto
# study when those are sharded. A cluster job costs two Snakemake start-ups and a status check
# (python -m benchmarks.cluster), more than most jobs take at the paper's sizes (python -m
# benchmarks.pipeline): splitting a study over jobs (paper_b.shards > 1) is what makes it worth
# a cluster, and the shards are what is sent.
PAPER_VALUES = source("data/paper_values.csv")
REPORT_DIR = f"{RESULTS_DIR}/report"
REPORT_LANDING = f"{REPORT_DIR}/landing.rst"


def dataset(paper, name):
    """Path of dataset ``name`` of ``paper`` ("a", "b" or "c")."""
    return f"{RESULTS_DIR}/paper_{paper}/datasets/{name}.nc"


def shard_file(paper, name):
    """Path of one shard of a batch study's dataset ``name`` (wildcards ``shard`` and
    ``shards``: shard k of n), gathered by the study's rule (rotorvib.pipeline.shards).
    """
    return f"{RESULTS_DIR}/paper_{paper}/shards/{name}.{{shard}}-of-{{shards}}.nc"


def shards_of(paper, name, shards):
    """Input function of a study's rule: the files of its ``shards`` shards, or none when it
    runs as one job (``shards`` = 1)."""

    def files(wildcards):
        if shards == 1:
            return []
        template = shard_file(paper, name)
        return [
            template.format(**dict(wildcards.items()), shard=k, shards=shards)
            for k in range(shards)
        ]

    return files


def batch_study(
    name,
    message,
    params,
    inputs=None,
    wildcards=None,
    runtime=30,
    priority=LONGEST_CHAIN,
    shards=1,
):
    """A batch study of paper B (its rules: paper_b.smk): its dataset ``name`` (with its
    wildcards' patterns), its job's parameters and inputs, its wall-time bound in minutes
    (``runtime``) and the least number of shards it is split into (``paper_b.shards``, if
    larger, wins); its log and benchmark are ``b_<name>``."""
    return {
        "shards": shards,
        "dataset": name,
        "name": f"b_{name}",
        "message": message,
        "params": params,
        "inputs": inputs or {},
        "wildcards": wildcards or {},
        "runtime": runtime,
        "priority": priority,
    }


def table(paper, name, ext):
    return f"{RESULTS_DIR}/paper_{paper}/tables/{name}.{ext}"


def figure_file(paper, name, ext="png"):
    """A figure's PNG, its vector copy (svg), or what it draws and depends on (json, for its
    caption; rotorvib.io.plotting)."""
    return f"{RESULTS_DIR}/paper_{paper}/figures/{name}.{ext}"


def logs(name):
    return f"{RESULTS_DIR}/logs/{name}.log"


def benchmarks(name):
    return f"{RESULTS_DIR}/benchmarks/{name}.tsv"


def paper_outputs(paper):
    """The module that declares ``paper``'s outputs (rotorvib.papers.<paper>.outputs)."""
    return import_module(f"rotorvib.papers.{paper}.outputs")


# Figures of each paper, as its package declares them (rotorvib.outputs.figure), drawn by the
# figure jobs (figures.smk): FIGURES[paper][name] names the drawing function of
# rotorvib.papers.<paper>.figures, the datasets it reads (argument -> dataset name), what it
# shows (the first sentence of its report caption, rotorvib.pipeline.report), the comparison
# items it shows beyond those its name numbers ("Fig 8" for fig8) and its options.
FIGURES = {
    paper: paper_outputs(paper).figures(config[f"paper_{paper}"]) for paper in PAPERS
}


def outputs_named(paper, name):
    """The paper outputs whose cases figure ``name`` depends on: itself and those its
    declaration names ("the three (beta, m) cases of Table 2"); its parameters statement
    leaves out the cases of the others (rotorvib.io.plotting.parameters_text)."""
    declared = FIGURES[paper][name]
    return sorted({name} | names_in(" ".join([declared["shows"], *declared["items"]])))


# Tables shown in the report: TABLES[paper][name] says what the table shows, the comparison
# items beyond those its name numbers ("Table 2" for table2) and where its CSV is; each paper's
# as its package declares them (in its tables folder), the whole project's ("all") by
# report_table.
TABLES = {
    paper: {
        name: {**declared, "csv": table(paper, name, "csv")}
        for name, declared in paper_outputs(paper)
        .tables(config[f"paper_{paper}"])
        .items()
    }
    for paper in PAPERS
}


def report_table(paper, name, shows, items=(), path=None):
    """Declare table ``name`` of the whole project (``paper`` "all"), written as CSV to
    ``path``, and return that path. Rule report_text writes it as an HTML page, rule
    report_results shows that page in the report."""
    TABLES.setdefault(paper, {})[name] = {
        "shows": shows,
        "items": list(items),
        "csv": path,
    }
    return path


def caption_file(paper, name, kind):
    """The generated caption file of a figure or table (rule report_text)."""
    return f"{REPORT_DIR}/captions/{kind}s/{paper}_{name}.rst"


def table_page(paper, name):
    """The HTML page of a declared table (rule report_text)."""
    return f"{REPORT_DIR}/pages/{paper}_{name}.html"


SUMMARY_PAGE = f"{REPORT_DIR}/pages/summary.html"


def shown(paper, file_name):
    """Where rule report_results puts a file the report shows, for ``paper`` ("all" for the
    whole project); the report names a result by its file name."""
    folder = "" if paper == "all" else f"paper_{paper}/"
    return f"{REPORT_DIR}/shown/{folder}{file_name}"


def report_entries():
    """Every result the report shows, ``{shown path: (source file, report() arguments)}``: the
    summary, each paper's figures and tables, and the comparison tables. Each has one label,
    ``item``: Snakemake's report turns a second label into a toggle, which breaks a view
    where it takes two values (one of two results, say). A view sorts its results by it.
    """
    named = categories(PAPERS)
    entries = {
        shown("all", "summary.html"): (
            SUMMARY_PAGE,
            {"category": named["Summary"], "labels": {"item": "Verdicts and findings"}},
        )
    }
    for kind, declared in (("figure", FIGURES), ("table", TABLES)):
        for paper, outputs in declared.items():
            for name, d in outputs.items():
                if kind == "figure":
                    source = figure_file(paper, name)
                else:
                    source = table_page(paper, name)
                entries[shown(paper, f"{name}{Path(source).suffix}")] = (
                    source,
                    {
                        "caption": in_working_folder(caption_file(paper, name, kind)),
                        "category": named[
                            "Comparison" if paper == "all" else f"Paper {paper.upper()}"
                        ],
                        "subcategory": (
                            None if paper == "all" else subcategory(d["shows"], kind)
                        ),
                        "labels": {"item": entry_label(name, kind, tuple(d["items"]))},
                    },
                )
    return entries


@cache
def rule_making(path):
    """Which of ``workflow.rules`` makes ``path`` (the first that does, as
    snakemake_rules.producer finds it; None for a file of the workflow's own), looked for once
    a path. Rules are only ever added after the others, so the first that makes a path stays
    the first. Every job's input check and every figure's group ask for it; looked for each
    time, a dry run of the reduced configuration forked from a prepared Snakemake
    (tests/forked_snakemake.py) took 0.57 s instead of 0.49 s."""
    return producer(workflow.rules, path)


def figure_rule(paper, name):
    """The name of the job that draws figure ``name`` of ``paper`` (its group's, named for the
    group's first figure, figures.smk)."""
    return next(
        f"figures_{paper}_{names[0]}"
        for (group_paper, _), names in figure_groups().items()
        if group_paper == paper and name in names
    )


def made_by(paper, name, kind):
    """How the report says a figure or table was made: the rule that drew or wrote it, its
    script, the drawing function, and the rules of the datasets it reads."""
    if kind == "table":
        writer = rule_making(TABLES[paper][name]["csv"])
        return {"rule": writer.name, "script": script_name(writer)}
    declared = FIGURES[paper][name]
    return {
        "rule": figure_rule(paper, name),
        "script": "workflow/scripts/figures.py",
        "function": f"rotorvib.papers.{paper}.figures.{declared['function']}",
        "datasets": {
            d: rule_making(dataset(paper, d)).name
            for d in dict.fromkeys(declared["datasets"].values())
        },
    }


def script_name(rule):
    """A rule's script, relative to the workflow's folder."""
    return str(Path(script_path(rule)).resolve().relative_to(WORKFLOW_ROOT))


def figure_groups():
    """The figures of each paper grouped by the batch studies their datasets wait for, in
    declaration order: ``{(paper, those rules' names): [figure names]}``. One job draws a group
    (figures.smk); read once the rules of the papers exist. The figures that wait for no batch
    study (datasets of seconds) are one job per paper: their start-ups, half a second each,
    would cost more than their drawing. A figure of a batch study waits for that study only,
    as its dataset does."""
    groups = {}
    for paper, figures in FIGURES.items():
        for name, declared in figures.items():
            studies = set().union(
                *(
                    batch_upstream(dataset(paper, d))
                    for d in declared["datasets"].values()
                )
            )
            groups.setdefault((paper, tuple(sorted(studies))), []).append(name)
    return groups


@cache
def batch_upstream(path):
    """The batch rules (``threads: BATCH_THREADS``) that ``path`` waits for: its own rule if
    that is one, else those its rule's inputs wait for. Only a batch rule's inputs are
    functions of its wildcards (its shards), and the walk stops there."""
    maker = rule_making(path)
    if maker is None:  # a file of the workflow's own
        return frozenset()
    if maker.name in BATCH_RULES:
        return frozenset({maker.name})
    if any(callable(item) for item in maker.input):
        raise WorkflowError(
            f"{maker.name} takes an input function, which figure_groups "
            "cannot follow to the batch rules it waits for"
        )
    return frozenset().union(*(batch_upstream(str(item)) for item in maker.input))


def figure_datasets(paper, names):
    """The datasets the figures ``names`` of ``paper`` read, sorted."""
    return sorted({d for n in names for d in FIGURES[paper][n]["datasets"].values()})


def all_results():
    """Every final file: each paper's results, the comparison, the report's words and pages
    and the files it shows."""
    files = [f for paper in sorted(RESULTS) for f in RESULTS[paper]]
    return (
        files
        + [
            f"{RESULTS_DIR}/{name}.{ext}"
            for name in ("comparison", "discrepancies")
            for ext in ("csv", "md")
        ]
        + report_text_files()
        + list(report_entries())
    )


def figure_companions():
    """Each figure's vector copy (svg) and what it draws and depends on (json): made with its
    PNG by the figure job, and archived with it."""
    return [
        figure_file(paper, name, ext)
        for paper in FIGURES
        for name in FIGURES[paper]
        for ext in ("svg", "json")
    ]


def report_text_files():
    """The report's landing page, its summary page, the captions of every figure and table
    and the HTML page of every table."""
    return (
        [REPORT_LANDING, SUMMARY_PAGE]
        + captions(FIGURES, "figure")
        + captions(TABLES, "table")
        + table_pages()
    )


def table_pages():
    return [table_page(paper, name) for paper in TABLES for name in TABLES[paper]]


def captions(declared, kind):
    """The caption files of the ``declared`` figures or tables of every paper."""
    return [
        caption_file(paper, name, kind)
        for paper in declared
        for name in declared[paper]
    ]


def drawn_datasets(paper):
    """The datasets the figures of ``paper`` draw from (its FIGURES declarations)."""
    return {
        name for each in FIGURES[paper].values() for name in each["datasets"].values()
    }


def results_of(paper):
    """Every final file of a paper: its figures, the datasets they draw from and those its
    package declares no figure draws, its tables (csv and md) and notes (md) and the
    reproduced values of its claims."""
    declared = paper_outputs(paper)
    return (
        [figure_file(paper, name) for name in FIGURES[paper]]
        + [
            dataset(paper, name)
            for name in sorted(drawn_datasets(paper) | set(declared.UNDRAWN_DATASETS))
        ]
        + [table(paper, name, ext) for name in TABLES[paper] for ext in ("csv", "md")]
        + [table(paper, name, "md") for name in declared.NOTES]
        + [reproduced_file(paper)]
    )


# Final files of each paper.
RESULTS = {paper: results_of(paper) for paper in PAPERS}


def add_code_fingerprints(rules):
    """Give every script rule a ``code`` parameter (the fingerprint of the library code its
    script can run, rotorvib.pipeline.fingerprint), so that a behaviour-changing edit of that
    code reruns exactly its jobs. A module the script loads by name is its ``module`` parameter.
    """
    for each in rules:
        if (script := script_path(each)) is None:
            continue
        named = dict(each.params.items()).get("module")
        if callable(named):
            add_params(
                each, code=lambda wc, s=script, m=named: code_fingerprint(s, m(wc))
            )
        else:
            add_params(each, code=code_fingerprint(script, *([named] if named else [])))


def producer_of(path):
    """The rule that makes ``path`` in this run and the SHA-256 of the configuration it records
    in it (its parameters for that file's wildcards, rotorvib.pipeline.job.job_config).
    """
    maker = rule_making(path)
    given = SimpleNamespace(**wildcards(maker, path))
    return {
        "rule": maker.name,
        "config_sha256": config_hash(
            {
                name: value(given) if callable(value) else value
                for name, value in job_config(maker.params).items()
            }
        ),
    }


def input_producers(wildcards, input):
    """Each input dataset's producer and its configuration hash, checked on read: a dataset
    made by another rule or under another configuration (copied, restored, ``--touch``ed)
    stops the job."""
    return {path: producer_of(path) for path in input if str(path).endswith(".nc")}


def add_input_checks(rules):
    """Give every script rule the parameter rotorvib.pipeline.job.INPUT_PRODUCERS_PARAM."""
    for each in rules:
        if script_path(each) is not None:
            add_params(each, **{INPUT_PRODUCERS_PARAM: input_producers})


def configuration_files():
    """The configuration files the run read that lie in the working directory, as relative
    paths (the whole merged configuration is a file of the archive in any case, archive.smk).
    """
    here = Path.cwd()
    paths = {Path(f).resolve() for f in workflow.configfiles}
    return sorted(str(p.relative_to(here)) for p in paths if p.is_relative_to(here))
