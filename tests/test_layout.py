"""The package layout holds: models and methods know no paper, no paper imports another, the
library never imports Snakemake, and modules stay small."""

import ast
import re
from pathlib import Path

import pytest

from rotorvib.pipeline.fingerprint import imported_names

SRC = Path(__file__).resolve().parents[1] / "src"
MODULES = {".".join(p.relative_to(SRC).with_suffix("").parts).removesuffix(".__init__"): p
           for p in sorted((SRC / "rotorvib").rglob("*.py"))}

#: layer -> layers it must not import
FORBIDDEN = {
    "rotorvib.io": ("rotorvib.models", "rotorvib.methods", "rotorvib.papers",
                    "rotorvib.comparison", "rotorvib.pipeline"),
    "rotorvib.methods": ("rotorvib.models", "rotorvib.papers", "rotorvib.comparison",
                         "rotorvib.pipeline"),
    "rotorvib.models": ("rotorvib.papers", "rotorvib.comparison", "rotorvib.pipeline"),
    "rotorvib.papers": ("rotorvib.pipeline",),
    # the contract the papers share (no paper either: see the test)
    "rotorvib.papers.outputs": ("rotorvib.comparison",),
    "rotorvib.papers.config_problems": ("rotorvib.comparison",),
    "rotorvib.comparison": ("rotorvib.pipeline", "rotorvib.papers"),
    "rotorvib.comparison.choices": ("rotorvib.comparison.verdicts",
                                    "rotorvib.comparison.reproduced",
                                    "rotorvib.comparison.table",
                                    "rotorvib.comparison.reproduced_csv",
                                    "rotorvib.comparison.discrepancy"),
    "rotorvib.comparison.paper_values": ("rotorvib.comparison.verdicts",
                                         "rotorvib.comparison.reproduced",
                                         "rotorvib.comparison.table",
                                         "rotorvib.comparison.reproduced_csv",
                                         "rotorvib.comparison.discrepancy"),
    "rotorvib.comparison.verdicts": ("rotorvib.comparison.reproduced",
                                     "rotorvib.comparison.table",
                                     "rotorvib.comparison.reproduced_csv",
                                     "rotorvib.comparison.discrepancy"),
    "rotorvib.comparison.reproduced": ("rotorvib.comparison.table",
                                       "rotorvib.comparison.reproduced_csv",
                                       "rotorvib.comparison.discrepancy"),
    "rotorvib.comparison.table": ("rotorvib.comparison.reproduced_csv",
                                  "rotorvib.comparison.discrepancy"),
    "rotorvib.comparison.reproduced_csv": ("rotorvib.comparison.discrepancy",),
    "rotorvib.checks": ("rotorvib.io", "rotorvib.methods", "rotorvib.models",
                        "rotorvib.papers", "rotorvib.comparison", "rotorvib.pipeline"),
}
#: The papers' own packages (beside them in rotorvib.papers, the contract they share).
PAPERS = sorted(p.name for p in (SRC / "rotorvib/papers").iterdir()
                if (p / "__init__.py").is_file())


def imports_of(name):
    path = MODULES[name]
    return imported_names(path.read_text(), name, path.name == "__init__.py")


@pytest.mark.parametrize("name", sorted(MODULES))
def test_module_respects_the_layers(name):
    imported = imports_of(name)
    assert not any(i.split(".")[0] == "snakemake" for i in imported)
    for layer, forbidden in FORBIDDEN.items():
        if name.startswith(layer):
            assert not [i for i in imported if i.startswith(forbidden)], name
    if name.startswith("rotorvib.papers."):
        paper = name.split(".")[2]     # a paper, or a module of the contract they share
        others = [i for i in imported if i.startswith("rotorvib.papers.")
                  and i.split(".")[2] in set(PAPERS) - {paper}]
        assert not others, f"{name} imports another paper: {others}"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_modules_stay_small(name):
    assert len(MODULES[name].read_text().splitlines()) <= 430


def test_the_package_root_holds_packages_and_the_shared_checks():
    """The root shows the architecture: its packages, and beside them only ``checks`` (the
    argument checks every layer shares; rotorvib/__init__.py says why)."""
    root = SRC / "rotorvib"
    assert sorted(p.name for p in root.glob("*.py")) == ["__init__.py", "checks.py"]


