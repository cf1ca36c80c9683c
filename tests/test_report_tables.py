"""A table page of the report (rotorvib.pipeline.report_tables) in headless Chromium, as a reader
uses it: a header sorts its column by value (every digit, not the rounded text), a second click
the other way; a box under a column keeps the rows that contain its text and the count says so;
the page is small (it carried DataTables' 970 kB bundle, once per table page) and fits a phone's
width without cutting a line."""

from rotorvib.pipeline.report_pages import rst_to_html
from rotorvib.pipeline.report_tables import table_page

CSV = ("item,paper_value,reproduced,verdict,explanation\n"
       "Fig 2,1.5,1.5004,MATCH,a\n"
       "Fig 10,10,9.9,MATCH,b\n"
       "Table 1,2,2.0001,MISMATCH," + "a long explanation " * 20 + "\n"
       "Table 2,0.25,-3,MATCH,d\n")


def _page(browser, width=1200):
    page = browser.new_page(viewport={"width": width, "height": 800})
    page.set_content(table_page("Title", "<p>caption</p>", CSV, "t.csv"))
    return page


def _column(page, i):
    return page.eval_on_selector_all(
        "table.results tbody tr:not([hidden])", f"rows => rows.map(r => r.cells[{i}].innerText)")


def test_a_header_sorts_by_value_and_a_box_filters(browser):
    page = _page(browser)
    errors = []
    page.on("pageerror", lambda error: errors.append(error))
    headers = page.locator("table.results thead th")
    assert headers.nth(2).inner_text() == "reproduced"
    headers.nth(2).click()
    assert _column(page, 0) == ["Table 2", "Fig 2", "Table 1", "Fig 10"]      # -3 < 1.5 < 2 < 9.9
    headers.nth(2).click()
    assert _column(page, 0) == ["Fig 10", "Table 1", "Fig 2", "Table 2"]
    headers.nth(0).click()
    assert _column(page, 0) == ["Fig 10", "Fig 2", "Table 1", "Table 2"]
    page.locator("table.results tfoot input").nth(3).fill("mis")
    assert _column(page, 0) == ["Table 1"] and page.inner_text("#shown") == "1"
    page.locator("table.results tfoot input").nth(3).fill("")
    assert len(_column(page, 0)) == 4 and page.inner_text("#shown") == "4"
    assert not errors


def test_the_page_is_small_and_fits_a_phone(browser):
    text = table_page("Title", "<p>caption</p>", CSV, "t.csv")
    assert len(text.encode()) < 10_000
    page = _page(browser, width=390)
    cut = page.evaluate("() => [...document.querySelectorAll('.caption, .bar, h1')]"
                        ".some(e => e.scrollWidth > e.clientWidth + 1)")
    body = page.evaluate("() => document.body.scrollWidth <= window.innerWidth")
    assert not cut and body


def test_the_summary_page_fits_a_wide_view_and_scrolls_its_table_on_a_phone(browser):
    """The summary (docutils' page): a sans-serif face, its verdict table whole at 1400 pixels
    (it was cut there), and on a phone nothing beyond the view (a table too wide scrolls in its
    own box)."""
    columns = ["paper", "MATCH", "MINOR", "MAJOR", "PAPER-INCONSISTENT", "UNDETERMINED",
               "EXPECTED", "UNEXPECTED", "SUPPORTED", "NOT SUPPORTED", "DEPENDS",
               "UNDETERMINED", "CALIBRATED", "hypotheses"]
    rows = [columns] + [[f"Paper {p}"] + ["10"] * (len(columns) - 1) for p in "ABC"]
    rst = "Summary\n=======\n\n.. list-table::\n   :header-rows: 1\n\n" + "".join(
        "   * " + "\n     ".join(f"- {c}" for c in row) + "\n" for row in rows)
    html = rst_to_html(rst + "\n" + "A long sentence of the findings. " * 40 + "\n")
    for width in (1400, 390):
        page = browser.new_page(viewport={"width": width, "height": 800})
        page.set_content(html)
        font, body, table = page.evaluate(
            "() => { const t = document.querySelector('table');"
            " return [getComputedStyle(document.body).fontFamily,"
            " document.body.scrollWidth <= window.innerWidth,"
            " t.scrollWidth <= t.clientWidth]; }")
        assert "sans-serif" in font and body and (table or width < 1000)
