"""A table of the report as a page a reviewer reads: what matters first (the paper's value, ours,
the error and the verdict), headers in words with units, every number rounded to what it can
tell, long texts and the columns a reviewer does not scan for folded into toggles, per-column
filters and sorting by DataTables (through itables, its whole bundle inside the page: the report
works offline), and the CSV itself, with every digit, as a download.

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
import re
from functools import cache

import pandas as pd
from itables import to_html_datatable
from itables.javascript import generate_init_offline_itables_html
from itables.options import dt_bundle

from rotorvib.paper_values import decimals

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
.caption { max-width: 70em; }
.bar { margin: .8em 0; }
table.dataTable td { vertical-align: top; max-width: 22em; overflow-wrap: break-word; }
table.dataTable tfoot input { width: 100%; min-width: 3em; box-sizing: border-box; }
table.dataTable td { min-width: 4em; } details { min-width: 14em; }
dl { margin: .3em 0; } dt { font-weight: 600; } dd { margin: 0 0 .3em .8em; }
table.dataTable td.dt-type-numeric { white-space: nowrap; }
details summary { cursor: pointer; color: #0f172a; }
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


@cache
def _bundle() -> str:
    """DataTables as itables ships it, to go inside a page (no network needed)."""
    return generate_init_offline_itables_html(dt_bundle)


def table_page(title: str, caption_html: str, csv_text: str, filename: str) -> str:
    """An HTML page of one CSV table: ``title``, the caption (HTML), a link that downloads the
    CSV as ``filename``, and the table (:func:`columns`, :func:`header`, :func:`shown`), each
    column sortable (its header) and filtered by its own box (below it), every row shown."""
    rows = list(csv.DictReader(io.StringIO(csv_text)))
    given = list(csv.reader(io.StringIO(csv_text)))[0]
    names = columns(given)
    cells = [[shown(row[n], n, row) for n in names] for row in rows]
    headers = [html.escape(header(n)) for n in names]
    if any(n in MORE for n in given):
        cells = [line + [more(row)] for line, row in zip(cells, rows)]
        headers.append("more")
    frame = pd.DataFrame(cells, columns=headers, dtype=object)
    table = to_html_datatable(frame, allow_html=True, paging=False, showIndex=False,
                              column_filters="footer", connected=False, classes="display compact",
                              display_logo_when_loading=False, order=[],
                              # named for its file, not at random: a page is the same bytes
                              # from run to run (the archive's are compared)
                              table_id="itables_" + re.sub(r"\W", "_", filename),
                              warn_on_unexpected_types=False)
    data = base64.b64encode(csv_text.encode("utf-8")).decode("ascii")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>{_STYLE}</style></head>
<body>
{_bundle()}
<h1>{html.escape(title)}</h1>
<div class="caption">{caption_html}</div>
<div class="bar">{len(rows)} rows. <a download="{html.escape(filename)}"
href="data:text/csv;base64,{data}">Download the CSV</a> (every digit).</div>
{table}
</body></html>
"""
