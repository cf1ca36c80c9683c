"""The workflow from a user's own folder, as right as from its own: a project that uses it as a
Snakemake ``module``, and a run with ``--directory``, each in a separate folder that is a git
work tree of its own. Given the reduced run's results (tests/workflow_runs.py), no job's
parameters differ there (the code fingerprints are the code's, not the SHA-256 of nothing; a
module's rules have the names its caller gives them, which the report's texts state); a
behaviour edit of a library module plans exactly the jobs that load it and those downstream;
the report builds with the captions of the user's own results (not the module's clone's); and
a dataset made there names the library's commit, not the caller's. (The results were made at
the repository's root and moved: the plans compare parameters and code, not the input file
lists, in which the workflow's own files are named from where Snakemake runs.)"""

import shlex
import shutil
import subprocess

import pytest
import xarray as xr
import yaml

from conftest import ROOT
from test_reruns import downstream_outputs
from workflow_runs import (
    BIN,
    copy_run,
    environment,
    job_counts,
    job_records,
    run_block_jobs,
    to_update,
)

pytestmark = pytest.mark.workflow
#: A module loaded by few jobs, and an edit that changes its behaviour.
EDITED = "src/rotorvib/papers/c/spin.py"
MARKER = "A caption of the user's own results."


def git(cwd, *args) -> str:
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True,
                          env={"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
                               "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t",
                               "HOME": str(cwd)}).stdout.strip()


def commit_all(folder) -> str:
    git(folder, "init", "-q")
    git(folder, "add", "-A")
    git(folder, "commit", "-q", "--allow-empty", "-m", "state")
    return git(folder, "rev-parse", "HEAD")


def _snakemake(repo, cwd, *args, check=True):
    """Snakemake in ``cwd`` importing the library of ``repo`` (the module's clone)."""
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=environment(repo), timeout=600, check=False)
    if check:
        assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-4000:]
    return run


def _moved_results(repo, folder):
    """The run's results and Snakemake's records of them, moved from the clone ``repo`` into
    the user's ``folder``; the clone keeps a copy of the report's texts whose captions say
    something else (where the report took them from the clone, this showed)."""
    folder.mkdir(exist_ok=True)
    shutil.copytree(repo / "results/report", repo / "report_copy")
    shutil.move(repo / "results", folder / "results")
    shutil.move(repo / "report_copy", repo / "results/report")
    for caption in (repo / "results/report/captions").rglob("*.rst"):
        caption.write_text("The module's clone's caption.\n")
    shutil.copytree(repo / ".snakemake/metadata", folder / ".snakemake/metadata")
    (folder / "results/report/captions/figures/c_fig5.rst").write_text(MARKER + "\n")


@pytest.fixture(params=["module", "directory"])
def user(request, run_dir, tmp_path):
    """``(repo, folder, command)``: the clone, the user's folder holding the results, and the
    arguments that run the workflow there as the user does."""
    repo = copy_run(run_dir, tmp_path / "rotorvib")
    folder = tmp_path / "analysis"
    _moved_results(repo, folder)
    overrides = yaml.safe_load((ROOT / "config/test/config.yaml").read_text())
    if request.param == "module":
        (folder / "config.yaml").write_text(
            yaml.safe_dump({"rotorvib": {**overrides, "results": "results"}}))
        (folder / "Snakefile").write_text(
            'configfile: "config.yaml"\n\n\nmodule rotorvib:\n'
            f'    snakefile: "{repo / "workflow/Snakefile"}"\n'
            '    config: config["rotorvib"]\n\n\nuse rule * from rotorvib as rotorvib_*\n')
        command = (folder, [])
    else:
        (folder / "reduced.yaml").write_text(yaml.safe_dump({**overrides, "results": "results"}))
        command = (repo, ["--directory", str(folder), "--configfile",
                          str(repo / "config/config.yaml"), str(folder / "reduced.yaml")])
    commit_all(folder)                                      # the user's own work tree
    return repo, folder, command, request.param


def _planned(repo, command) -> set[str]:
    cwd, given = command
    return to_update(_snakemake(repo, cwd, "--summary", "--rerun-triggers", "params", "code",
                                "software-env", *given).stdout)


def test_a_users_folder_plans_and_reruns_as_the_workflows_own(user, run_dir):
    repo, _, command, kind = user
    recorded = job_records(run_dir)
    records = [r for r in recorded + run_block_jobs(run_dir, recorded) if r["rule"] != "archive"]
    renamed = downstream_outputs(records, lambda r: kind == "module" and r["rule"] == "report_text")
    assert _planned(repo, command) == renamed
    name = EDITED.removeprefix("src/").removesuffix(".py").replace("/", ".")
    expected = downstream_outputs(records, lambda r: name in r["modules"])
    assert expected and "results/comparison.csv" in expected
    source = repo / EDITED
    original = source.read_text()
    source.write_text(original + "\n\ndef _an_edit():\n    return 1\n")
    assert _planned(repo, command) == expected | renamed


def test_a_run_in_a_users_folder_names_the_librarys_commit_and_its_report_command_works(
        user, run_dir):
    """A job run there writes a dataset that names the library's commit; the report's command
    (with ``--directory``, the one the run's closing lines give, run as given from the folder
    the user is in; in a module's caller, the user guide's) builds the report with that
    folder's captions."""
    repo, folder, command, kind = user
    cwd, given = command
    library = commit_all(repo)
    rule = "rotorvib_c_spin" if kind == "module" else "c_spin"
    run = _snakemake(repo, cwd, "-j1", *given, "--forcerun", rule, "--until", rule)
    assert job_counts(run).get(rule) == 1
    (made,) = (f for r in job_records(run_dir) if r["rule"] == "c_spin" for f in r["output"]
               if f.endswith(".nc"))
    with xr.open_dataset(folder / made) as ds:
        assert ds.attrs["provenance_git_commit"] == library != git(folder, "rev-parse", "HEAD")
        assert ds.attrs["provenance_code_origin"] == "git checkout"
    said = (run.stdout + run.stderr).splitlines()
    told = [said[i + 1] for i, text in enumerate(said) if text.startswith("Build the report")]
    if kind == "module":        # Snakemake runs no module's onsuccess: the user guide's command
        assert told == []
        words = ["snakemake", "--report", "results/report.html"]
    else:
        (line,) = told
        words = shlex.split(line)
        assert words[:2] == ["snakemake", "--report"] and "--directory" in words
    _snakemake(repo, cwd, *words[1:])
    text = (folder / words[2]).read_text()
    assert MARKER in text and "The module's clone's caption." not in text
