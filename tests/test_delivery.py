"""What a user opens from a reduced run (tests/workflow_runs.py): the report in a real browser
(headless Chromium), under every profile the repository ships. What a user keeps, the
archive, is test_archive_runs.py (a file of its own, so that the two pytest-xdist workers share
the tests that read the runs)."""

import csv
import html
import re
from pathlib import Path

import pytest

import report_browser
from conftest import ROOT
from rotorvib.comparison.paper_values import decimals
from rotorvib.pipeline.report import SUBCATEGORIES, numbers_of_item, numbers_of_name
from rotorvib.pipeline.report import categories as report_categories
from workflow_runs import REDUCED, copy_run, snakemake

pytestmark = pytest.mark.workflow


@pytest.fixture(scope="module")
def report(run_dir, tmp_path_factory) -> Path:
    """`snakemake --report` of a copy of the reduced run, as the README says to open it."""
    work = copy_run(run_dir, tmp_path_factory.mktemp("report") / "work")
    snakemake(work, "--report", "results/report.html", *REDUCED)
    return work / "results/report.html"


#: Every profile the repository ships, as a command names it (none: the default profile).
PROFILES = {"default": [], "slurm": ["--workflow-profile", "profiles/slurm"]}


def test_the_landing_page_reads_from_its_first_line(report, browser):
    """At three window sizes, the report (built under every shipped profile: a
    --workflow-profile replaces the default one) opens with its title and the verdict totals
    inside the window (nothing above or left of it, where no scroll bar reaches), beside the rule
    graph and not under it, and lists its categories in the story's order; a screenshot of each
    is kept (report_browser.SCREENSHOTS)."""
    work = report.parents[1]
    for profile, options in PROFILES.items():
        built = work / f"results/report_{profile}.html"
        snakemake(work, "--report", str(built.relative_to(work)), *REDUCED, *options)
        for width, height in report_browser.SIZES:
            shot = report_browser.SCREENSHOTS / f"landing_{profile}_{width}x{height}.png"
            seen = report_browser.landing(browser, built, width, height, shot)
            for part in (seen.title, seen.totals):
                left, top, right, bottom = part
                assert left >= 0 and top >= 0 and right <= width and bottom <= height, (
                    profile, seen, part)
            assert seen.description[2] <= seen.rule_graph[0], (profile, seen)
        assert report_browser.sidebar(browser, built) == list(
            report_categories(papers_of_run(work)).values())


def _numbers_as_precise_as_they_can_tell(cells: list[list[str]]):
    """The comparison as a reader sees it: the paper's value and ours, the error and the verdict
    among the first eight columns (inside a 1280 px window), every reproduced value to at most
    two decimals more than the paper's, every other number to at most four significant digits
    (the CSV download carries every digit)."""
    head, *rows = cells
    assert {"paper value", "reproduced", "relative error", "verdict"} <= set(head[:8]), head
    paper, ours = head.index("paper value"), head.index("reproduced")
    for row in rows:
        for k, cell in enumerate(row):
            if not re.fullmatch(r"-?\d+(\.\d+)?(e[-+]\d+)?", cell) or k == paper:
                continue
            if k == ours and row[paper]:
                assert decimals(cell) <= decimals(row[paper]) + 2, (row[paper], cell)
            else:
                assert len(re.sub(r"e.*|[-.]", "", cell).strip("0")) <= 4, (head[k], cell)


def test_every_view_of_the_report_opens_and_shows_its_result(report, browser):
    """Every category of the sidebar, every subcategory and every result's view button, clicked
    as a reader does: no page error, every figure shown as an image, every table as an HTML
    table with all its rows, each paper's figures and tables in the paper's order, and each
    figure's caption stating its own comparison rows and no other figure's."""
    work = report.parents[1]
    categories, views, lists = report_browser.every_view(browser, report)
    named = report_categories(papers_of_run(work))
    assert report_browser.sidebar(browser, report) == list(named.values())  # the story's order
    assert set(categories) == set(named.values())
    assert [view for view in views if view.errors or not view.kind] == []
    figures = list((work / "results").glob("paper_*/figures/*.png"))
    assert sum(view.kind == "img" and view.image_width >= 800 for view in views) == len(figures)
    tables = {view.path[-1]: view for view in views if view.kind == "html"}
    comparison = read_comparison(work / "results/comparison.csv")
    assert tables["Comparison"].table_rows == len(comparison)
    assert tables["Discrepancies"].table_rows == len(
        read_comparison(work / "results/discrepancies.csv"))
    assert f"{len(comparison)} values and claims" in tables["Verdicts and findings"].text
    _numbers_as_precise_as_they_can_tell(tables["Comparison"].cells)
    assert "Findings" in tables["Verdicts and findings"].text
    table2 = sorted((work / "results").glob("paper_*/tables/table2.csv"))
    assert table2
    for csv_path in table2:
        paper = csv_path.parents[1].name.removeprefix("paper_")
        shown = [v for v in views if v.path[:2] == (named[f"Paper {paper.upper()}"],
                                                     SUBCATEGORIES["Tables"])
                 and v.path[-1] == "Table \u20072"]
        assert [v.table_rows for v in shown] == [len(read_comparison(csv_path))]
    for where, labels in lists.items():
        numbered = [int(m.group(1)) for label in labels
                    if (m := re.match(r"(?:Fig|Table) [\u2007]?(\d+)", label))]
        assert numbered == sorted(numbered), where  # Fig 2 before Fig 10
    figure_captions = {path: text for path, text in report_captions(browser, report).items()
                       if path.endswith(".png")}
    claims = read_claims()
    for row in comparison:
        said = claims.get((row["paper"], row["quantity"])) or row["quantity"]
        lead = (f"<strong>{row['verdict']}</strong> ({html.escape(row['item'], quote=False)}) "
                + html.escape(" ".join(said.split()), quote=False))
        stated = {re.sub(r".*/", "", path) for path, text in figure_captions.items()
                  if lead in text and f"paper_{row['paper'].lower()}/" in path}
        kind, numbers = numbers_of_item(row["item"])
        if kind == "figure":  # in the caption of every figure the item numbers, and no other
            assert stated == {name for name in stated
                              if set(numbers_of_name(Path(name).stem)) & set(numbers)}, row
            assert stated, row
        else:                 # an item naming no figure: one figure's caption at most
            assert len(stated) <= 1, (row["quantity"], stated)


def papers_of_run(work: Path) -> list[str]:
    """The papers of the run in ``work``: the letters of its results' ``paper_<p>`` folders."""
    return sorted(p.name.removeprefix("paper_") for p in (work / "results").glob("paper_*"))


def read_claims() -> dict[tuple[str, str], str]:
    return {(r["paper"], r["quantity"]): r["claim"]
            for r in read_comparison(ROOT / "data/paper_values.csv")}


def report_captions(browser, report: Path) -> dict[str, str]:
    """Each result's caption, as the report holds it (HTML), by the result's path."""
    page = browser.new_page()
    page.goto(report.as_uri())
    page.wait_for_selector("h1")
    captions = page.evaluate("Object.fromEntries(Object.entries(results)"
                             ".map(([path, r]) => [path, r.caption]))")
    page.close()
    return captions


def read_comparison(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))
