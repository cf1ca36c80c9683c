"""The package's declared dependencies against what its code imports: every third-party module
the library and the workflow's scripts import comes from a distribution of
``[project].dependencies``; what the tests and benchmarks import or run, from those or the
``test`` and ``docs`` extras; and the hashed locks (requirements/lock): environment.txt, the
runtime the README's run command installs, holds exactly what the package's own dependencies
need, no test or docs tool, and requirements/test.txt adds the extras at the same versions."""

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions, requires

from packaging.markers import Marker
from packaging.requirements import Requirement

from conftest import ROOT

PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
#: Run by the tests as commands (not imported): their distributions.
COMMANDS = {"snakefmt": "snakefmt", "compliance-checker": "compliance-checker",
            "sphinx-build": "sphinx"}
#: Benchmark-only, built with gfortran (benchmarks/requirements.txt).
BENCHMARK_ONLY = {"numbalsoda"}


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


#: Each lock's entries: a pin, the marker of the Pythons that have it (none: all) and its hashes.
_ENTRY = re.compile(r"^([A-Za-z0-9][\w.-]*)==([^ ;]+)(?: ; (.+?))? \\\n"
                    r"((?:[ \t]+--hash=sha256:\w+.*\n?)+)", re.M)


def _lock(path: str, python: str) -> dict[str, str]:
    """The pins of lock ``path`` (requirements/lock) that Python ``python`` ("3.12") installs,
    ``{normalised name: version}``; each entry of the file hashed."""
    text = (ROOT / path).read_text()
    entries = _ENTRY.findall(text)
    assert len(entries) == len(re.findall(r"^[A-Za-z0-9]", text, re.M)), path
    return {_name(name): version for name, version, marker, _ in entries
            if not marker or Marker(marker).evaluate({"python_version": python})}


def _supported_pythons() -> list[str]:
    heading = re.search(r"^## Set up and run \(fresh machine, Python ([^)]*)\)$",
                        (ROOT / "README.md").read_text(), re.M).group(1)
    return re.findall(r"3\.\d+", heading)


def _closure(requirements) -> set[str]:
    """The distributions that ``requirements`` (strings) need on this Python, theirs
    included, as the installed distributions' metadata declares them."""
    seen, todo = set(), [(Requirement(r), frozenset()) for r in requirements]
    while todo:
        requirement, wanted = todo.pop()
        environments = [{"extra": e} for e in wanted or {""}]
        if requirement.marker and not any(requirement.marker.evaluate(e) for e in environments):
            continue
        key = (_name(requirement.name), frozenset(requirement.extras))
        if key not in seen:
            seen.add(key)
            todo += [(Requirement(r), key[1]) for r in requires(key[0]) or ()]
    return {name for name, _ in seen}


def test_each_supported_python_has_the_same_tested_pins_in_both_locks():
    """The README names the supported Pythons; for each, the runtime lock (environment.txt)
    pins a part of the test lock (requirements/test.txt), at its versions, and every
    distribution the package declares is pinned where it belongs."""
    assert _supported_pythons() == ["3.11", "3.12", "3.13"]
    runtime_declared = {_name(r) for r in PROJECT["dependencies"]}
    extras_declared = {_name(r) for rs in PROJECT["optional-dependencies"].values()
                       for r in rs} - {"rotorvib"}
    for python in _supported_pythons():
        runtime, test = _lock("environment.txt", python), _lock("requirements/test.txt", python)
        assert len(test) > len(runtime) > 50, python
        assert runtime.items() <= test.items(), (python, runtime.items() - test.items())
        assert runtime_declared <= runtime.keys(), runtime_declared - runtime.keys()
        assert extras_declared <= test.keys(), extras_declared - test.keys()


def test_the_runtime_lock_holds_what_the_workflow_needs_and_no_development_tool():
    """environment.txt, which the README's run command installs, pins exactly the distributions
    the package's own dependencies and the SLURM executor plugin (extra ``slurm``, the README's
    cluster command) need (their metadata's requirements, followed), which cover every
    third-party module the library and the workflow's scripts import; none of the test or docs
    extras' tools (pytest, sphinx, ruff, playwright, ...) that the runtime does not itself
    need."""
    python = "{}.{}".format(*sys.version_info)
    runtime = set(_lock("environment.txt", python))
    needed = _closure(PROJECT["dependencies"] + PROJECT["optional-dependencies"]["slurm"])
    assert runtime == needed, (runtime - needed, needed - runtime)
    assert _imported("src", "workflow/scripts") <= runtime
    tools = {_name(r) for rs in PROJECT["optional-dependencies"].values() for r in rs}
    assert not runtime & (tools - needed), runtime & tools
    assert {"pytest", "sphinx", "ruff", "playwright", "black"} <= set(
        _lock("requirements/test.txt", python)) - runtime
