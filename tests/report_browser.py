"""What a reader sees of the HTML report in a real browser (headless Chromium through
Playwright): where the landing page's parts lie in the window, and every view the sidebar and
the result lists open, by clicking them as a reader does. tests/test_delivery.py asserts on
what these functions return."""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import pytest

SIZES = ((1280, 800), (1400, 1000), (1920, 1080))
# Where the landing page's screenshots go: $REPORT_SCREENSHOTS (.ci/run sets it), else
# test-artifacts/ in the repository.
SCREENSHOTS = Path(os.environ.get("REPORT_SCREENSHOTS", Path(__file__).parents[1] / "test-artifacts"))


@dataclass
class Landing:
    """Boxes (left, top, right, bottom, in CSS pixels of the window) of the landing page."""
    width: int
    height: int
    title: tuple
    totals: tuple
    description: tuple
    rule_graph: tuple


def box(page, selector: str) -> tuple:
    rect = page.eval_on_selector(selector, "e => e.getBoundingClientRect().toJSON()")
    return rect["left"], rect["top"], rect["right"], rect["bottom"]


def landing(browser, report: Path, width: int, height: int, screenshot: Path) -> Landing:
    """The landing page as opened in a window of ``width`` x ``height``, without scrolling."""
    page = browser.new_page(viewport={"width": width, "height": height})
    page.goto(report.as_uri())
    page.wait_for_selector("h1.title")
    page.wait_for_selector("canvas")
    screenshot.parent.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=screenshot)
    seen = Landing(width, height, box(page, "h1.title"),
                   box(page, ".prose ul:first-of-type"), box(page, ".prose"),
                   box(page, "canvas"))
    page.close()
    return seen


def sidebar(browser, report: Path) -> list[str]:
    """The report's categories as its sidebar lists them, top to bottom (under "Results")."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.goto(report.as_uri())
    page.wait_for_selector("h1.title")
    lines = page.locator("nav").first.inner_text().splitlines()
    page.close()
    return lines[[line.upper() for line in lines].index("RESULTS") + 1:]


@dataclass
class View:
    """One view a reader opened: how (the clicks), what it showed, and the page errors."""
    path: tuple[str, ...]
    kind: str = ""              # "img", "html" or "" (nothing shown)
    image_width: int = 0
    table_rows: int = -1        # rows of the table inside an HTML result (-1: none)
    text: str = ""
    errors: list[str] = field(default_factory=list)
    cells: list[list[str]] = field(default_factory=list)  # a DataTable's header, then its rows


def _sidebar_links(page) -> list[str]:
    return page.eval_on_selector_all("nav a", "links => links.map(a => a.innerText.trim())")


#: How long a click may take to change what the page shows (ms)
CHANGE_TIMEOUT = 10_000
#: The src of what the content area shows: an image, or an HTML page in a frame (None: neither)
_CONTENT = ("document.querySelector('iframe, div.p-3 > img') && "
            "document.querySelector('iframe, div.p-3 > img').getAttribute('src')")
#: What the sidebar shows (a click in it must change this)
_SIDEBAR = "document.querySelector('nav').innerHTML"


def _click_changing(page, target, state: str) -> bool:
    """Click ``target`` and wait until the JavaScript expression ``state`` differs from its
    value before the click (what a reader waits for); False if it has not within
    CHANGE_TIMEOUT."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    before = page.evaluate(state)
    target.click()
    try:
        page.wait_for_function(f"before => ({state}) !== before", arg=before,
                               timeout=CHANGE_TIMEOUT)
    except PlaywrightTimeout:
        return False
    return True


def _click_text(page, text: str) -> None:
    """Click the sidebar link ``text``: the sidebar must change."""
    changed = _click_changing(page, page.locator("nav a", has_text=text).first, _SIDEBAR)
    assert changed, f"clicking {text!r} in the sidebar changed nothing"


def _back_to_the_categories(page) -> None:
    """Back to the sidebar's list of categories as a reader goes back, by its "Results" link
    (shown once a category is open), without loading the report again."""
    back = page.locator("nav a").filter(has_text=re.compile(r"^\s*Results\s*$"))
    if back.count():
        _click_changing(page, back.first, _SIDEBAR)
    assert "Results" not in _sidebar_links(page), "the sidebar's Results link led nowhere"


def _result_rows(page) -> list[str]:
    return page.eval_on_selector_all(
        "nav table tbody tr", "rows => rows.map(r => r.cells[0].innerText.trim())")


def _shown(page, path: tuple[str, ...], errors: list[str], changed: bool) -> View:
    """What the content area shows after the click that ``path`` ends with (an error if the
    click did not ``changed`` it)."""
    view = View(path, errors=list(errors) + ([] if changed else ["the view did not change"]))
    frame = page.query_selector("iframe")
    image = page.query_selector("div.p-3 > img")  # the content area's image view
    if frame is None and image is not None:
        image.evaluate("img => img.decode()")
        view.kind, view.image_width = "img", image.evaluate("img => img.naturalWidth")
    if frame is not None:
        view.kind = "html"
        content = frame.content_frame()
        content.wait_for_load_state()
        view.table_rows = content.evaluate(
            "() => { const t = document.querySelector('table.results') || "
            "document.querySelector('table'); "
            "return t ? t.querySelectorAll('tbody tr').length : -1; }")
        view.text = content.evaluate("() => document.body.innerText")
        view.cells = content.evaluate(
            "() => { const t = document.querySelector('table.results'); if (!t) return []; "
            "const texts = row => [...row.cells].map(c => c.innerText.trim()); "
            "return [texts(t.tHead.rows[0]), ...[...t.tBodies[0].rows].map(texts)]; }")
    errors.clear()
    return view


def every_view(browser, report: Path) -> tuple[list[str], list[View], dict[str, list[str]]]:
    """Click every category of the sidebar, every subcategory in it and the view button of
    every result listed, as a reader would: the categories, every view opened, and the labels
    each list showed, in its order (by "category/subcategory")."""
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.goto(report.as_uri())
    page.wait_for_selector("h1.title")
    categories = page.evaluate("Object.keys(categories)")
    views, lists = [], {}
    for category in categories:
        subcategories = page.evaluate(f"Object.keys(categories[{category!r}])")
        for sub in subcategories:
            _back_to_the_categories(page)
            _click_text(page, category)
            if len(subcategories) > 1:
                _click_text(page, sub)
            labels = _result_rows(page)
            lists[f"{category}/{sub}"] = labels
            if not labels:
                views.append(View((category, sub), errors=list(errors)))
                errors.clear()
            for i, label in enumerate(labels):
                button = page.locator("nav table tbody tr").nth(i).locator("a").first
                changed = _click_changing(page, button, _CONTENT)
                views.append(_shown(page, (category, sub, label), errors, changed))
    page.close()
    return categories, views, lists


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def chromium():
    """Headless Chromium (Debian's package, installed by .ci/run) driven by Playwright, for a
    fixture to yield; a test skips (fails under CI) where Chromium is missing."""
    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("Chromium is missing: .ci/run installs Debian's chromium package")
        pytest.skip("no Chromium on this machine (Debian package chromium)")
    from playwright.sync_api import sync_playwright
    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(
            executable_path=CHROMIUM,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"])
        yield launched
        launched.close()
