"""The report's words (rotorvib.report): rendered through docutils and Jinja2 exactly as
Snakemake renders captions, they must give no system message and say what the rows say."""

import jinja2
import pytest
from docutils.core import publish_parts
from docutils.utils import Reporter

from rotorvib import report

# Snakemake appends link targets for each category to every caption and to the landing page.
LINKS = "\n\n" + "\n".join(f".. _{name}: javascript:app.showCategory('{name}')"
                          for name in ("Paper A", "Paper B", "Paper C", "Comparison")) + "\n"


def html(rst: str) -> str:
    """``rst`` as HTML; any docutils warning or error raises instead of becoming a box."""
    return publish_parts(rst + LINKS, writer="html",
                         settings_overrides={"halt_level": Reporter.WARNING_LEVEL,
                                             "report_level": Reporter.WARNING_LEVEL})["html_body"]


def row(paper="B", item="Fig 8", quantity="q", verdict="MAJOR", paper_value="9.04",
        reproduced="5.98", rel_error="0.3385", unit="s", explanation="why"):
    return {"paper": paper, "item": item, "quantity": quantity, "unit": unit, "source": "printed",
            "paper_value": paper_value, "reproduced": reproduced, "rel_error": rel_error,
            "verdict": verdict, "explanation": explanation}


@pytest.mark.parametrize("text", ["|Theta(omega_n)|", "x_i * y_", "`a` [8] <b> \\c", "r_G_ d_1_"])
def test_markup_characters_come_through_as_text(text):
    body = html(f"Before {report.rst_text(text)} after.")
    assert f"Before {text.replace('<', '&lt;').replace('>', '&gt;')} after." in body


@pytest.mark.parametrize("name, numbers, label", [
    ("fig8", (8,), "Fig 8"), ("fig4_5", (4, 5), "Figs 4-5"), ("basin", (), "basin"),
    ("error_study", (), "error study")])
def test_output_names_give_the_paper_numbers_and_labels(name, numbers, label):
    assert report.numbers_of_name(name) == numbers
    assert report.label(name) == label


@pytest.mark.parametrize("item, expected", [
    ("Fig 7", ("figure", (7,))), ("Figs 8-10", ("figure", (8, 9, 10))),
    ("Table 2", ("table", (2,))), ("Section 9", ("", ())), ("eq. 41", ("", ()))])
def test_comparison_items_name_figures_and_tables(item, expected):
    assert report.numbers_of_item(item) == expected


def test_the_report_order_is_the_papers_then_the_outputs_beyond_it():
    names = ["fig2", "fig10", "basin", "fig4_5", "kinematics", "fig16"]
    declared = {name: i for i, name in enumerate(names)}
    others = {"basin": 0, "kinematics": 1}
    keys = {name: report.order_key(name, others.get(name, 0)) for name in declared}
    ordered = sorted(names, key=keys.get)  # the report compares the labels as strings
    assert ordered == ["fig2", "fig4_5", "fig10", "fig16", "basin", "kinematics"]


def test_rows_are_tied_to_every_figure_their_item_names_and_to_declared_items():
    table = [row(item="Figs 8-10", quantity="a"), row(item="Fig 8", quantity="b"),
             row(item="Fig 18", quantity="c"), row(item="GA", quantity="d"),
             row(paper="C", item="Fig 8", quantity="e"), row(item="Table 8", quantity="f")]
    assert [r["quantity"] for r in report.rows_for(table, "b", "fig8")] == ["a", "b"]
    assert [r["quantity"] for r in report.rows_for(table, "b", "fig9")] == ["a"]
    assert [r["quantity"] for r in report.rows_for(table, "b", "ga_convergence",
                                                   items=("GA",))] == ["d"]
    assert [r["quantity"] for r in report.rows_for(table, "b", "table8", "table")] == ["f"]


def test_a_caption_states_each_row_with_its_verdict_and_renders_cleanly():
    rows = [row(explanation="envelope | threshold *crossing*"),
            row(verdict="SUPPORTED", paper_value="", reproduced="", rel_error="", unit="",
                quantity="claim_q", explanation="holds under printed")]
    text = report.caption("Paper B, Fig 8", "Balance time against beta_i.", rows,
                          {("B", "q"): "balance time of the Fig 7 case"})
    body = html(text)
    assert "<strong>MAJOR</strong> (Fig 8) balance time of the Fig 7 case: paper 9.04 s, " \
           "reproduced 5.98 s (33.9 % off). envelope | threshold *crossing*" in body
    assert "<strong>SUPPORTED</strong> (Fig 8) claim_q. holds under printed" in body
    assert "Balance time against beta_i." in body
    assert "states no value" in html(report.caption("t", "shows", []))
    assert "states" not in html(report.caption("t", "shows"))


def test_a_caption_file_renders_as_written(tmp_path):
    """Snakemake renders each caption file as a Jinja template: the text comes out verbatim,
    braces included."""
    text = report.caption("Paper B, Fig 8", "Eight {{ x }} {% y %} {# z #}", [])
    report.write_caption(tmp_path / "fig8.rst", text)
    env = jinja2.Environment(trim_blocks=True, lstrip_blocks=True)  # as Snakemake's
    rendered = env.from_string((tmp_path / "fig8.rst").read_text()).render(snakemake=None)
    assert rendered == text


def test_the_landing_page_totals_and_findings_follow_the_rows():
    table = [row(paper="A", verdict="MATCH", quantity="a1", item="Fig 2"),
             row(paper="B", verdict="MAJOR", quantity="b1", rel_error="0.2",
                 explanation="first clause; second"),
             row(paper="B", verdict="MAJOR", quantity="b2", rel_error="0.5",
                 explanation="eq. (20) gives 3. Then more"),
             row(paper="B", verdict="NOT SUPPORTED", quantity="b3", item="Fig 6",
                 paper_value="", reproduced="", rel_error="", explanation="never settles")]
    papers = {p: {"citation": f"Citation {p}.", "summary": f"Summary {p}."} for p in "ABC"}
    text = report.landing_page(table, {("B", "b2"): "the b2 claim"}, papers, "discrepancies (1)")
    body = html(text)
    counts = report.verdict_counts(table)
    assert counts["B"]["MAJOR"] == 2 and counts["A"]["MATCH"] == 1
    assert "<strong>Paper B, Fig 8 (2 MAJOR)</strong> the b2 claim: paper 9.04 s, reproduced " \
           "5.98 s (50.0 % off). eq. (20) gives 3" in body  # the larger miss, its first clause
    assert "Then more" not in body and "first clause" not in body
    assert "<strong>Paper B, Fig 6 (1 NOT SUPPORTED)</strong> b3. never settles" in body
    assert "Paper A, Fig 2" not in body  # a MATCH is not a finding
    assert "Citation C. Summary C." in body
    assert body.count("javascript:app.showCategory") >= 3  # links into each paper


def test_check_counts_summarise_a_status_column():
    rows = [{"status": "PASS"}, {"status": "FAIL"}, {"status": "PASS"}]
    assert report.check_counts(rows) == " Checks: 1 FAIL, 2 PASS."
    assert report.check_counts([{"value": 1}]) == ""
