# Helpers shared by all rules: configuration validation (before any job), paths, the figure
# declaration, the code fingerprint every script rule receives and the configuration hash each
# of its input datasets must carry.
from pathlib import Path
from types import SimpleNamespace

from snakemake.exceptions import WorkflowError
from snakemake.utils import update_config

from rotorvib.io.config import (
    INPUTS_CONFIG_PARAM,
    ConfigError,
    config_hash,
    job_config,
    load_yaml,
    typed_overrides,
    validate_config,
)
from rotorvib.io.fingerprint import code_fingerprint
from rotorvib.report import label, numbers_of_name, order_key

try:
    # Snakemake's own loader keeps a duplicate key's last value: read each file strictly too.
    for _path in workflow.configfiles:
        load_yaml(_path)
    # and it leaves the values inside a nested `--config` override as text: type them.
    update_config(config, typed_overrides(workflow.config_settings.overwrite_config))
    config.update(validate_config(config, load_yaml("config/schema.yaml")))
except ConfigError as error:
    raise WorkflowError(str(error)) from None

A, B, C = (config[f"paper_{paper}"] for paper in "abc")
# Scheduling: every job runs one thread (a batch study's second thread gains less than a second
# job beside it on a few cores; workflow/profiles/slurm gives paper B's batch studies more), and
# long jobs start first so that short ones fill the gaps at the end (`priority`): paper B's
# symbolic checks, the longest job that needs no compiled engine, beside the first engine job
# (on an empty cache it compiles the engine while the next engine job waits for it,
# rotorvib.methods.numba_cache); paper B's run-up studies, which head the longest chain of jobs
# (their reproduced values, the discrepancy analysis, the comparison, the report), and that
# chain; then every other job that computes; then the figures and tables (local rules, 0).
BESIDE_THE_COMPILE, LONGEST_CHAIN, COMPUTES = 3, 2, 1
PAPER_VALUES = "data/paper_values.csv"
REPORT_DIR = "results/report"
REPORT_LANDING = f"{REPORT_DIR}/landing.rst"


def dataset(paper, name):
    """Path of dataset ``name`` of ``paper`` ("a", "b" or "c")."""
    return f"results/paper_{paper}/datasets/{name}.nc"


def table(paper, name, ext):
    return f"results/paper_{paper}/tables/{name}.{ext}"


def figure_file(paper, name):
    return f"results/paper_{paper}/figures/{name}.png"


def logs(name):
    return f"results/logs/{name}.log"


def benchmarks(name):
    return f"results/benchmarks/{name}.tsv"


# Figures of each paper, filled by the paper's .smk and drawn by the figure jobs (figures.smk);
# FIGURES[paper][name] names the drawing function of rotorvib.papers.<paper>.figures, the
# datasets it reads (argument -> dataset name), what it shows (the first sentence of its
# report caption, rotorvib.report), the comparison items it shows beyond those its name
# numbers ("Fig 8" for fig8) and its options.
FIGURES = {}


def figure(function, datasets, shows, items=(), **options):
    """A figure declaration: ``function(**datasets, paper=<paper's values>, **options)``."""
    return {
        "function": function,
        "datasets": datasets,
        "shows": shows,
        "items": list(items),
        "options": options,
    }


# Tables shown in the report, filled by the papers' .smk: TABLES[paper][name] says what the
# table shows and the comparison items beyond those its name numbers ("Table 2" for table2).
TABLES = {}


def report_table(paper, name, shows, items=()):
    """Declare table ``name`` of ``paper`` ("all" for the whole project) and return the
    ``report()`` flag's arguments: its generated caption, category and labels."""
    TABLES.setdefault(paper, {})[name] = {"shows": shows, "items": list(items)}
    return {
        "caption": f"../../{caption_file(paper, name, 'table')}",
        "category": "Comparison" if paper == "all" else f"Paper {paper.upper()}",
        "subcategory": None if paper == "all" else "Tables",
        "labels": report_labels(TABLES[paper], name, "table"),
    }


