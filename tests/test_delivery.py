"""What a user opens and keeps from a reduced run (tests/workflow_runs.py): the report in a
real browser (headless Chromium), and the archive, its RO-Crate (rocrate-validator) and its
restoration without recomputation."""

import csv
import os
import re
import shutil
import tarfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from ro_crate import validate_crate
from rotorvib.io.archive import verify_archive
from workflow_runs import REDUCED, copy_repository, copy_run, planned_jobs, snakemake

pytestmark = pytest.mark.workflow


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def browser():
    """Headless Chromium (Debian's package, installed by .ci/run) driven by Playwright."""
    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("Chromium is missing: .ci/run installs Debian's chromium package")
        pytest.skip("no Chromium on this machine (Debian package chromium)")
    from playwright.sync_api import sync_playwright
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(
            executable_path=CHROMIUM,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"])
        yield chromium
        chromium.close()


def _shown_entries(page, report: Path, category: str, subcategory: str) -> list[list[str]]:
    """The rows (label cells) the report lists for one subcategory, in its order, as shown
    after opening the report afresh and choosing that subcategory."""
    page.goto(report.as_uri())
    page.wait_for_selector("h1")
    page.evaluate(f"app.setView({{navbarMode: 'subcategory', category: '{category}', "
                  f"subcategory: '{subcategory}'}})")
    page.wait_for_selector("nav table tbody tr")
    return page.eval_on_selector_all(
        "nav table tbody tr",
        "rows => rows.map(r => [...r.querySelectorAll('td')].map(td => td.innerText.trim()))")


def test_the_report_reads_in_a_browser(run_dir, browser, tmp_path):
    """`snakemake --report` opened in headless Chromium: no console error, no docutils system
    message, the verdict totals on the landing page, every paper's figures in paper order,
    each with its own caption that states every comparison row about it."""
    work = copy_run(run_dir, tmp_path / "work")
    snakemake(work, "--report", "results/report.html", *REDUCED)
    page = browser.new_page()
    errors = []
    page.on("console", lambda message: errors.append(message.text)
            if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(str(error)))
    report = work / "results/report.html"
    page.goto(report.as_uri())
    page.wait_for_selector("h1")
    landing = page.inner_text("body")
    table = read_comparison(work / "results/comparison.csv")
    assert "Findings" in landing and f"{len(table)} stated values and claims" in landing
    majors = sum(r["verdict"] == "MAJOR" for r in table)
    assert re.search(rf"\ball\s+\d+\s+\d+\s+{majors}\s", landing)  # totals row: MAJOR column
    captions = page.evaluate("Object.fromEntries(Object.entries(results)"
                             ".map(([path, r]) => [path, r.caption]))")
    assert not [path for path, text in captions.items() if "system-message" in text]
    assert not page.query_selector_all(".system-message")
    for paper in "abc":
        drawn = {p.stem for p in (work / f"results/paper_{paper}/figures").glob("*.png")}
        rows = _shown_entries(page, report, f"Paper {paper.upper()}", "Figures")
        names = [figure for _, figure in (row[:2] for row in rows)]
        numbered = [int(m.group(1)) for n in names if (m := re.match(r"Figs? (\d+)", n))]
        assert numbered == sorted(numbered)  # the paper's order, Fig 2 before Fig 10
        assert names[:len(numbered)] == [n for n in names if re.match(r"Figs? \d", n)]
        assert len(names) == len(drawn)
        for name in drawn:
            text = next(t for path, t in captions.items()
                        if path.endswith(f"paper_{paper}/figures/{name}.png"))
            assert f"Paper {paper.upper()}, " in text and (
                "What the paper states" in text or "states no value" in text)
        assert len({captions[p] for p in captions if f"paper_{paper}/figures/" in p}) == len(drawn)
    for row in table:  # every row about a numbered figure is in that figure's caption
        match = re.fullmatch(r"Figs? (\d+)(?:-(\d+))?", row["item"])
        if not match:
            continue
        first, last = int(match.group(1)), int(match.group(2) or match.group(1))
        for path, text in captions.items():
            name = re.search(rf"paper_{row['paper'].lower()}/figures/fig([\d_]+)\.png$", path)
            if name and {int(n) for n in name.group(1).split("_")} & set(range(first, last + 1)):
                assert f"<strong>{row['verdict']}</strong> ({row['item']})" in text, path
    assert errors == []


def read_comparison(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_archive_restores_without_recomputation(run_dir, tmp_path):
    """The archive holds the results, the report, the run's configuration and commit and an
    RO-Crate that passes rocrate-validator; restored into a fresh copy, nothing reruns."""
    work = copy_run(run_dir, tmp_path / "work")
    snakemake(work, "-j2", "archive", *REDUCED)
    archive = work / "results/archive/rotorvib-results.tar.gz"
    members = verify_archive(archive)
    assert {"results/paper_c/datasets/ga.nc", "LICENSE", "CITATION.cff", "Snakefile",
            "results/report.html", "results/run/config.yaml", "results/run/commit.txt",
            "config/test/config.yaml", "ro-crate-metadata.json"} <= set(members)
    fresh = copy_repository(tmp_path / "fresh")
    with tarfile.open(archive) as tar:
        tar.extractall(fresh, filter="data")
    assert "Findings" in (fresh / "results/report.html").read_text(errors="replace")
    with ThreadPoolExecutor(1) as pool:      # the validator works while Snakemake restores
        issues = pool.submit(validate_crate, fresh, tmp_path / "cache")
        snakemake(fresh, "-j1", "--touch", *REDUCED)
        assert planned_jobs(snakemake(fresh, "-n", *REDUCED)) == set()
    assert [message for _, message, _ in issues.result()] == [
        "The Root Data Entity SHOULD have a `publisher` property (Organization or Person)"]
