"""What a user opens and keeps from a reduced run (tests/workflow_runs.py): the report in a
real browser (headless Chromium), and the archive, its RO-Crate (rocrate-validator) and its
restoration without recomputation."""

import base64
import csv
import hashlib
import html
import json
import re
import tarfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import yaml

import report_browser
from conftest import ROOT
from ro_crate import validate_crate
from rotorvib.paper_values import decimals
from rotorvib.pipeline.archive import METADATA_DIR, digest_file, restore_archive, verify_archive
from rotorvib.pipeline.report import SUBCATEGORIES, numbers_of_item, numbers_of_name
from rotorvib.pipeline.report import categories as report_categories
from workflow_runs import (
    REDUCED,
    REDUCED_SHARDED,
    copy_repository,
    copy_run,
    job_records,
    planned_jobs,
    snakemake,
)

pytestmark = pytest.mark.workflow


@pytest.fixture(scope="module")
def report(run_dir, tmp_path_factory) -> Path:
    """`snakemake --report` of a copy of the reduced run, as the README says to open it."""
    work = copy_run(run_dir, tmp_path_factory.mktemp("report") / "work")
    snakemake(work, "--report", "results/report.html", *REDUCED)
    return work / "results/report.html"


#: Every profile the repository ships, as a command names it (none: the default profile).
PROFILES = {"default": [], "slurm": ["--workflow-profile", "workflow/profiles/slurm"]}


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
        assert report_browser.sidebar(browser, built) == list(report_categories("abc").values())


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
    named = report_categories("abc")
    assert report_browser.sidebar(browser, report) == list(named.values())  # the story's order
    assert set(categories) == set(named.values())
    assert [view for view in views if view.errors or not view.kind] == []
    figures = list((work / "results").glob("paper_*/figures/*.png"))
    assert sum(view.kind == "img" and view.image_width >= 800 for view in views) == len(figures)
    tables = {view.path[-1]: view for view in views if view.kind == "html"}
    tables_of = {f"Paper {p.upper()}": SUBCATEGORIES["Tables"] for p in "bc"}
    comparison = read_comparison(work / "results/comparison.csv")
    assert tables["Comparison"].table_rows == len(comparison)
    assert tables["Discrepancies"].table_rows == len(
        read_comparison(work / "results/discrepancies.csv"))
    assert f"{len(comparison)} values and claims" in tables["Verdicts and findings"].text
    _numbers_as_precise_as_they_can_tell(tables["Comparison"].cells)
    assert "Findings" in tables["Verdicts and findings"].text
    for paper in "bc":
        csv_rows = len(read_comparison(work / f"results/paper_{paper}/tables/table2.csv"))
        shown = [v for v in views if v.path[:2] == (named[f"Paper {paper.upper()}"],
                                                     tables_of[f"Paper {paper.upper()}"])
                 and v.path[-1] == "Table \u20072"]
        assert [v.table_rows for v in shown] == [csv_rows]
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


