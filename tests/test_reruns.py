"""What reruns after a change to a reduced run (tests/workflow_runs.py): exactly the jobs
that depend on it, neither more nor fewer, for a configuration value, every module of the
package and every data file; nothing for a comment or a docstring. The dry runs are forked from
one prepared Snakemake process (tests/forked_snakemake.py), which answers as a fresh command
does. (A file of its own, apart from test_workflow.py, so that any pytest-xdist worker can take
it once the runs exist.)"""

import json
import os
import re
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from conftest import ROOT
from forked_snakemake import ForkedSnakemake
from rotorvib.pipeline.fingerprint import import_closure
from workflow_runs import (
    REDUCED,
    copy_run,
    environment,
    job_records,
    planned_outputs,
    run_block_jobs,
    snakemake,
    to_update,
)

pytestmark = pytest.mark.workflow


def downstream_outputs(records: list[dict], selected) -> set[str]:
    """Outputs of the ``selected`` jobs and of every job that reads them, transitively."""
    chosen = [r for r in records if selected(r)]
    outputs = {f for r in chosen for f in r["output"]}
    grew = True
    while grew:
        more = [r for r in records if r not in chosen and outputs & set(r["input"])]
        chosen += more
        outputs |= {f for r in more for f in r["output"]}
        grew = bool(more)
    return outputs


def test_config_change_reruns_exactly_the_dependent_jobs(run_dir, tmp_path):
    assert planned_outputs(run_dir) == set()
    records = job_records(run_dir)
    records += run_block_jobs(run_dir, records)
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  den_hartog:\n    d: 0.09\n")
    expected = downstream_outputs(records, lambda r: r["rule"] == "c_time_response")
    assert "results/paper_c/figures/fig4.png" in expected
    assert planned_outputs(run_dir, str(change)) == expected
    # the same override on the command line: its nested value is read as YAML, a number
    assert planned_outputs(run_dir, "--config", 'paper_c={den_hartog: {d: 0.09}}') == expected
    change.write_text("paper_b:\n  balance_studies:\n    eps_bar:\n      fixed: {beta: 0.5, "
                      "mass: 0.01}\n")
    study = "results/paper_b/datasets/balance_eps_bar.nc"
    expected = downstream_outputs(records, lambda r: study in r["output"])
    assert {study, "results/paper_b/datasets/balance_mass.nc"} & expected == {study}
    assert planned_outputs(run_dir, str(change)) == expected


def _edit_in_turn(work: Path, files: list[str], edit) -> dict[str, set[str]]:
    """Planned outputs after editing each file alone (restored afterwards), each dry run a
    ``snakemake`` command forked from one that has done its imports (tests/forked_snakemake.py)."""
    planned = {}
    with ForkedSnakemake(work, environment(work)) as command:
        for name in files:
            path = work / name
            original, stat = path.read_bytes(), path.stat()
            try:
                edit(path)
                planned[name] = planned_outputs(work, command=command)
            finally:
                path.write_bytes(original)
                os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    return planned


def _behaviour_edit(path: Path):
    if path.suffix == ".py":
        path.write_text(path.read_text() + "\n_EDITED = True\n")
    else:  # a data file: new content (Snakemake ignores a newer file with an unchanged checksum)
        path.write_text(path.read_text() + "\n")


def test_every_module_and_data_file_reruns_exactly_the_jobs_that_load_it(run_dir, tmp_path):
    """Edit each module under src/rotorvib and each file under data/ in turn: the dry run plans
    exactly the jobs that loaded that module (recorded from sys.modules while they ran) or read
    that file, and everything downstream of them, neither more nor fewer."""
    recorded = job_records(run_dir)
    records = [r for r in recorded + run_block_jobs(run_dir, recorded) if r["rule"] != "archive"]
    modules = sorted(p.relative_to(run_dir).as_posix()
                     for p in (run_dir / "src/rotorvib").rglob("*.py"))
    data = sorted(p.relative_to(run_dir).as_posix() for p in (run_dir / "data").iterdir())
    files = modules + data

    def name_of(path):
        parts = Path(path).relative_to("src").with_suffix("").parts
        return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)

    def expected(path):
        if path.startswith("data/"):
            return downstream_outputs(records, lambda r: path in r["input"])
        return downstream_outputs(records, lambda r: name_of(path) in r["modules"])

    copies = [copy_run(run_dir, tmp_path / name) for name in ("first", "second")]
    with ThreadPoolExecutor(len(copies)) as pool:
        halves = pool.map(lambda k: _edit_in_turn(copies[k], files[k::2], _behaviour_edit),
                          range(len(copies)))
    planned = {name: plan for half in halves for name, plan in half.items()}
    wrong = {name: {"missing": sorted(expected(name) - plan), "extra": sorted(plan - expected(name))}
             for name, plan in planned.items() if plan != expected(name)}
    assert not wrong, json.dumps(wrong, indent=1)
    assert planned["src/rotorvib/__init__.py"] >= {f for r in records for f in r["output"]}
    # the machinery stays out of the jobs: an edit of a pipeline module reruns at most one job
    # (and what follows from it), but for a job's start-up and a sharded study's split
    loaders = {name: sum(name_of(name) in r["modules"] for r in records) for name in modules
               if name.startswith("src/rotorvib/pipeline/") and name_of(name) not in (
                   "rotorvib.pipeline", "rotorvib.pipeline.job", "rotorvib.pipeline.pint_probe",
                   "rotorvib.pipeline.console", "rotorvib.pipeline.shards")}
    assert max(loaders.values()) <= 1, loaders
    # no job reads YAML: the configuration and the papers' citations are read with the rules
    assert loaders["src/rotorvib/pipeline/strict_yaml.py"] == 0, loaders