def test_the_rules_keep_the_rules_for_rule_authors(declared):
    """rotorvib.pipeline.plan.rule_problems holds for the workflow's rules (Snakemake also
    refuses to plan otherwise): every rule that writes a dataset has a benchmark and a priority."""
    from rotorvib.pipeline.plan import COMPUTES, rule_problems

    assert rule_problems(list(declared.values())) == []
    computes = [r for r in declared.values() if any(o.endswith(".nc") for o in r.outputs)]
    assert len(computes) > 20 and all(r.benchmark and r.priority >= COMPUTES for r in computes)


def test_only_the_shards_of_batch_studies_are_cluster_jobs(declared):
    """Every rule runs where Snakemake runs but the shards of paper B's batch studies, and its
    Pareto study when those are sharded (workflow/rules/paper_b.smk)."""
    from rotorvib.pipeline.slurm_profile import declared_rules

    cluster = {name for name, rule in declared.items() if not rule.local}
    assert cluster == {name for name in declared if name.endswith("_shard")}
    assert len(cluster) == 6 and all(declared[name].batch for name in cluster)
    sharded = declared_rules(SRC.parent, "--configfile", "tests/config/three_shards.yaml")
    assert {rule.name for rule in sharded if not rule.local} == cluster | {"b_pareto"}


def test_every_job_the_longest_chain_waits_for_shares_its_priority(snakemake_here, declared):
    """The longest chain (rotorvib.pipeline.plan) starts as early as its inputs allow: every
    rule that paper B's discrepancy analysis needs, directly or through other rules (its
    ancestors in Snakemake's rule graph), declares the chain's priority or the first jobs'
    (the genetic algorithm); one with less waits behind other jobs and holds the chain back."""
    from rotorvib.pipeline.plan import BESIDE_THE_COMPILE, LONGEST_CHAIN

    graph = snakemake_here("--rulegraph")
    assert graph.returncode == 0, graph.stderr
    label = dict(re.findall(r'^\s*(\d+)\[label = "(\w+)"', graph.stdout, re.M))
    needs = [(label[a], label[b]) for a, b in re.findall(r"^\s*(\d+) -> (\d+)", graph.stdout, re.M)]
    upstream, frontier = set(), {"b_discrepancies"}
    while frontier:
        frontier = {a for a, b in needs if b in frontier} - upstream
        upstream |= frontier
    assert {"b_ga", "b_boundary", "b_ga_law", "b_reproduced_values"} <= upstream
    waiting = {name for name in upstream
               if declared[name].priority not in (LONGEST_CHAIN, BESIDE_THE_COMPILE)}
    assert not waiting


SCRIPTS = sorted((SRC.parent / "workflow/scripts").glob("*.py"))


@pytest.mark.parametrize("path", SCRIPTS, ids=lambda p: p.name)
def test_every_job_script_starts_as_a_job(path):
    """rotorvib.pipeline.job imported first (the imports then run without the cyclic collector), and
    ``job.start(snakemake.log[0])`` once, at the top level, after every import (a module
    imported by name, ``importlib.import_module``, included)."""
    body = ast.parse(path.read_text()).body
    assert isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)  # docstring
    first = body[1]
    assert isinstance(first, ast.ImportFrom) and first.module == "rotorvib.pipeline"
    assert [alias.name for alias in first.names] == ["job"]
    starts = [i for i, s in enumerate(body) if ast.unparse(s) == "job.start(snakemake.log[0])"]
    assert len(starts) == 1
    after = body[starts[0]:]
    assert not [s for s in after if isinstance(s, (ast.Import, ast.ImportFrom))]
    assert "import_module" not in ast.unparse(ast.Module(body=after, type_ignores=[]))


def test_the_tests_benchmarks_and_docs_import_in_order():
    """ruff's import-order rules (isort) over the tests, the benchmarks and the docs'
    configuration, as pyproject.toml configures them (the library and the job scripts keep
    their own order: pyproject.toml says why)."""
    import subprocess
    import sys

    root = SRC.parent
    run = subprocess.run([sys.executable, "-m", "ruff", "check", "--select", "I", "tests",
                          "benchmarks", "docs/conf.py"], cwd=root, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr

