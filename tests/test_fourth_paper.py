"""A fourth paper added as docs/developer.md says: its own package, rule file and scripts, and
edits of four existing files only (its configuration section and schema, its stated values,
its citation). Snakemake plans its jobs, its figure job and its rows in the comparison with no
other file changed: the workflow finds the papers from the configuration."""

import subprocess

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
    "workflow/scripts/d_response.py": '"""Rule d_response."""\n',
    "workflow/scripts/d_reproduced_values.py": '"""Rule d_reproduced_values."""\n',
}

#: The existing files it edits, and what it adds to each.
EDITS = {
    "config/config.yaml": "paper_d:\n  omega: 1.0   # toy\n",
    "config/schema.yaml": "",       # below: a property of its own
    "data/paper_values.csv": "D,Fig 1,peak,m,1.0,printed,no,the peak response,,,\n",
    "data/papers.yaml": "D:\n  title: A toy paper\n  citation: A toy paper.\n"
                        "  summary: Shows how a paper is added.\n",
}


def test_a_fourth_paper_touches_four_existing_files(tmp_path):
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
    for name, text in EDITS.items():
        (work / name).write_text((work / name).read_text() + text)
    schema = work / "config/schema.yaml"
    schema.write_text(schema.read_text().replace(
        "\nproperties:\n", "\nproperties:\n  paper_d:\n    type: object\n"
        "    additionalProperties: false\n"
        "    properties:\n      omega: {$ref: '#/$defs/positive'}\n", 1))

    changed = [name for name in tracked
               if (work / name).read_bytes() != (ROOT / name).read_bytes()]
    assert sorted(changed) == sorted(EDITS)
    plan = snakemake(work, "-n", "-j1", "--forceall", "--quiet", "rules").stdout
    for rule in ("d_response", "figures_d_fig1", "d_reproduced_values", "comparison"):
        assert rule in plan, plan
    comparison = snakemake(work, "-n", "-j1", "--forceall", "comparison").stdout
    assert "results/paper_d/reproduced.csv" in comparison