def test_a_forked_command_answers_as_a_fresh_one(run_dir, tmp_path):
    """The dry runs above come from tests/forked_snakemake.py: a forked command exits and prints
    as a fresh ``snakemake`` does, for a command that fails and, after an edit made once the
    server has answered, for a plan."""
    work = copy_run(run_dir, tmp_path / "work")
    failing = ("-n", *REDUCED, "--config", "paper_c={rotor: {M: -5}}")
    with ForkedSnakemake(work, environment(work)) as forked:
        answers = [(snakemake(work, *failing, check=False), forked(*failing))]
        _behaviour_edit(work / "src/rotorvib/papers/c/claims.py")
        answers.append((snakemake(work, "--summary", *REDUCED), forked("--summary", *REDUCED)))
    for fresh, fork in answers:
        assert (fork.returncode, fork.stdout, fork.stderr) == (
            fresh.returncode, fresh.stdout, fresh.stderr)
    (failed, _), (planned, _) = answers
    assert failed.returncode == 1 and "config key 'paper_c.rotor.M'" in failed.stdout
    assert "results/paper_c/figures/fig6.png" in to_update(planned.stdout)


def test_comments_and_docstrings_rerun_nothing(run_dir, tmp_path):
    work = copy_run(run_dir, tmp_path / "work")
    for path in sorted((work / "src/rotorvib").rglob("*.py")):
        text = path.read_text()
        if text.startswith('"""'):
            text = '"""Edited: ' + text[3:]
        path.write_text(text + "\n# a comment\n")
    assert planned_outputs(work) == set()


def _jobs_by_rule(cwd: Path, *args: str) -> dict[str, int]:
    """The jobs of a whole run of the configuration ``args``, by rule (a forced dry run)."""
    stats = snakemake(cwd, "-n", "-j1", "--forceall", "--quiet", "rules", *args).stdout
    return {rule: int(n) for rule, n in re.findall(r"^(\w+)\s+(\d+)$", stats, re.M)
            if rule != "total"}


def test_the_decisions_state_what_an_edit_of_the_jobs_machinery_reruns(run_dir, declared):
    """The decisions table (docs/architecture.md) gives, for the pipeline modules that more
    than one job loads (a job's start-up; a batch study's split), the jobs an edit of one
    reruns, in a paper run and in the reduced run: counted here from the modules each job of
    the reduced run loaded, and from the code the scripts of a paper run's jobs import."""
    records = job_records(run_dir)
    paper = _jobs_by_rule(ROOT)
    scripts = {name: ROOT / rule.script for name, rule in declared.items() if rule.script}
    stated = re.compile(r"(\d+) of a paper run's (\d+) jobs, (\d+) of the reduced run's (\d+)")
    table = (ROOT / "docs/architecture.md").read_text()
    for module in ("job", "pint_probe", "console", "shards"):
        row = next(line for line in table.splitlines()
                   if f"`pipeline/{module}.py`" in line and stated.search(line))
        name = f"rotorvib.pipeline.{module}"
        in_paper = sum(n for rule, n in paper.items()
                       if rule in scripts and name in import_closure(scripts[rule]))
        in_reduced = sum(name in r["modules"] for r in records)
        reduced = sum(_jobs_by_rule(run_dir, *REDUCED).values())
        assert [int(n) for n in stated.search(row).groups()] == [
            in_paper, sum(paper.values()), in_reduced, reduced], module
