"""The report's words (rotorvib.pipeline.report): rendered through docutils and Jinja2 exactly as
Snakemake renders captions, they must give no system message and say what the rows say."""

import jinja2
import pytest
from docutils.core import publish_parts
from docutils.utils import Reporter

from rotorvib.comparison.table import with_findings
from rotorvib.pipeline import report

# Snakemake appends link targets for each category to every caption and to the landing page.
LINKS = "\n\n" + "\n".join(f".. _{name}: javascript:app.showCategory('{name}')"
                          for name in report.categories("abc").values()) + "\n"


def html(rst: str) -> str:
    """``rst`` as HTML; any docutils warning or error raises instead of becoming a box."""
    return publish_parts(rst + LINKS, writer="html",
                         settings_overrides={"halt_level": Reporter.WARNING_LEVEL,
                                             "report_level": Reporter.WARNING_LEVEL})["html_body"]


def row(paper="B", item="Fig 8", quantity="q", verdict="MAJOR", paper_value="9.04",
        reproduced="5.98", rel_error="0.3385", unit="s", explanation="why", margin=""):
    """A row of results/comparison.csv as the report reads it (text cells); ``margin`` is
    ``(value, uncertainty, unit, basis)`` for a claim."""
    return {"paper": paper, "item": item, "quantity": quantity, "unit": unit, "source": "printed",
            "paper_value": paper_value, "reproduced": reproduced, "rel_error": rel_error,
            "verdict": verdict, "explanation": explanation,
            **dict(zip(("margin", "uncertainty", "margin_unit", "margin_basis"),
                       margin or ("", "", "", "")))}


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


def test_the_report_lists_sort_in_the_papers_order_and_read_as_labels():
    """The report sorts a list by its labels as strings: a figure space pads the numbers below
    10, which a browser's localeCompare collates before the digits (the order is checked in
    Chromium, test_delivery.py); each label reads as the output."""
    labels = {name: report.entry_label(name, "figure", ("GA", "Section 9"))
              for name in ("fig2", "fig4_5", "fig10", "ga_convergence")}
    assert labels["fig2"] == "Fig \u20072" and labels["fig10"] == "Fig 10"
    assert labels["fig4_5"] == "Fig \u20074\u20135"
    assert labels["ga_convergence"] == "GA convergence (section 9)"
    assert report.entry_label("uncertainty_table2", "figure") == "Uncertainty Table 2"
    assert report.entry_label("table1", "table") == "Table \u20071"


def test_outputs_beyond_the_paper_have_their_own_subcategory():
    assert report.subcategory("Beyond the paper: the basin.", "figure") == "3 Beyond the paper"
    assert report.subcategory("Balance time against beta.", "figure") == "1 Figures"
    assert report.subcategory("Table 2 beside the GA.", "table") == "2 Tables"


def test_the_categories_sort_in_the_storys_order():
    """Snakemake's sidebar sorts by name (localeCompare): the numbered names sort as the story
    goes, summary, papers, comparison, for any number of papers."""
    assert list(report.categories("abc").values()) == [
        "1 Summary", "2 Paper A", "3 Paper B", "4 Paper C", "5 Comparison"]
    named = list(report.categories("abcdefghijk").values())
    assert named[0] == "01 Summary" and named[-1] == "13 Comparison" and sorted(named) == named


def test_a_declaration_names_the_outputs_whose_cases_it_draws():
    assert report.names_in("the three (beta, m) cases of Table 2, as in Figs 8-10") == {
        "table2", "fig8", "fig9", "fig10"}
    assert report.names_in("the basin map") == set()


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
    rows = [row(explanation="printed: envelope | consistent: threshold *crossing*"),
            row(verdict="SUPPORTED", paper_value="", reproduced="", rel_error="", unit="",
                quantity="claim_q", explanation="holds under printed",
                margin=("0.25", "0.01", "s", "half the range over 5 seeds"))]
    text = report.caption("Paper B, Fig 8", "Balance time against beta_i.", rows,
                          {("B", "q"): "balance time of the Fig 7 case"})
    body = html(text)
    assert "<strong>MAJOR</strong> (Fig 8) balance time of the Fig 7 case: paper 9.04 s, " \
           "reproduced 5.98 s (33.9 % off). printed: envelope; consistent: threshold *crossing*" in body
    assert "<strong>SUPPORTED</strong> (Fig 8) claim_q: margin +0.25 +/- 0.01 (s; half the " \
           "range over 5 seeds). holds under printed" in body
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


def test_the_summary_and_the_landing_page_follow_the_rows():
    """One bullet per finding (rows of one cause: the same explanation but for its numbers),
    its largest miss stated whole; totals count rows and findings."""
    table = with_findings([
        row(paper="A", verdict="MATCH", quantity="a1", item="Fig 2"),
        row(paper="B", verdict="MAJOR", quantity="b1", rel_error="0.2",
            explanation="eq. (20) gives 2. Then more"),
        row(paper="B", verdict="MAJOR", quantity="b2", rel_error="0.5", item="Fig 9",
            explanation="eq. (20) gives 3. Then more"),
        row(paper="B", verdict="NOT SUPPORTED", quantity="b3", item="Fig 6",
            paper_value="", reproduced="", rel_error="",
            explanation="not under printed, consistent: printed: share 0.3 | consistent: "
                        "share 0.4")])
    papers = {p: {"title": f"Title {p}", "citation": f"Citation {p}.", "summary": f"Summary {p}."}
              for p in "ABC"}
    body = html(report.summary_text(table, {("B", "b2"): "the b2 claim"}, papers,
                                    "discrepancies (1)"))
    counts = report.verdict_counts(table)
    assert counts["B"]["MAJOR"] == 2 and counts["A"]["MATCH"] == 1
    assert "<strong>Paper B, finding B1: Fig 8, Fig 9 (2 rows, MAJOR)</strong> the b2 claim: " \
           "paper 9.04 s, reproduced 5.98 s (50.0 % off). eq. (20) gives 3. Then more" in body
    assert "gives 2" not in body                      # one bullet for the two rows
    assert "<strong>Paper B, finding B2: Fig 6 (1 row, NOT SUPPORTED)</strong> b3. not under " \
           "printed, consistent: printed: share 0.3; consistent: share 0.4" in body
    assert "Paper A" not in body.split("Findings")[1].split("Papers")[0]  # a MATCH is none
    assert "Citation C. Summary C." in body and "discrepancies (1)" in body
    landing = html(report.landing_page(table, papers))
    assert "4 stated values and claims" in landing
    assert ("printed numbers (3 rows, 2 findings): MATCH 1 (1 finding), MINOR 0, MAJOR 2 "
            "(1 finding)") in landing
    assert "Title C" in landing and "Citation C" not in landing
    assert landing.count("javascript:app.showCategory") == 5  # summary, comparison, papers


def test_check_counts_summarise_a_status_column():
    rows = [{"status": "PASS"}, {"status": "FAIL"}, {"status": "PASS"}]
    assert report.check_counts(rows) == " Checks: 1 FAIL, 2 PASS."
    assert report.check_counts([{"value": 1}]) == ""
