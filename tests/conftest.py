"""Shared fixtures: paper C's rotor and Table 2 from the repository's configuration."""

import dataclasses
import os
from functools import cache
from pathlib import Path

import pytest

from rotorvib.models.absorber.parameters import Rotor, dual_absorber
from rotorvib.pipeline.config import load_yaml, validate_config
from rotorvib.pipeline.fingerprint import import_closure

ROOT = Path(__file__).resolve().parents[1]
#: The module of the balancer's compiled integrators (tests/workflow_runs.compile_the_engine).
INTEGRATORS = "rotorvib.models.balancer.simulate"


@pytest.hookimpl(tryfirst=True)     # before ``-m`` deselects by the markers added here
def pytest_collection_modifyitems(items):
    """A test that reads the reduced runs (its fixtures reach ``run_dir``) is a workflow test
    (marker ``workflow``: ``pytest -m "not workflow"`` leaves it out with the runs it needs).
    test_workflow.py first: it builds the reduced runs (tests/workflow_runs.py), the first and
    then, at its first comparison of the two, the second, most of the suite's time, on one
    pytest-xdist worker (pyproject.toml) while the others take the library tests; the other
    files with a test that reads the runs last, whole (a worker takes a file at its first test:
    one taken early would wait for the runs with its other tests behind), so that whichever
    worker is free then takes them once the runs exist, those that compare the two runs before
    those that read the first only: a worker that takes one before the second run exists waits
    while that run's build keeps both cores busy, and the longest of them (test_cluster.py) is
    not left to run alone at the end. Among the library tests, the files that can run the
    balancer's compiled integrators (their imports reach them) come after the others: the first
    worker compiles them for the runs meanwhile, and the others would wait on the compile lock."""
    read_runs, read_both = set(), set()
    for item in items:
        if "run_dir" in item.fixturenames:
            item.add_marker(pytest.mark.workflow)
            read_runs.add(item.path)
        if "runs" in item.fixturenames:
            read_both.add(item.path)

    @cache
    def runs_integrators(path):
        return INTEGRATORS in import_closure(path, root=ROOT / "src")

    def order(item):
        if item.path.name == "test_workflow.py":
            return 0
        if item.path in read_runs:
            return 3 if item.path in read_both else 4
        return 2 if runs_integrators(item.path) else 1
    items.sort(key=order)


def _shared_run(tmp_path_factory, worker_id, name: str) -> Path:
    from workflow_runs import shared_run

    root = tmp_path_factory.getbasetemp()
    return shared_run(root if worker_id == "master" else root.parent, name)


@pytest.fixture(scope="session")
def run_dir(tmp_path_factory, worker_id) -> Path:
    """The first reduced run (tests/workflow_runs.py), built once for all workers in the folder
    they share: to be read, or copied (workflow_runs.copy_run) to be changed."""
    return _shared_run(tmp_path_factory, worker_id, "repo")


@pytest.fixture(scope="session")
def runs(run_dir, tmp_path_factory, worker_id) -> list[Path]:
    """The two reduced runs of the session, the first and the sharded one
    (tests/workflow_runs.py), the second built once for all workers when first asked for."""
    return [run_dir, _shared_run(tmp_path_factory, worker_id, "sharded")]


@pytest.fixture(scope="session")
def snakemake_here():
    """Dry runs of Snakemake in the repository, each a child of one prepared process
    (tests/forked_snakemake.py: as a fresh ``snakemake`` command answers, for a start-up's
    cost once)."""
    from forked_snakemake import ForkedSnakemake

    with ForkedSnakemake(ROOT, dict(os.environ)) as command:
        yield command


@pytest.fixture(scope="session")
def declared():
    """Every rule of the workflow as Snakemake reads it (its rule objects, as the plan reads
    them: rotorvib.pipeline.slurm_profile.declared_rules), by name; read once a session."""
    from rotorvib.pipeline.slurm_profile import declared_rules

    return {rule.name: rule for rule in declared_rules(ROOT)}


@pytest.fixture(scope="session")
def config():
    return validate_config(load_yaml(ROOT / "config/config.yaml"),
                           load_yaml(ROOT / "config/schema.yaml"))


@pytest.fixture(scope="session")
def setup(config):
    """Paper B's setup from the configuration, with 8 s runs (every run the tests of paper B
    make with it balances)."""
    from rotorvib.papers.b.setup import Setup

    s = Setup.from_paper_b(config["paper_b"])
    return dataclasses.replace(s, criterion=dataclasses.replace(s.criterion, t_end=8.0))


@pytest.fixture(scope="session")
def schema():
    return load_yaml(ROOT / "config/schema.yaml")


@pytest.fixture(scope="session")
def rotor(config):
    return Rotor(**config["paper_c"]["rotor"])


@pytest.fixture(scope="session")
def table2(config):
    return dual_absorber(**config["paper_c"]["table2"])


def cf_check(*paths):
    """Run the compliance-checker (CF 1.11) on ``paths`` in one process; return (all passed,
    report naming each file's issues)."""
    import subprocess
    import sys

    checker = Path(sys.executable).parent / "compliance-checker"
    run = subprocess.run([str(checker), "--test", "cf:1.11", "--criteria", "normal",
                          *map(str, paths)], capture_output=True, text=True)
    return run.returncode == 0, run.stdout


@pytest.fixture(scope="module")
def browser():
    """Headless Chromium through Playwright (tests/report_browser.py)."""
    from report_browser import chromium

    yield from chromium()
