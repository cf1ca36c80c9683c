"""The package's declared dependencies against what its code imports: every third-party module
the library and the workflow's scripts import comes from a distribution of
``[project].dependencies``; what the tests and benchmarks import or run, from those or the
``test`` and ``docs`` extras; and every declared distribution is pinned in environment.txt."""

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions

from conftest import ROOT

PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
#: Run by the tests as commands (not imported): their distributions.
COMMANDS = {"snakefmt": "snakefmt", "compliance-checker": "compliance-checker",
            "sphinx-build": "sphinx"}
#: Benchmark-only, built with gfortran (benchmarks/requirements.txt).
BENCHMARK_ONLY = {"numbalsoda"}
#: What `pip freeze` (which wrote environment.txt) leaves out: its own tools.
FROZEN_OUT = {"pip", "setuptools", "wheel"}


def _name(requirement: str) -> str:
    """A requirement's distribution name, normalised (PEP 503)."""
    return re.sub(r"[-_.]+", "-", re.match(r"[A-Za-z0-9_.-]+", requirement).group(0)).lower()


def _imported(*folders) -> set[str]:
    """The distributions of the third-party modules imported under ``folders``."""
    distributions = packages_distributions()
    found = set()
    for folder in folders:
        for path in (ROOT / folder).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                         [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0
                         and node.module else [])
                for top in {n.split(".")[0] for n in names} - set(sys.stdlib_module_names):
                    found |= {_name(d) for d in distributions.get(top, ())}
    return found - {"rotorvib"}


def test_the_library_and_scripts_import_only_declared_dependencies():
    declared = {_name(r) for r in PROJECT["dependencies"]}
    assert _imported("src", "workflow/scripts") <= declared


def test_tests_and_benchmarks_need_only_the_test_extra_besides():
    extras = PROJECT["optional-dependencies"]
    declared = {_name(r) for r in PROJECT["dependencies"]} | {
        _name(r) for name in ("test", "docs", "slurm") for r in extras[name]}
    assert _imported("tests", "benchmarks", "docs") - BENCHMARK_ONLY <= declared
    assert {_name(d) for d in COMMANDS.values()} <= declared


def test_every_declared_distribution_is_pinned():
    pinned = {_name(line) for line in (ROOT / "environment.txt").read_text().splitlines()
              if re.match(r"[A-Za-z0-9]", line)}
    declared = {_name(r) for r in PROJECT["dependencies"]} | {
        _name(r) for rs in PROJECT["optional-dependencies"].values() for r in rs} - {"rotorvib"}
    assert declared <= pinned, declared - pinned


def test_each_supported_python_has_a_hashed_lock_of_the_tested_pins():
    """The README names the supported Pythons; each has a lock (requirements/lock, uv) whose
    every version is the one environment.txt pins and whose every entry is hashed."""
    heading = re.search(r"^## Set up and run \(fresh machine, Python ([^)]*)\)$",
                        (ROOT / "README.md").read_text(), re.M).group(1)
    versions = re.findall(r"3\.\d+", heading)
    assert versions == ["3.11", "3.12", "3.13"]
    pinned = dict(re.findall(r"^([A-Za-z0-9][\w.-]*)==(\S+)$",
                             (ROOT / "environment.txt").read_text(), re.M))
    pinned = {_name(k): v for k, v in pinned.items()}
    for version in versions:
        lock = (ROOT / f"requirements/py{version.replace('.', '')}.txt").read_text()
        entries = re.findall(r"^([A-Za-z0-9][\w.-]*)==(\S+) \\\n((?:\s+--hash=sha256:\w+.*\n)+)",
                             lock, re.M)
        assert len(entries) == lock.count("==") > 100, version
        for name, pin, _ in entries:
            if _name(name) not in FROZEN_OUT:
                assert pinned.get(_name(name)) == pin, (version, name)
