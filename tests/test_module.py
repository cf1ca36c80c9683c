"""The workflow reused as others would: as a Snakemake ``module`` of another workflow (through
``workflow/Snakefile``, the catalog's layout, and as ``snakedeploy`` deploys it), with the
caller's own ``config:`` (merged over the shipped defaults and checked as strictly) and results
folder, and run from another working directory (``--directory``). Every file the workflow
reads of its own (the schema, the papers' data, the Snakefile) is found beside its rules, not
in the caller's folder."""

import os
import re
import subprocess

import pytest
import yaml

from workflow_runs import BIN, ROOT, copy_repository, environment

TARGET = "paper_c/datasets/ga.nc"


def _reduced(results: str) -> dict:
    """The reduced configuration's overrides, writing to ``results``."""
    overrides = yaml.safe_load((ROOT / "config/test/config.yaml").read_text())
    return {**overrides, "results": results}


def _consumer(tmp_path, module_config: dict):
    repo = copy_repository(tmp_path / "rotorvib")
    consumer = tmp_path / "analysis"
    consumer.mkdir()
    (consumer / "config.yaml").write_text(yaml.safe_dump({"rotorvib": module_config}))
    (consumer / "Snakefile").write_text(
        'configfile: "config.yaml"\n\n\n'
        "module rotorvib:\n"
        f'    snakefile: "{repo / "workflow/Snakefile"}"\n'
        '    config: config["rotorvib"]\n\n\n'
        "use rule * from rotorvib as rotorvib_*\n")
    return repo, consumer


def _snakemake(cwd, *args, check=True, repo=None):
    """Snakemake in ``cwd``, importing the package of ``repo`` (by default ``cwd``): a caller's
    folder has none of its own, and the one installed may be another checkout's."""
    env = environment(cwd, {"PYTHONPATH": environment(repo or cwd)["PYTHONPATH"]})
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=env, timeout=600)
    if check:
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return run


def test_a_module_with_its_own_config_writes_where_the_caller_says(tmp_path):
    repo, consumer = _consumer(tmp_path, _reduced("out/rv"))
    dry = _snakemake(consumer, "-n", "-j1", repo=repo)
    assert "rotorvib_c_ga" in dry.stdout and "out/rv/paper_c/figures/fig5.png" in dry.stdout
    _snakemake(consumer, "-j1", f"out/rv/{TARGET}", repo=repo)
    made = consumer / "out/rv" / TARGET
    assert made.is_file() and not (consumer / "results").exists()
    assert not (repo / "results").exists()


def test_a_module_config_gets_the_same_checks(tmp_path):
    repo, consumer = _consumer(tmp_path, {"results": "out/rv", "paper_c": {"rotor": {"M": -5.0}}})
    run = _snakemake(consumer, "-n", check=False, repo=repo)
    assert run.returncode != 0
    assert "config key 'paper_c.rotor.M': -5.0 is not allowed" in run.stdout + run.stderr
    assert "Job " not in run.stdout


def test_a_run_from_another_directory_finds_its_own_files(tmp_path):
    repo = copy_repository(tmp_path / "rotorvib")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "reduced.yaml").write_text(yaml.safe_dump(_reduced("results")))
    args = ["--directory", str(elsewhere), "--configfile", str(repo / "config/config.yaml"),
            str(elsewhere / "reduced.yaml")]
    _snakemake(repo, "-j1", f"results/{TARGET}", *args)
    assert (elsewhere / "results" / TARGET).is_file() and not (repo / "results").exists()


