"""The first-look configuration (config/first_look/config.yaml, the tutorial's first run): it
validates over the paper configuration, writes to its own folder, and plans what its comments
say: paper C whole, the comparison and the report, nothing of the papers it leaves out."""

import re

import pytest

from conftest import ROOT
from rotorvib.pipeline.config import ConfigError, check_files

FIRST_LOOK = ROOT / "config/first_look/config.yaml"
FILES = ["--configfile", "config/config.yaml", "config/first_look/config.yaml"]
#: A dry run's table of planned jobs: "rule  count".
PLANNED = re.compile(r"^(\w+)\s+(\d+)$", re.M)


def _plan(run) -> dict[str, int]:
    assert run.returncode == 0, run.stdout + run.stderr
    return {rule: int(n) for rule, n in PLANNED.findall(run.stdout + run.stderr)
            if rule != "total"}


def test_the_first_look_validates_and_keeps_the_sections_of_the_papers_it_runs():
    checked = check_files([ROOT / "config/config.yaml", FIRST_LOOK], ROOT / "config/schema.yaml")
    assert checked["papers"] == ["c"] and checked["results"] == "results/first_look"
    assert "paper_c" in checked and "paper_a" not in checked and "paper_b" not in checked


def test_the_first_look_plans_what_it_says(snakemake_here):
    """Fewer jobs than the paper configuration, none of a paper left out, every one of paper
    C's, the comparison and the report's; the file's comments name the papers it leaves out."""
    fresh = ["-n", "--forceall"]
    paper = _plan(snakemake_here(*fresh, "--config", "results=results/first-look-check"))
    first = _plan(snakemake_here(*fresh, *FILES))
    assert sum(first.values()) < sum(paper.values()) / 2
    assert not [rule for rule in first if rule.startswith(("a_", "b_", "figures_a", "figures_b"))]
    assert {rule for rule in paper if rule.startswith(("c_", "figures_c"))} <= set(first)
    assert {"comparison", "report_text", "report_results"} <= set(first)
    comments = " ".join(line.lstrip("# ") for line in FIRST_LOOK.read_text().splitlines()
                        if line.startswith("#"))
    assert "What it leaves out: papers A and B" in comments


def test_key_papers_names_papers_that_have_sections(tmp_path):
    """Every section is kept where key ``papers`` is absent; a paper named without a section is
    refused naming the key."""
    every = check_files([ROOT / "config/config.yaml"], ROOT / "config/schema.yaml")
    assert {"paper_a", "paper_b", "paper_c"} <= set(every) and "papers" not in every
    wrong = tmp_path / "wrong.yaml"
    wrong.write_text("papers: [c, e]\n")
    with pytest.raises(ConfigError, match="config key 'papers': paper 'e' has no section"):
        check_files([ROOT / "config/config.yaml", wrong], ROOT / "config/schema.yaml")
