"""A fourth paper added as docs/developer.md says: its own package, rule file and scripts, and
edits of the seven existing files the guide lists (its configuration section and schema, its
stated values, its citation in data/papers.yaml, the README and CITATION.cff, the layout of the
architecture page). Snakemake plans its jobs, its figure job and its rows in the comparison,
and the library's checks a new paper touches pass on it."""

import os
import re
import subprocess
import sys

from conftest import ROOT
from workflow_runs import snakemake

#: The new files of a toy paper D: one dataset, one figure drawn from it, one claim.
NEW_FILES = {
    "src/rotorvib/papers/d/__init__.py": '"""Paper D: a toy paper, added as one is."""\n',
    "src/rotorvib/papers/d/outputs.py": '''"""Paper D's outputs."""
from rotorvib.papers.outputs import figure

UNDRAWN_DATASETS = ()
NOTES = ()


def figures(d: dict) -> dict:
    """Its one figure."""
    return {"fig1": figure("fig1", {"resp": "response"}, "The response over the speed.")}


def tables(d: dict) -> dict:
    """No table."""
    return {}
''',
    "src/rotorvib/papers/d/config_checks.py": '''"""Paper D's checks beyond the schema."""


def problems(d: dict) -> list:
    """None."""
    return []
''',
    "src/rotorvib/papers/d/figures.py": '''"""Paper D's figures."""


def fig1(resp, paper, **options):
    """The response."""
''',
    "workflow/rules/paper_d.smk": '''# Paper D: a toy paper.
D = config["paper_d"]


rule d_response:
    output:
        dataset("d", "response"),
    log:
        logs("d_response"),
    benchmark:
        benchmarks("d_response")
    priority: COMPUTES
    localrule: True
    params:
        omega=D["omega"],
    script:
        "../scripts/d_response.py"


rule d_reproduced_values:
    input:
        resp=rules.d_response.output[0],
        paper_values=PAPER_VALUES,
    output:
        reproduced_file("d"),
    log:
        logs("d_reproduced_values"),
    localrule: True
    script:
        "../scripts/d_reproduced_values.py"
''',
    "workflow/scripts/d_response.py": '"""Rule d_response."""\n\n'
    "from rotorvib.pipeline import job  # first\n\njob.start(snakemake.log[0])\n",
    "workflow/scripts/d_reproduced_values.py": '"""Rule d_reproduced_values."""\n\n'
    "from rotorvib.pipeline import job  # first\n\njob.start(snakemake.log[0])\n",
}


def _before(text: str, anchor: str, added: str) -> str:
    """``text`` with ``added`` inserted before the first ``anchor``."""
    assert anchor in text, anchor
    return text.replace(anchor, added + anchor, 1)


#: The existing files it edits, as the developer guide lists them, and each edit.
EDITS = {
    "config/config.yaml": lambda t: t + "paper_d:\n  omega: 1.0   # toy\n",
    "config/schema.yaml": lambda t: t.replace(
        "\nproperties:\n", "\nproperties:\n  paper_d:\n    type: object\n"
        "    additionalProperties: false\n"
        "    properties:\n      omega: {$ref: '#/$defs/positive'}\n", 1),
    "data/paper_values.csv": lambda t: t + "D,Fig 1,peak,m,1.0,printed,no,the peak response,,,\n",
    "data/papers.yaml": lambda t: t + "D:\n  title: A toy paper\n  citation: A toy paper.\n"
                                      "  summary: Shows how a paper is added.\n",
    "README.md": lambda t: _before(
        t, "\n## What it found", "- **D.** A toy paper. *Summary:* Shows how a paper is added.\n"),
    "CITATION.cff": lambda t: t + "  - type: article\n    title: A toy paper\n"
                                  "    authors:\n      - name: anonymous\n",
    "docs/architecture.md": lambda t: _before(t, "  papers/c/", "  papers/d/               a toy "
                                              "paper: config_checks, outputs, figures\n"),
}

#: The library's checks a new paper touches: its citation, the README, the layout (its package,
#: its scripts), the docs' layout, the papers the console names, the recorded findings.
CHECKS = [
    "tests/test_citation.py::test_the_release_is_the_changelogs_newest_and_every_paper_is_cited",
    "tests/test_readme.py::test_the_readme_reads_in_five_minutes",
    "tests/test_readme.py::test_readme_cites_the_papers_as_data_papers_yaml_does",
    "tests/test_readme.py::test_the_readme_totals_are_generated_from_the_paper_configuration",
    "tests/test_layout.py",
    "tests/test_docs.py::test_the_layout_names_every_package_and_module",
    "tests/test_console.py::test_the_papers_left_out_come_from_the_schema",
    "tests/test_findings.py",
]


def guide_lists() -> list[str]:
    """The existing files the developer guide's step 3 of "Adding a fourth paper" names."""
    guide = (ROOT / "docs/developer.md").read_text()
    step = re.search(r"^3\. \*\*(\w+) existing files\*\*.*?(?=^4\. )", guide, re.M | re.S)
    return sorted(set(re.findall(r"`([\w./-]+\.\w+)`", step.group(0))))


def test_a_fourth_paper_as_the_guide_says_plans_and_passes_the_checks_it_touches(tmp_path):
    tracked = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                             cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    tracked = [name for name in tracked if (ROOT / name).is_file()]
    work = tmp_path / "repo"
    for name in tracked:
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_bytes((ROOT / name).read_bytes())
    for name, text in NEW_FILES.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_text(text)
    for name, edit in EDITS.items():
        (work / name).write_text(edit((work / name).read_text()))

    changed = [name for name in tracked
               if (work / name).read_bytes() != (ROOT / name).read_bytes()]
    assert sorted(changed) == sorted(EDITS) == sorted(guide_lists())
    assert "3. **Seven existing files**" in (ROOT / "docs/developer.md").read_text()
    assert len(EDITS) == 7
    plan = snakemake(work, "-n", "-j1", "--forceall", "--quiet", "rules").stdout
    for rule in ("d_response", "figures_d_fig1", "d_reproduced_values", "comparison"):
        assert rule in plan, plan
    comparison = snakemake(work, "-n", "-j1", "--forceall", "comparison").stdout
    assert "results/paper_d/reproduced.csv" in comparison
    checks = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-n", "0", *CHECKS],
        cwd=work, capture_output=True, text=True,
        env=os.environ | {"PYTHONPATH": str(work / "src")})
    assert checks.returncode == 0, checks.stdout[-3000:]
