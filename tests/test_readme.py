"""The README: short, every command in it accepted, the papers cited as data/papers.yaml
cites them, no typed timing."""

import re
import shlex

import pytest

from conftest import ROOT
from rotorvib.papers.a.studies import REFERENCE as A
from rotorvib.papers.b.attributes import REFERENCE as B
from rotorvib.papers.c.broadband import REFERENCE as C_BROADBAND
from rotorvib.papers.c.studies import REFERENCE as C
from rotorvib.pipeline.config import load_yaml

README = (ROOT / "README.md").read_text()


def test_the_readme_reads_in_five_minutes():
    assert len(README.splitlines()) <= 200


def test_readme_cites_the_papers_as_data_papers_yaml_does():
    """The README's papers section quotes data/papers.yaml, the report's source."""
    text = " ".join(README.split())
    for paper in load_yaml(ROOT / "data/papers.yaml").values():
        assert " ".join(paper["citation"].split()) in text
        assert " ".join(paper["summary"].split()) in text


def _without_run_time(text: str) -> str:
    """The text without the README's generated run-time block (from the recorded benchmark)."""
    from rotorvib.pipeline.readme import RUN_TIME_BEGIN, RUN_TIME_END

    return re.sub(re.escape(RUN_TIME_BEGIN) + ".*?" + re.escape(RUN_TIME_END), "", text,
                  flags=re.S)


def test_readme_types_no_measured_time():
    """Timings are measured on the machine at hand by the benchmark scripts (benchmarks/), never
    typed into the README or the docs, where they would go stale with the next speed-up; the
    README's one timing is generated from the recorded cold run (its own test)."""
    for text in [_without_run_time(README)] + [p.read_text()
                                               for p in (ROOT / "docs").glob("*.md")]:
        typed = re.findall(r"\d[\d.,]*\s?(?:CPU-s|CPU seconds|s of wall|(?:ms|s) (?:a|per) run"
                           r"|[x×] (?:faster|slower)|minutes? on)", text)
        assert typed == []


def _snakemake_commands() -> list[list[str]]:
    commands = []
    for block in re.findall(r"```bash\n(.*?)```", README, re.S):
        for line in block.splitlines():
            words = shlex.split(line.split("  #")[0].strip(), comments=True)
            if words and words[0] == "snakemake" and "--report" not in words:
                commands.append(words)
    return commands


@pytest.mark.parametrize("words", _snakemake_commands(), ids=" ".join)
def test_each_readme_snakemake_command_is_accepted(words, tmp_path, snakemake_here):
    """Each snakemake command of the README is accepted as written (a dry run; the tests run
    the workflow, the report, the archive and the SLURM profile for real), ``my.yaml`` being
    the override file the README writes."""
    override = tmp_path / "my.yaml"
    override.write_text("paper_c:\n  den_hartog:\n    d: 0.09\n")
    words = [str(override) if w == "my.yaml" else w for w in words]
    run = snakemake_here(*words[1:], "-n")
    assert run.returncode == 0, run.stdout + run.stderr


def test_every_dataset_cites_its_paper_as_data_papers_yaml_does():
    """The ``references`` of every dataset open with the paper's title as data/papers.yaml
    gives it, and say no more of its journal than that file does."""
    papers = load_yaml(ROOT / "data/papers.yaml")
    for letter, references in (("A", [A]), ("B", [B]), ("C", [C, C_BROADBAND])):
        for reference in references:
            assert reference.startswith(f"Paper {letter}: {papers[letter]['title']}"), reference
    assert "Journal" not in C and "Modares Mechanical Engineering 14(3)" in B


def test_the_workflow_catalog_usage_runs(snakemake_here):
    """.snakemake-workflow-catalog.yml: no conda or container deployment (the set-up
    installs the project itself), a report, and its mandatory flags give a workflow that a dry
    run accepts."""
    catalog = load_yaml(ROOT / ".snakemake-workflow-catalog.yml")["usage"]
    assert catalog["report"] is True
    assert not any(catalog["software-stack-deployment"].values())
    flags = shlex.split(catalog["mandatory-flags"]["flags"])
    run = snakemake_here("-n", *flags)
    assert run.returncode == 0, run.stdout + run.stderr
    assert (ROOT / "config/README.md").is_file()


def test_the_readme_totals_are_generated_from_the_paper_configuration():
    """The README's verdict totals sit between the generator's markers, name every verdict
    group with as many rows as data/paper_values.csv gives the papers of the recorded paper
    run (rotorvib.pipeline.findings), and -- where a run of the paper
    configuration has left results/comparison.csv -- are exactly what the generator writes
    from it (after a change: snakemake -j2 comparison, then python -m
    rotorvib.pipeline.readme results/comparison.csv README.md)."""
    from rotorvib.comparison.paper_values import read_paper_values
    from rotorvib.comparison.verdicts import VERDICT_GROUPS, group_of
    from rotorvib.pipeline import findings
    from rotorvib.pipeline.readme import BEGIN, END, read_table, totals_block, with_totals

    block = README[README.index(BEGIN):README.index(END) + len(END)]
    # the rows of the papers the recorded paper run compared (a paper added since counts from
    # the next recorded run on: docs/developer.md)
    recorded = {row["paper"] for row in findings.read_record(findings.RECORD).values()}
    values = [v for v in read_paper_values(ROOT / "data/paper_values.csv")
              if v["paper"] in recorded]
    assert recorded
    shown = {name: int(re.search(rf"^- {re.escape(name)} \((\d+) rows?, ", block, re.M).group(1))
             for name, _ in VERDICT_GROUPS}
    # a calibrated row leaves its group (which the paper-values file gives) for its own
    calibrated, *_ = VERDICT_GROUPS[-1]
    missing = 0
    for name, _ in VERDICT_GROUPS[:-1]:
        rows = sum(group_of({"paper_value": v["value"], "source": v["source"]}) == name
                   for v in values)
        assert shown[name] <= rows, name
        missing += rows - shown[name]
    assert missing == shown[calibrated]
    comparison = ROOT / "results/comparison.csv"
    if comparison.is_file():
        assert block == totals_block(read_table(comparison)), "regenerate the README's totals"
    with pytest.raises(ValueError, match="markers missing"):
        with_totals("no block here", [])


def test_the_readme_run_time_is_generated_from_the_recorded_cold_run():
    """The README's expected run time is the block the generator writes from
    benchmarks/records/cold_run.json (python -m benchmarks.cold_run --record), a commit of this
    repository's history, two cores as the README's command asks; and without its markers the
    generator refuses."""
    import json
    import subprocess

    from rotorvib.pipeline.readme import (
        RUN_TIME_BEGIN,
        RUN_TIME_END,
        RUN_TIME_RECORD,
        run_time_block,
        with_run_time,
    )

    record = json.loads((ROOT / RUN_TIME_RECORD).read_text())
    block = README[README.index(RUN_TIME_BEGIN):README.index(RUN_TIME_END) + len(RUN_TIME_END)]
    assert block == run_time_block(record), "regenerate the README (python -m rotorvib.pipeline.readme)"
    assert record["cores"] == 2 and 0 < record["wall_s"] <= record["cpu_s"]
    known = subprocess.run(["git", "cat-file", "-e", f"{record['commit']}^{{commit}}"],
                           cwd=ROOT, capture_output=True)
    assert known.returncode == 0 or not (ROOT / ".git").exists(), record["commit"]
    with pytest.raises(ValueError, match="markers missing"):
        with_run_time("no block here", record)
