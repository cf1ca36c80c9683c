"""The findings page (docs/papers.md) and the README's totals are written by the run that backs
them: the template filled from the recorded comparison of a paper-configuration run, no number
or verdict typed by hand, and the record equal to a paper run's comparison where one is here."""

import pytest

from conftest import ROOT
from rotorvib.pipeline import findings
from rotorvib.pipeline.readme import BEGIN, END, totals_block

TEMPLATE = findings.TEMPLATE.read_text(encoding="utf-8")
RECORD = findings.read_record(findings.RECORD)


def test_the_page_is_its_template_filled_from_the_recorded_run():
    assert findings.PAGE.read_text(encoding="utf-8") == findings.render(TEMPLATE, RECORD), \
        "regenerate: python -m rotorvib.pipeline.findings"


def test_the_readme_totals_are_the_recorded_runs():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = readme[readme.index(BEGIN):readme.index(END) + len(END)]
    assert block == totals_block([dict(row) for row in RECORD.values()])


def test_the_template_types_no_number_and_no_verdict():
    """Every number and verdict of the findings is a placeholder; references to the paper
    (figures, tables, equations, sections, ICs) and code in backticks are not findings."""
    assert findings.typed(TEMPLATE) == []
    assert findings.typed("Fig 7's time is 5.98 s, SUPPORTED") == ["5.98"]
    assert findings.typed("## What the reproduction found\nit is SUPPORTED") == ["SUPPORTED"]
    assert findings.typed("Figs 2–3 and 8–14, eq. (41), Table 2, section 9, IC3, ref. [8], "
                          "`paper_b.ga.seed: 0`, (7)–(9)") == []


def test_the_record_is_the_paper_runs_comparison_where_one_is_here():
    """After a run of the paper configuration in this checkout, its comparison is the record
    (as the README's totals are: tests/test_readme.py)."""
    comparison = ROOT / "results/comparison.csv"
    if not comparison.is_file():
        pytest.skip("no run of the paper configuration in this checkout")
    assert findings.read_record(comparison) == RECORD, \
        "record the run: python -m rotorvib.pipeline.findings results/comparison.csv"


def test_a_changed_number_or_verdict_changes_the_page():
    """The page follows the record: a number or verdict moved in the comparison moves the page,
    so a page not regenerated fails the test above and the docs build."""
    rows = {key: dict(row) for key, row in RECORD.items()}
    rows[("B", "fig7_balance_time")]["reproduced"] = "7.5"
    rows[("B", "ics_typical")]["verdict"] = "SUPPORTED"
    page = findings.render(TEMPLATE, rows)
    assert page != findings.render(TEMPLATE, RECORD)
    assert "7.50 s (MAJOR)" in page and "random (SUPPORTED)" in page


def test_placeholders_name_a_row_a_field_and_a_format():
    rows = {("B", "t"): {"paper_value": "9.04", "reproduced": "5.9797", "rel_error": "0.3385",
                         "verdict": "MAJOR", "margin": "-0.5", "uncertainty": "",
                         "alternatives": "consistent: 6.835"}}
    text = ("{{B.t.reproduced:.2f}} {{B.t.verdict}} {{B.t.rel_error:.0%}} "
            "{{B.t.alt[consistent]:.3g}} {{B.t.-margin:.1f}}")
    assert findings.render(text, rows).endswith("5.98 MAJOR 34% 6.83 0.5")
    for bad, why in (("{{B.u.reproduced}}", "no row B u"), ("{{B.t.size}}", "unknown field"),
                     ("{{B.t.uncertainty}}", "has no uncertainty"),
                     ("{{B.t.alt[printed]}}", "no variant 'printed'")):
        with pytest.raises(ValueError, match=why):
            findings.render(bad, rows)
