"""The workflow's plan, without Snakemake: where every file of a run goes, what each paper
makes, what the report shows, which figures one job draws, and the rules a rule's author keeps.

``workflow/rules/common.smk`` builds one :class:`Plan` from the checked configuration and the
papers' declarations (``rotorvib.papers.<p>.outputs``), and hands it the rule graph as one
function, ``maker(path) -> Maker | None``: the rule that makes a file, as
:func:`rotorvib.pipeline.snakemake_rules.declared` reads it from Snakemake's rule objects (None for
a file of the workflow's own). A test hands it a fake graph.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from importlib import import_module
from pathlib import Path

from rotorvib.pipeline.report import categories, entry_label, names_in, subcategory

#: Priorities (Snakemake's ``priority:``): long jobs start first, so that short ones fill the
#: gaps at the end. Paper B's genetic algorithm, the longest job (on an empty cache it compiles
#: the engine), beside its symbolic checks; the longest chain of jobs (paper B's run-up studies,
#: their reproduced values, the discrepancy analysis, the comparison, the report) and every job
#: it waits for; then every other job that computes; the figures and tables have none.
BESIDE_THE_COMPILE, LONGEST_CHAIN, COMPUTES = 3, 2, 1


@dataclass(frozen=True)
class Maker:
    """A rule as the plan reads it: its name, its inputs (paths; None for an input function),
    its outputs, whether it is a batch rule (``resources: batch=1``), whether it runs where
    Snakemake runs (``localrule: True``), its priority, whether it has a ``benchmark:``, and
    its script (in the workflow's folder; None for a rule without one)."""

    name: str
    inputs: tuple[str | None, ...] = ()
    outputs: tuple[str, ...] = ()
    batch: bool = False
    local: bool = True
    priority: int = 0
    benchmark: bool = False
    script: str | None = None


def rule_problems(rules: list[Maker]) -> list[str]:
    """The rules for whoever writes a rule (docs/developer.md), each broken one as a sentence:

    1. a rule that writes a dataset (``.nc``) computes: it has a ``benchmark:`` and a priority
       (``COMPUTES`` or more), and every rule with a ``benchmark:`` has one;
    2. a rule without a ``benchmark:`` (it draws, tabulates or reads) declares no priority but
       the longest chain's, ``LONGEST_CHAIN``;
    3. only a batch rule takes an input function (its shards): the figure grouping follows the
       other rules' inputs to the batch rules they wait for;
    4. only a batch rule runs as a cluster job; every other rule is a ``localrule``. A cluster
       job costs two Snakemake start-ups and a status check (``python -m benchmarks.cluster``),
       more than most jobs take at the paper's sizes (``python -m benchmarks.pipeline``):
       splitting a study over jobs (``paper_b.shards`` > 1) is what makes a cluster worth it,
       and the shards (and paper B's Pareto study, when they are sharded) are what is sent.
    """
    problems = []
    for rule in rules:
        if any(out.endswith(".nc") for out in rule.outputs) and not rule.benchmark:
            problems.append(f"rule {rule.name} writes a dataset but no benchmark:")
        if rule.benchmark and rule.priority < COMPUTES:
            problems.append(f"rule {rule.name} has a benchmark: but no priority: COMPUTES or more")
        if not rule.benchmark and rule.priority not in (0, LONGEST_CHAIN):
            problems.append(f"rule {rule.name} computes nothing measured (no benchmark:) "
                            "but has a priority other than LONGEST_CHAIN")
        if None in rule.inputs and not rule.batch:
            problems.append(f"rule {rule.name} takes an input function but is no batch rule "
                            "(resources: batch=1)")
        if not rule.local and not rule.batch:
            problems.append(f"rule {rule.name} is a cluster job but no batch rule: "
                            "give it localrule: True")
    return problems


class Plan:
    """The files of a run under ``results`` (the configuration's ``results`` key) for the papers
    of ``sections`` (``{paper: its configuration section}``, from which its package declares its
    outputs), the report's texts named under the run's ``working_folder``."""

    def __init__(self, sections: dict[str, dict], results: str, working_folder: Path):
        self.papers = sorted(sections)
        self.results = results
        self.working_folder = Path(working_folder)
        self.report_dir = f"{results}/report"
        self.landing = f"{self.report_dir}/landing.rst"
        self.summary_page = f"{self.report_dir}/pages/summary.html"
        declared = {p: import_module(f"rotorvib.papers.{p}.outputs") for p in self.papers}
        self.declared = declared
        self.figures = {p: declared[p].figures(sections[p]) for p in self.papers}
        self.tables = {
            p: {name: {**d, "csv": self.table(p, name, "csv")}
                for name, d in declared[p].tables(sections[p]).items()}
            for p in self.papers
        }

    # -- paths -----------------------------------------------------------------------------

    def dataset(self, paper: str, name: str) -> str:
        """Dataset ``name`` of ``paper``."""
        return f"{self.results}/paper_{paper}/datasets/{name}.nc"

    def shard_file(self, paper: str, name: str) -> str:
        """One shard of a batch study's dataset (wildcards ``shard`` of ``shards``), gathered by
        the study's rule (rotorvib.pipeline.shards)."""
        return f"{self.results}/paper_{paper}/shards/{name}.{{shard}}-of-{{shards}}.nc"

    def shards_of(self, paper: str, name: str, shards: int) -> Callable:
        """Input function of a study's rule: the files of its ``shards`` shards (one job's
        wildcards), or none when it runs as one job (``shards`` = 1)."""

        def files(wildcards) -> list[str]:
            template = self.shard_file(paper, name)
            return [template.format(**dict(wildcards.items()), shard=k, shards=shards)
                    for k in range(shards)] if shards > 1 else []

        return files

    def table(self, paper: str, name: str, ext: str) -> str:
        return f"{self.results}/paper_{paper}/tables/{name}.{ext}"

    def figure_file(self, paper: str, name: str, ext: str = "png") -> str:
        """A figure's PNG, its vector copy (svg), or what it draws and depends on (json)."""
        return f"{self.results}/paper_{paper}/figures/{name}.{ext}"

    def reproduced_file(self, paper: str) -> str:
        """The reproduced values of a paper's stated quantities."""
        return f"{self.results}/paper_{paper}/reproduced.csv"

    def logs(self, name: str) -> str:
        return f"{self.results}/logs/{name}.log"

    def benchmarks(self, name: str) -> str:
        return f"{self.results}/benchmarks/{name}.tsv"

    def caption_file(self, paper: str, name: str, kind: str) -> str:
        """The generated caption of a figure or table (rule report_text)."""
        return f"{self.report_dir}/captions/{kind}s/{paper}_{name}.rst"

    def table_page(self, paper: str, name: str) -> str:
        """The HTML page of a declared table (rule report_text)."""
        return f"{self.report_dir}/pages/{paper}_{name}.html"

    def shown(self, paper: str, file_name: str) -> str:
        """Where rule report_results puts a file the report shows (``paper`` "all" for the
        whole project's)."""
        folder = "" if paper == "all" else f"paper_{paper}/"
        return f"{self.report_dir}/shown/{folder}{file_name}"

    def in_working_folder(self, path: str) -> str:
        """A file of this run as an absolute path under the run's working folder: Snakemake
        reads the report's texts relative to the rule file's folder, the workflow's own."""
        return str(self.working_folder / path)

    # -- the papers' outputs ---------------------------------------------------------------

    def report_table(self, paper: str, name: str, shows: str, items=(), path=None) -> str:
        """Declare table ``name`` of the whole project (``paper`` "all"), written as CSV to
        ``path``, and return that path."""
        self.tables.setdefault(paper, {})[name] = {"shows": shows, "items": list(items),
                                                   "csv": path}
        return path

    def outputs_named(self, paper: str, name: str) -> list[str]:
        """The outputs whose cases figure ``name`` depends on: itself and those its
        declaration names ("the three (beta, m) cases of Table 2")."""
        d = self.figures[paper][name]
        return sorted({name} | names_in(" ".join([d["shows"], *d["items"]])))

    def figure_datasets(self, paper: str, names) -> list[str]:
        """The datasets the figures ``names`` of ``paper`` read, sorted."""
        return sorted({d for n in names for d in self.figures[paper][n]["datasets"].values()})

    def results_of(self, paper: str) -> list[str]:
        """Every final file of a paper: its figures, the datasets they draw from and those its
        package declares no figure draws, its tables (csv and md) and notes (md) and the
        reproduced values of its claims."""
        declared = self.declared[paper]
        drawn = set(self.figure_datasets(paper, self.figures[paper]))
        return ([self.figure_file(paper, name) for name in self.figures[paper]]
                + [self.dataset(paper, name)
                   for name in sorted(drawn | set(declared.UNDRAWN_DATASETS))]
                + [self.table(paper, name, ext)
                   for name in self.tables[paper] for ext in ("csv", "md")]
                + [self.table(paper, name, "md") for name in declared.NOTES]
                + [self.reproduced_file(paper)])

    def captions(self, kind: str) -> list[str]:
        """The caption files of every paper's figures or tables (``kind``)."""
        declared = self.figures if kind == "figure" else self.tables
        return [self.caption_file(p, name, kind) for p in declared for name in declared[p]]

    def table_pages(self) -> list[str]:
        return [self.table_page(p, name) for p in self.tables for name in self.tables[p]]

    def report_text_files(self) -> list[str]:
        """The report's landing page, summary page, captions and table pages."""
        return ([self.landing, self.summary_page] + self.captions("figure")
                + self.captions("table") + self.table_pages())

    def report_entries(self) -> dict[str, tuple[str, dict]]:
        """Every result the report shows, ``{shown path: (source file, report() arguments)}``:
        the summary, each paper's figures and tables, and the project's tables. Each has one
        label, ``item`` (a second label becomes a toggle in Snakemake's report, which breaks a
        view where it takes two values); a view sorts its results by it."""
        named = categories(self.papers)
        entries = {self.shown("all", "summary.html"): (
            self.summary_page,
            {"category": named["Summary"], "labels": {"item": "Verdicts and findings"}})}
        for kind, declared in (("figure", self.figures), ("table", self.tables)):
            for paper, outputs in declared.items():
                for name, d in outputs.items():
                    source = (self.figure_file(paper, name) if kind == "figure"
                              else self.table_page(paper, name))
                    entries[self.shown(paper, f"{name}{Path(source).suffix}")] = (source, {
                        "caption": self.in_working_folder(self.caption_file(paper, name, kind)),
                        "category": named["Comparison" if paper == "all"
                                          else f"Paper {paper.upper()}"],
                        "subcategory": None if paper == "all" else subcategory(d["shows"], kind),
                        "labels": {"item": entry_label(name, kind, tuple(d["items"]))},
                    })
        return entries

    def all_results(self) -> list[str]:
        """Every final file: each paper's, the comparison, the report's words, pages and the
        files it shows."""
        return ([f for p in self.papers for f in self.results_of(p)]
                + [f"{self.results}/{name}.{ext}" for name in ("comparison", "discrepancies")
                   for ext in ("csv", "md")]
                + self.report_text_files() + list(self.report_entries()))

    def figure_companions(self) -> list[str]:
        """Each figure's vector copy (svg) and what it draws (json), archived with its PNG."""
        return [self.figure_file(p, name, ext) for p in self.figures
                for name in self.figures[p] for ext in ("svg", "json")]

    # -- the figure jobs -------------------------------------------------------------------

    def figure_groups(self, maker: Callable[[str], Maker | None]) -> dict[tuple, list[str]]:
        """The figures of each paper grouped by the batch rules their datasets wait for, in
        declaration order: ``{(paper, those rules' names): [figure names]}``; one job draws a
        group. The figures that wait for no batch rule (datasets of seconds) are one job per
        paper: their start-ups, half a second each, would cost more than their drawing."""
        groups = {}
        for paper, figures in self.figures.items():
            for name, d in figures.items():
                studies = set().union(*(batch_upstream(maker, self.dataset(paper, each))
                                        for each in d["datasets"].values()))
                groups.setdefault((paper, tuple(sorted(studies))), []).append(name)
        return groups

    def figure_rule(self, groups: dict, paper: str, name: str) -> str:
        """The name of the job that draws figure ``name`` of ``paper``: its group's, named for
        the group's first figure."""
        return next(f"figures_{paper}_{names[0]}" for (p, _), names in groups.items()
                    if p == paper and name in names)

    def made_by(self, maker: Callable[[str], Maker | None], groups: dict, paper: str,
                name: str, kind: str) -> dict:
        """How the report says a figure or table was made: the rule that drew or wrote it, its
        script, the drawing function and the rules of the datasets it reads."""
        if kind == "table":
            writer = maker(self.tables[paper][name]["csv"])
            return {"rule": writer.name, "script": writer.script}
        d = self.figures[paper][name]
        return {"rule": self.figure_rule(groups, paper, name),
                "script": "workflow/scripts/figures.py",
                "function": f"rotorvib.papers.{paper}.figures.{d['function']}",
                "datasets": {each: maker(self.dataset(paper, each)).name
                             for each in dict.fromkeys(d["datasets"].values())}}


@cache
def batch_upstream(maker: Callable[[str], Maker | None], path: str) -> frozenset[str]:
    """The batch rules ``path`` waits for: its own rule if that is one, else those its rule's
    inputs wait for (the walk stops at a batch rule, whose inputs are its shards). Asked once
    a path and graph: the figures of a paper share most of their rules."""
    rule = maker(path)
    if rule is None:  # a file of the workflow's own
        return frozenset()
    if rule.batch:
        return frozenset({rule.name})
    if None in rule.inputs:
        raise ValueError(f"{rule.name} takes an input function but is no batch rule: the "
                         "figure grouping cannot follow it to the batch rules it waits for")
    return frozenset().union(*(batch_upstream(maker, each) for each in rule.inputs))
