"""The HTML pages of the report: the summary and every table, as self-contained documents.

Snakemake's report shows a ``text/html`` result inside the page (in a frame), and offers any
other file, a CSV among them, only as a download. Each table is therefore written as an HTML
page: its caption, the table (sortable by any column, filterable by text), and its CSV as a
download link carried inside the page. The summary page is reStructuredText (rotorvib.pipeline.report)
rendered by docutils with its own stylesheet embedded.
"""

from __future__ import annotations

import base64
import csv
import html
import io

from docutils.core import publish_parts, publish_string

_STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.2em; color: #1e293b; }
h1 { font-size: 1.3em; margin: 0 0 .4em; }
.caption { max-width: 70em; }
.bar { display: flex; gap: 1em; align-items: center; margin: .8em 0; }
input { font: inherit; padding: .2em .4em; width: 20em; }
table { border-collapse: collapse; }
th, td { border: 1px solid #cbd5e1; padding: .25em .5em; vertical-align: top; text-align: left; }
th { background: #f1f5f9; cursor: pointer; position: sticky; top: 0; white-space: nowrap; }
th[aria-sort=ascending]::after { content: " \\25b2"; }
th[aria-sort=descending]::after { content: " \\25bc"; }
td.number { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr:nth-child(even) td { background: #f8fafc; }
"""

# Sorting compares numbers as numbers and text as text; the filter keeps the rows whose text
# contains every word typed.
_SCRIPT = """
const table = document.querySelector("table"), body = table.tBodies[0];
const rows = [...body.rows];
table.tHead.querySelectorAll("th").forEach((th, column) => th.addEventListener("click", () => {
  const up = th.getAttribute("aria-sort") !== "ascending";
  table.tHead.querySelectorAll("th").forEach(h => h.removeAttribute("aria-sort"));
  th.setAttribute("aria-sort", up ? "ascending" : "descending");
  const key = r => r.cells[column].dataset.value ?? r.cells[column].textContent;
  rows.sort((a, b) => {
    const x = key(a), y = key(b), nx = parseFloat(x), ny = parseFloat(y);
    const order = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : x.localeCompare(y);
    return up ? order : -order;
  });
  rows.forEach(r => body.appendChild(r));
}));
const filter = document.querySelector("input");
const shown = document.querySelector("#shown");
filter.addEventListener("input", () => {
  const words = filter.value.toLowerCase().split(/\\s+/).filter(Boolean);
  let n = 0;
  rows.forEach(r => {
    const keep = words.every(w => r.textContent.toLowerCase().includes(w));
    r.hidden = !keep; n += keep;
  });
  shown.textContent = n;
});
"""


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return text.strip() != ""


def _cell(text: str) -> str:
    if _is_number(text):
        return f'<td class="number" data-value="{html.escape(text)}">{html.escape(text)}</td>'
    return f"<td>{html.escape(text)}</td>"


def table_page(title: str, caption_html: str, csv_text: str, filename: str) -> str:
    """An HTML page of one CSV table: ``title``, the caption (HTML), a filter box, the table
    (click a header to sort by its column) and a link that downloads the CSV as ``filename``."""
    header, *rows = list(csv.reader(io.StringIO(csv_text)))
    data = base64.b64encode(csv_text.encode("utf-8")).decode("ascii")
    head = "".join(f"<th>{html.escape(name)}</th>" for name in header)
    body = "\n".join("<tr>" + "".join(_cell(cell) for cell in row) + "</tr>" for row in rows)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>{_STYLE}</style></head>
<body>
<h1>{html.escape(title)}</h1>
<div class="caption">{caption_html}</div>
<div class="bar"><input type="search" placeholder="Filter rows" aria-label="Filter rows">
<span><span id="shown">{len(rows)}</span> of {len(rows)} rows</span>
<a download="{html.escape(filename)}" href="data:text/csv;base64,{data}">Download CSV</a></div>
<table><thead><tr>{head}</tr></thead>
<tbody>
{body}
</tbody></table>
<script>{_SCRIPT}</script>
</body></html>
"""


#: docutils settings of every page written here: any warning raises, and no directive may
#: include a file or pass raw HTML through (the texts are escaped, rotorvib.pipeline.report.rst_text;
#: this holds even where one is not).
_SETTINGS = {"halt_level": 2, "report_level": 2, "_disable_config": True,
             "raw_enabled": False, "file_insertion_enabled": False}


def rst_to_html(text: str) -> str:
    """``text`` (reStructuredText) as a standalone HTML page; any docutils warning raises."""
    return publish_string(text, writer_name="html5", settings_overrides={
        **_SETTINGS, "embed_stylesheet": True, "output_encoding": "unicode"}).strip() + "\n"


def rst_fragment(text: str) -> str:
    """``text`` (reStructuredText) as an HTML fragment (a caption inside a page)."""
    return publish_parts(text, writer_name="html5", settings_overrides=_SETTINGS)["body"]