def report_labels(declared, name, kind):
    """The report's labels of an output among the ``declared`` ones of its paper: its place
    in the paper's order and its name ("Fig 8")."""
    before = list(declared)[: list(declared).index(name)]
    others = sum(1 for each in before if not numbers_of_name(each))
    return {"#": order_key(name, others), kind: label(name, kind)}


def caption_file(paper, name, kind):
    """The generated caption file of a figure or table (rule report_text)."""
    return f"{REPORT_DIR}/captions/{kind}s/{paper}_{name}.rst"


def figure_groups():
    """The figures of each paper grouped by the datasets they read, in declaration order:
    ``{(paper, dataset names): [figure names]}``. One job draws a group (figures.smk).
    """
    groups = {}
    for paper, figures in FIGURES.items():
        for name, declared in figures.items():
            key = (paper, tuple(sorted(set(declared["datasets"].values()))))
            groups.setdefault(key, []).append(name)
    return groups


# Final files of each paper, filled by the paper's .smk.
RESULTS = {}


def all_results():
    """Every final file: each paper's results, the comparison and the report's text."""
    files = [f for paper in sorted(RESULTS) for f in RESULTS[paper]]
    return (
        files
        + [
            f"results/{name}.{ext}"
            for name in ("comparison", "discrepancies")
            for ext in ("csv", "md")
        ]
        + report_text_files()
    )


def report_text_files():
    """The report's landing page and the captions of every figure and table."""
    return [REPORT_LANDING] + captions(FIGURES, "figure") + captions(TABLES, "table")


def captions(declared, kind):
    """The caption files of the ``declared`` figures or tables of every paper."""
    return [
        caption_file(paper, name, kind)
        for paper in declared
        for name in declared[paper]
    ]


def results_of(paper, datasets, tables=()):
    """Every final file of a paper: its figures, datasets, tables (csv and md) and the
    reproduced values of its claims."""
    return (
        [figure_file(paper, name) for name in FIGURES[paper]]
        + [dataset(paper, name) for name in datasets]
        + [table(paper, name, ext) for name in tables for ext in ("csv", "md")]
        + [f"results/paper_{paper}/reproduced.csv"]
    )


def add_code_fingerprints(rules):
    """Give every script rule a ``code`` parameter (the fingerprint of the library code its
    script can run, rotorvib.io.fingerprint), so that a behaviour-changing edit of that code
    reruns exactly its jobs. A module the script loads by name is its ``module`` parameter.
    """
    for each in rules:
        if not each.script:
            continue
        script = each.basedir.join(each.script).get_path_or_uri(secret_free=True)
        named = dict(each.params.items()).get("module")
        if callable(named):
            each.set_params(
                code=lambda wc, s=script, m=named: code_fingerprint(s, m(wc))
            )
        else:
            each.set_params(code=code_fingerprint(script, *([named] if named else [])))


def producer_config_hash(path):
    """SHA-256 of the configuration the rule that makes ``path`` records in it (its parameters
    for that file's wildcards, rotorvib.io.datasets.job_config)."""
    producer = next(each for each in workflow.rules if each.is_producer(path))
    wildcards = SimpleNamespace(**producer.get_wildcards(path))
    return config_hash(
        {
            name: value(wildcards) if callable(value) else value
            for name, value in job_config(producer.params).items()
        }
    )


def inputs_config_hashes(wildcards, input):
    """Each input dataset's expected producer-configuration hash, checked on read: a dataset
    made under another configuration (copied, restored, ``--touch``ed) stops the job."""
    return {
        path: producer_config_hash(path) for path in input if str(path).endswith(".nc")
    }


def add_input_checks(rules):
    """Give every script rule the parameter rotorvib.io.config.INPUTS_CONFIG_PARAM."""
    for each in rules:
        if each.script:
            each.set_params(**{INPUTS_CONFIG_PARAM: inputs_config_hashes})


def configuration_files():
    """The configuration files the run read that lie in the working directory, as relative
    paths (the whole merged configuration is a file of the archive in any case, archive.smk).
    """
    here = Path.cwd()
    paths = {Path(f).resolve() for f in workflow.configfiles}
    return sorted(str(p.relative_to(here)) for p in paths if p.is_relative_to(here))
