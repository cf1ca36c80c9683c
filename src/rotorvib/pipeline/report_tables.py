"""A table of the report as a page a reviewer reads: what matters first (the paper's value, ours,
the error and the verdict), headers in words with units, every number rounded to what it can
tell, long texts and the columns a reviewer does not scan for folded into toggles, per-column
filters and sorting (:data:`SCRIPT`, a few lines inside the page: the report works offline, and
every table page no longer carries its own 970 kB copy of DataTables), and the CSV itself, with
every digit, as a download.

Snakemake's report shows a ``text/html`` result inside the page (in a frame) and offers any other
file, a CSV among them, only as a download: hence a page per table. Every text is escaped here
before it reaches the page; the table's cells are HTML only for the toggles this module writes.
"""

from __future__ import annotations

import base64
import csv
import html
import io
import math

from rotorvib.comparison.paper_values import decimals

#: Columns shown first, in this order, where a table has them: what the paper states beside what
#: the reproduction finds and the verdict; the others follow in the CSV's order.
FIRST = ("paper", "item", "quantity", "paper_value", "reproduced", "unit", "rel_error",
         "verdict", "explanation", "hypothesis", "printed", "value", "reproduces")
#: Columns that say more about a row than a reviewer scans for: shown together in one folded
#: cell, "more" (the comparison's and the discrepancy analysis' own columns).
MORE = ("source", "paper_says", "margin", "uncertainty", "margin_unit", "margin_basis",
        "finding", "choices", "alternatives", "kind")
#: Headers that are not the column's name in words.
HEADERS = {"paper_value": "paper value", "rel_error": "relative error",
           "paper_says": "the paper says", "choices": "rests on", "margin_basis": "margin basis",
           "margin_unit": "margin unit", "ga_this_work": "GA (this work)",
           "table2_design": "Table 2's design"}
#: A column name's unit suffix and the unit it stands for: ``force_max_N`` -> "force max (N)".
UNITS = {"_rad_s": "rad/s", "_kg": "kg", "_N": "N", "_s": "s", "_rad": "rad", "_m": "m"}
#: Significant digits of a number no paper value fixes the precision of.
SIGNIFICANT = 4
#: A text longer than this is folded: its opening words, the rest behind a toggle.
FOLD = 60

_STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.2em; color: #1e293b; }
h1 { font-size: 1.3em; margin: 0 0 .4em; }
.caption { max-width: 70em; overflow-wrap: anywhere; }
.bar { margin: .8em 0; }
.scroll { overflow-x: auto; }
table.results { border-collapse: collapse; }
table.results th, table.results td { padding: .25em .5em; border-bottom: 1px solid #e2e8f0;
  text-align: left; vertical-align: top; }