def test_snakedeploys_layout_runs_the_workflow_as_a_module(tmp_path):
    """What a user of the workflow catalog does: ``snakedeploy deploy-workflow`` writes a
    workflow of their own (its Snakefile naming ``workflow/Snakefile`` as a module, with their
    copy of ``config/``); Snakemake, reading that copy with its own YAML loader, plans every job
    of the paper configuration into their folder. For a local repository snakedeploy writes the
    module's path relative to the new workflow; it is made the repository's, as ``github(...)``
    would fetch it."""
    repo = copy_repository(tmp_path / "rotorvib")
    # what a deployment fetches: the repository's last commit (snakedeploy copies a local
    # repository's whole folder, environments and results included, so it is given a clone)
    published = tmp_path / "published"
    subprocess.run(["git", "clone", "--quiet", "--depth", "1", ROOT.as_uri(), str(published)],
                   check=True, timeout=300)
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=published, capture_output=True,
                            text=True, check=True).stdout.strip()
    deployed = tmp_path / "analysis"
    run = subprocess.run([str(BIN / "snakedeploy"), "deploy-workflow", str(published),
                          str(deployed), "--commit", commit, "--name", "rotorvib"],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    snakefile = deployed / "workflow/Snakefile"
    text = snakefile.read_text()
    assert 'snakefile: \n        "workflow/Snakefile"' in text and "use rule * from rotorvib" in text
    snakefile.write_text(text.replace('"workflow/Snakefile"', f'"{repo / "workflow/Snakefile"}"'))
    (deployed / "config/config.yaml").write_text((repo / "config/config.yaml").read_text())
    plan = _snakemake(deployed, "--summary", "all", repo=repo)   # every output, its rule and status
    assert "results/paper_c/figures/fig5.png\t" in plan.stdout and "\tc_ga\t" in plan.stdout
    assert "workflow specific profile profiles/default" in plan.stdout + plan.stderr
    # both profiles deployed, each naming the stylesheet the deployment carries
    assert (deployed / "profiles/report.css").read_bytes() == (ROOT / "profiles/report.css").read_bytes()
    cluster = _snakemake(deployed, "--summary", "--workflow-profile", "profiles/slurm", "all",
                         repo=repo)
    assert "workflow specific profile profiles/slurm" in cluster.stdout + cluster.stderr
    assert not (repo / "results").exists()


#: A module's ``config:`` as callers write it, over the file ``config.yaml`` in their folder.
MODULE_PART = 'config: config["rotorvib"]'


def _dry_run_as_module(tmp_path, text: str, config_line: str = MODULE_PART, before: str = "",
                       *args: str) -> subprocess.CompletedProcess:
    """``snakemake -n`` of a caller whose Snakefile reads ``text`` as its ``config.yaml`` and
    gives this workflow (the working tree's, not a copy: a dry run writes nothing beside it)
    ``config_line``, after the Python lines ``before``."""
    (tmp_path / "config.yaml").write_text(text)
    (tmp_path / "Snakefile").write_text(
        f'configfile: "config.yaml"\n{before}\n\nmodule rotorvib:\n'
        f'    snakefile: "{ROOT / "workflow/Snakefile"}"\n    {config_line}\n\n\n'
        "use rule * from rotorvib as rotorvib_*\n")
    return subprocess.run([str(BIN / "snakemake"), "-n", "-j1", *args], cwd=tmp_path,
                          capture_output=True, text=True, timeout=300, check=False,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src")})


@pytest.mark.parametrize("text, config_line, refused", [
    # YAML 1.1 readings of the caller's file (Snakemake read 0777 as 511, 1:30 as 90 and kept
    # the last zeta): refused with file, line and column, as in a file given to the workflow
    ("rotorvib:\n  paper_b:\n    ga:\n      seed: 0777\n", MODULE_PART,
     "config.yaml:4:13: '0777' reads differently in YAML 1.1 and 1.2"),
    ("rotorvib:\n  paper_b:\n    balance:\n      t_end: 1:30\n", MODULE_PART,
     "config.yaml:4:14: '1:30' reads differently"),
    ("rotorvib:\n  paper_b:\n    machine:\n      zeta: 0.01\n      zeta: 0.02\n", MODULE_PART,
     "config.yaml:5:7: duplicate key 'zeta' (first at line 4)"),
    # the whole of the caller's configuration, as snakedeploy writes the module
    ("results: out\npaper_b:\n  progress: yes\n", "config: config",
     "config.yaml:3:13: 'yes' reads differently"),
    # out of the library's magnitudes: refused naming the key, before any job
    ("rotorvib:\n  paper_c:\n    rotor:\n      M: 1.0e+308\n", MODULE_PART,
     "config key 'paper_c.rotor.M': 1e+308 is not allowed; must be 0 or between 1e-100"),
    # a mapping built in the Snakefile: no file to read again, what YAML 1.1 leaves is refused
    ("{}\n", 'config: {"results": "out", "paper_b": {True: {}}}',
     "the module's config: key True is a bool, not text"),
])
def test_a_module_config_is_read_as_a_file_is(tmp_path, text, config_line, refused):
    run = _dry_run_as_module(tmp_path, text, config_line)
    assert run.returncode != 0 and refused in run.stdout + run.stderr, run.stdout + run.stderr
    assert "Job " not in run.stdout


def test_a_module_config_changed_by_the_caller_after_reading_is_refused(tmp_path):
    """Its change would be lost in reading the files again: the caller is told to give the
    module a mapping of its own."""
    run = _dry_run_as_module(tmp_path, "rotorvib:\n  results: out\n", MODULE_PART,
                             'config["rotorvib"]["results"] = "elsewhere"')
    assert run.returncode != 0
    assert ("config key 'results' of the module's config (the caller's 'rotorvib.results') "
            "differs from the files it was read from") in run.stdout + run.stderr


def test_a_module_config_reads_an_exponent_as_a_number(tmp_path):
    """YAML 1.1 reads 1e-10 as text; read again from the file, it is the number a file given to
    the workflow holds, and the module plans its jobs."""
    run = _dry_run_as_module(tmp_path, "rotorvib:\n  results: out\n  paper_c:\n"
                                       "    time_response:\n      rtol: 1e-10\n")
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert "rotorvib_c_ga" in run.stdout


def test_a_modules_callers_command_line_is_read_as_a_file_is(tmp_path):
    run = _dry_run_as_module(tmp_path, "rotorvib:\n  results: out\n", MODULE_PART, "",
                             "--config", "rotorvib={results: out, results: other}")
    assert run.returncode != 0
    assert "--config rotorvib:1:16: duplicate key 'results'" in run.stdout + run.stderr


def test_the_docs_name_only_refs_that_exist():
    """Every ``--tag``, ``--branch`` or ``tag=``/``branch=`` the docs give snakedeploy or a
    module is a ref of the repository (they named a tag v0.1.0 there never was)."""
    refs = set()
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = page.read_text(encoding="utf-8")
        refs |= {(a or c, b or d) for a, b, c, d in re.findall(
            r"--(tag|branch)[ =]([\w./-]+)|\b(tag|branch)=\"([\w./-]+)\"", text)}
    assert ("branch", "main") in refs
    for kind, name in refs:
        candidates = ([f"refs/tags/{name}"] if kind == "tag"
                      else [f"refs/heads/{name}", f"refs/remotes/origin/{name}"])
        assert any(subprocess.run(["git", "rev-parse", "--verify", "--quiet", ref], cwd=ROOT,
                                  capture_output=True, check=False).returncode == 0
                   for ref in candidates), (
            f"the docs name {kind} {name!r}, which the repository does not have")