def test_archive_restores_without_recomputation(run_dir, tmp_path):
    """The archive holds the results, the report's words and pages, the run's configuration
    and commit and an RO-Crate that passes rocrate-validator; restored into a fresh copy,
    nothing reruns, and the HTML report is rebuilt from it."""
    work = copy_run(run_dir, tmp_path / "work")
    snakemake(work, "-j2", "archive", *REDUCED)
    archive = work / "results/archive/rotorvib-results.tar.gz"
    members = verify_archive(archive)
    assert {"results/paper_c/datasets/ga.nc", "LICENSE", "CITATION.cff", "Snakefile",
            "results/run/config.yaml", "results/run/commit.txt",
            "config/test/config.yaml", "ro-crate-metadata.json"} <= set(members)
    for kind in ("png", "svg", "json"):  # every figure in both formats, with what it draws
        figures = {p.relative_to(work).as_posix()
                   for p in (work / "results").glob(f"paper_*/figures/*.{kind}")}
        assert figures and figures <= set(members), kind
    stored = [data for name, data in _members(archive, links=False).items()
              if name.startswith("results/")]   # the report's copies are links: bytes once
    assert len({hashlib.sha256(data).digest() for data in stored}) == len(stored)
    with tarfile.open(archive) as tar:
        links = {m.name for m in tar.getmembers() if m.islnk()}
    assert {p.relative_to(work).as_posix()
            for p in (work / "results/report").rglob("*.png")} <= links
    fresh = copy_repository(tmp_path / "fresh")
    published = digest_file(archive).read_text().split()[0]
    restored = restore_archive(archive, published, fresh)
    assert "Snakefile" not in restored and "results/paper_c/datasets/ga.nc" in restored
    with ThreadPoolExecutor(1) as pool:      # the validator works while Snakemake restores
        issues = pool.submit(validate_crate, fresh, tmp_path / "cache")
        snakemake(fresh, "-j1", "--touch", *REDUCED)
        assert planned_jobs(snakemake(fresh, "-n", *REDUCED)) == set()
        snakemake(fresh, "--report", "results/report.html", *REDUCED)   # rebuilt from it
        assert "Verdict totals" in (fresh / "results/report.html").read_text(errors="replace")
        rebuilt = snakemake(fresh, "-j1", "archive", *REDUCED)       # and the archive, again
        assert planned_jobs(rebuilt) == {"archive"}
        assert (fresh / archive.relative_to(work)).read_bytes() == archive.read_bytes()
    assert [message for _, message, _ in issues.result()] == [
        "The Root Data Entity SHOULD have a `publisher` property (Organization or Person)"]


def _members(archive: Path, links: bool = True) -> dict[str, bytes]:
    """Each member's bytes; a hard link's are its target's (``links``), else it is left out."""
    with tarfile.open(archive) as tar:
        return {m.name: tar.extractfile(m).read() for m in tar.getmembers()
                if m.isfile() or (links and m.islnk())}


def test_two_runs_pack_the_same_archive_but_for_the_split(runs, tmp_path):
    """The session's two independent runs (same commit, jobs run at different times, the
    second with paper B's batch studies in three shards) each pack their archive. Every member
    is the same byte for byte, job records included (their run times left out), but those that
    say how the second was split: its configuration (paper_b.shards, and the file that sets
    it), the records of the studies gathered from shards (their inputs), of the run's
    configuration files (their parameters), and the crate, manifest and README that list
    them. The first, packed again later, is the same file byte for byte."""
    archives = []
    for i, (run, config) in enumerate(zip(runs, (REDUCED, REDUCED_SHARDED))):
        work = copy_run(run, tmp_path / f"build{i}")
        snakemake(work, "-j2", "archive", *config)
        archives.append(_members(work / "results/archive/rotorvib-results.tar.gz"))
    packed = tmp_path / "build0/results/archive/rotorvib-results.tar.gz"
    first = packed.read_bytes()
    again = snakemake(tmp_path / "build0", "-j1", "-f", "archive", *REDUCED)
    assert planned_jobs(again) == {"archive"} and packed.read_bytes() == first
    one, split = archives
    assert set(split) - set(one) == {REDUCED_SHARDED[-1]} and set(one) <= set(split)
    records = {name for name in one if name.startswith(METADATA_DIR)}
    assert len(records) > 100
    differ = {name for name in one if one[name] != split[name]}
    assert differ - records == {"results/run/config.yaml", "ro-crate-metadata.json",
                                "results/ARCHIVE_MANIFEST.sha256", "results/ARCHIVE_README.md"}
    configs = [yaml.safe_load(members["results/run/config.yaml"]) for members in archives]
    assert [c["paper_b"].pop("shards") for c in configs] == [1, 3] and configs[0] == configs[1]
    changed = {}
    for name in differ & records:
        fields = [json.loads(members[name]) for members in archives]
        path = base64.urlsafe_b64decode(name.rsplit("/", 1)[1]).decode()
        changed[path] = {key for key in fields[0] if fields[0][key] != fields[1].get(key)}
    gathered = {r["output"][0] for r in job_records(runs[1])
                if any("/shards/" in f for f in r["input"])}
    assert len(gathered) == 10
    assert changed == {**{path: {"input", "input_checksums"} for path in gathered},
                       "results/run/commit.txt": {"params"},
                       "results/run/config.yaml": {"params"}}