table.results td { min-width: 4em; max-width: 22em; overflow-wrap: break-word; }
table.results td.number { white-space: nowrap; text-align: right; }
table.results thead th { cursor: pointer; position: sticky; top: 0; background: #f8fafc; }
table.results thead th[aria-sort=ascending]::after { content: " \\25B2"; }
table.results thead th[aria-sort=descending]::after { content: " \\25BC"; }
table.results tfoot input { width: 100%; min-width: 3em; box-sizing: border-box; }
details { min-width: 14em; } details summary { cursor: pointer; color: #0f172a; }
dl { margin: .3em 0; } dt { font-weight: 600; } dd { margin: 0 0 .3em .8em; }
"""
#: Sorting and filtering of the page's table: a header sorts its column (numbers by their
#: value, every digit, ``data-value``; texts alphabetically), a second click the other way; a
#: box under a column keeps the rows whose cell contains its text; the count says how many show.
SCRIPT = """
(() => {
  const table = document.querySelector("table.results"), body = table.tBodies[0];
  const rows = [...body.rows], count = document.getElementById("shown");
  const value = (row, i) => row.cells[i].dataset.value ?? row.cells[i].innerText.trim();
  const order = (a, b) => (a !== "" && b !== "" && isFinite(a) && isFinite(b))
    ? Number(a) - Number(b) : String(a).localeCompare(String(b));
  [...table.tHead.rows[0].cells].forEach((th, i) => {
    th.tabIndex = 0;
    const sort = () => {
      const up = th.getAttribute("aria-sort") !== "ascending";
      [...table.tHead.rows[0].cells].forEach(h => h.removeAttribute("aria-sort"));
      th.setAttribute("aria-sort", up ? "ascending" : "descending");
      body.append(...rows.slice().sort((a, b) => order(value(a, i), value(b, i)) * (up ? 1 : -1)));
    };
    th.addEventListener("click", sort);
    th.addEventListener("keydown", event => { if (event.key === "Enter") sort(); });
  });
  const boxes = [...table.tFoot.querySelectorAll("input")];
  boxes.forEach(box => box.addEventListener("input", () => {
    const words = boxes.map(b => b.value.trim().toLowerCase());
    let shown = 0;
    rows.forEach(row => {
      row.hidden = !words.every((w, i) => !w || row.cells[i].innerText.toLowerCase().includes(w));
      shown += !row.hidden;
    });
    count.textContent = shown;
  }));
})();
"""


def header(name: str) -> str:
    """A column's header: its name in words, a unit suffix as the unit in brackets."""
    if name in HEADERS:
        return HEADERS[name]
    for suffix, unit in UNITS.items():
        if name.endswith(suffix) and len(name) > len(suffix):
            return f"{name[:-len(suffix)].replace('_', ' ')} ({unit})"
    return name.replace("_", " ")


def columns(names: list[str]) -> list[str]:
    """The columns in the order shown: :data:`FIRST`, then the rest as in the CSV but those of
    :data:`MORE` (shown folded together, :func:`more`)."""
    return [n for n in FIRST if n in names] + [n for n in names
                                               if n not in FIRST and n not in MORE]


def more(row: dict[str, str]) -> str:
    """The columns of :data:`MORE` of a row that have a value, folded in one cell (HTML)."""
    given = [(n, row[n]) for n in MORE if row.get(n, "").strip()]
    if not given:
        return ""
    items = "".join(f"<dt>{html.escape(header(n))}</dt><dd>{html.escape(v)}</dd>"
                    for n, v in given)
    return f"<details><summary>{len(given)} more</summary><dl>{items}</dl></details>"


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except ValueError:
        return None
    return value if text.strip() and math.isfinite(value) else None


def significant(value: float) -> str:
    """``value`` to at most :data:`SIGNIFICANT` significant digits (no trailing zeros), without
    an exponent between 1e-4 and 1e6 (51130, 0.003948, 0.37), with one beyond (3.608e-05)."""
    if value == 0 or not 1e-4 <= abs(value) < 1e6:
        return f"{value:.{SIGNIFICANT}g}"
    rounded = float(f"{value:.{SIGNIFICANT}g}")
    places = SIGNIFICANT - 1 - math.floor(math.log10(abs(rounded)))
    text = f"{rounded:.{max(places, 0)}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def shown(text: str, column: str, row: dict[str, str]) -> str:
    """A cell as shown (HTML): a reproduced value to one decimal more than the paper's own
    (``paper_value`` of its row), any other number to :data:`SIGNIFICANT` significant digits, a
    long text folded; everything escaped."""
    value = _number(text)
    if column == "paper_value":
        return html.escape(text)           # as printed
    if value is not None:
        paper = _number(row.get("paper_value", ""))
        if column == "reproduced" and paper is not None:
            return f"{value:.{decimals(row['paper_value']) + 1}f}"
        return text if text.strip().lstrip("-").isdigit() else significant(value)
    if len(text) <= FOLD:
        return html.escape(text)
    head = html.escape(text[:FOLD].rsplit(" ", 1)[0])
    return f"<details><summary>{head} …</summary>{html.escape(text)}</details>"


def cell(text: str, column: str, row: dict[str, str]) -> str:
    """A ``<td>`` of :func:`shown`; a number's keeps its every digit in ``data-value``, by which
    its column sorts."""
    if _number(text) is None:
        return f"<td>{shown(text, column, row)}</td>"
    return (f'<td class="number" data-value="{html.escape(text.strip())}">'
            f"{shown(text, column, row)}</td>")


def table_page(title: str, caption_html: str, csv_text: str, filename: str) -> str:
    """An HTML page of one CSV table: ``title``, the caption (HTML), a link that downloads the
    CSV as ``filename``, and the table (:func:`columns`, :func:`header`, :func:`shown`), each
    column sortable (its header) and filtered by its own box (below it), every row shown."""
    rows = list(csv.DictReader(io.StringIO(csv_text)))
    given = list(csv.reader(io.StringIO(csv_text)))[0]
    names = columns(given)
    lines = [[cell(row[n], n, row) for n in names] for row in rows]
    headers = [html.escape(header(n)) for n in names]
    if any(n in MORE for n in given):
        lines = [line + [f"<td>{more(row)}</td>"] for line, row in zip(lines, rows)]
        headers.append("more")
    head = "".join(f'<th scope="col">{h}</th>' for h in headers)
    boxes = "".join(f'<td><input type="search" aria-label="rows whose {h} contains"></td>'
                    for h in headers)
    body = "\n".join(f"<tr>{''.join(line)}</tr>" for line in lines)
    data = base64.b64encode(csv_text.encode("utf-8")).decode("ascii")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)}</title>
<style>{_STYLE}</style></head>
<body>
<h1>{html.escape(title)}</h1>
<div class="caption">{caption_html}</div>
<div class="bar"><span id="shown">{len(rows)}</span> of {len(rows)} rows shown (a header
sorts, a box under a column filters). <a download="{html.escape(filename)}"
href="data:text/csv;base64,{data}">Download the CSV</a> (every digit).</div>
<div class="scroll"><table class="results">
<thead><tr>{head}</tr></thead>
<tbody>
{body}
</tbody>
<tfoot><tr>{boxes}</tr></tfoot>
</table></div>
<script>{SCRIPT}</script>
</body></html>
"""
