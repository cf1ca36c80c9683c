"""The library's fingerprints and provenance come from where its code is, never from the working
folder: a project that uses the workflow as a module runs Snakemake in a git work tree of its
own (before, the fingerprints there were the SHA-256 of nothing and the datasets named the
caller's commit)."""

import hashlib
import shutil
import subprocess

import pytest

from conftest import ROOT
from rotorvib.io import provenance
from rotorvib.io.provenance import code_origin, code_state, git_date
from rotorvib.pipeline.fingerprint import code_fingerprint, forget_modules, import_closure

SCRIPT = ROOT / "workflow/scripts/b_balance_law.py"


def git(cwd, *args) -> str:
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True,
                          env={"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
                               "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t",
                               "GIT_COMMITTER_DATE": "2001-02-03T04:05:06+00:00",
                               "GIT_AUTHOR_DATE": "2001-02-03T04:05:06+00:00",
                               "HOME": str(cwd)}).stdout.strip()


@pytest.fixture
def elsewhere(tmp_path, monkeypatch):
    """A caller's project: a git work tree with a commit of its own, the working folder."""
    git(tmp_path, "init", "-q")
    git(tmp_path, "commit", "-q", "--allow-empty", "-m", "the caller's")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_a_scripts_fingerprint_is_its_code_s_from_any_folder(elsewhere):
    forget_modules()
    closure = import_closure(SCRIPT)
    assert "rotorvib.papers.b.law" in closure and len(closure) > 20
    assert code_fingerprint(str(SCRIPT)) == code_fingerprint(str(SCRIPT), root=ROOT / "src")
    assert code_fingerprint(str(SCRIPT)) != hashlib.sha256().hexdigest()   # not of nothing


def test_the_commit_recorded_is_the_librarys_not_the_callers(elsewhere):
    if code_origin() != "git checkout":
        pytest.skip("the package under test is not a git checkout")
    commit, _, origin = code_state()
    assert origin == "git checkout" and commit == git(provenance.PACKAGE_DIR, "rev-parse", "HEAD")
    assert commit != git(elsewhere, "rev-parse", "HEAD")
    assert git_date() == git(provenance.PACKAGE_DIR, "log", "-1", "--format=%cI")


def test_a_copy_in_another_projects_work_tree_is_an_untracked_copy(elsewhere, monkeypatch):
    """A package whose files the work tree around it does not track (a wheel in a virtual
    environment inside the caller's project) names no commit, and says so."""
    package = elsewhere / ".venv/site-packages/rotorvib"
    shutil.copytree(ROOT / "src/rotorvib/io", package)
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    assert code_state(package) == ("unknown", False, "untracked copy")
    assert git_date(package) == "1970-01-01T00:00:00+00:00"
    git(elsewhere, "add", "-f", ".venv")
    git(elsewhere, "commit", "-q", "-m", "vendored")
    assert code_state(package) == (git(elsewhere, "rev-parse", "HEAD"), False, "git checkout")
    assert git_date(package) == "2001-02-03T04:05:06+00:00"
