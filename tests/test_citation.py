"""CITATION.cff is valid Citation File Format 1.2.0, checked by the format's own validator
(cffconvert, installed into a temporary directory: its ``jsonschema<4`` pin conflicts with the
project's), and agrees with the package metadata."""

import os
import subprocess
import sys
import tomllib

import pytest
import yaml

from conftest import ROOT


@pytest.fixture(scope="module")
def cffconvert(tmp_path_factory):
    target = tmp_path_factory.mktemp("cffconvert")
    install = subprocess.run([sys.executable, "-m", "pip", "install", "--quiet",
                              "--disable-pip-version-check", "--target", str(target),
                              "cffconvert==2.0.0"], capture_output=True, text=True)
    assert install.returncode == 0, install.stderr

    def validate(path):
        return subprocess.run([sys.executable, "-c", "from cffconvert.cli.cli import cli; cli()",
                               "--validate", "-i", str(path)], capture_output=True, text=True,
                              env={**os.environ, "PYTHONPATH": str(target)})

    return validate


def test_citation_file_is_valid_cff(cffconvert):
    run = cffconvert(ROOT / "CITATION.cff")
    assert run.returncode == 0 and "valid according to schema version 1.2.0" in run.stdout, (
        run.stdout + run.stderr)


def test_the_validator_rejects_a_citation_without_authors(cffconvert, tmp_path):
    broken = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    del broken["authors"]
    path = tmp_path / "CITATION.cff"
    path.write_text(yaml.safe_dump(broken))
    assert cffconvert(path).returncode != 0


def test_citation_agrees_with_the_package():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert cff["version"] == project["version"]
    assert cff["license"] == project["license"]["text"]


def test_the_release_is_the_changelogs_newest_and_every_paper_is_cited():
    """CITATION.cff's version and date are the newest entry of docs/changelog.md, and its
    references are the papers of data/papers.yaml, by title."""
    import re

    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    newest = re.search(r"^## (\S+) — (\d{4}-\d{2}-\d{2})$",
                       (ROOT / "docs/changelog.md").read_text(), re.M)
    assert (cff["version"], str(cff["date-released"])) == newest.groups()
    papers = yaml.safe_load((ROOT / "data/papers.yaml").read_text())

    def words(text):
        return " ".join(text.split()).lower()

    assert sorted(words(r["title"]) for r in cff["references"]) == sorted(
        words(p["title"]) for p in papers.values())
