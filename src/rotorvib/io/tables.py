"""Small result tables written twice: CSV for machines, Markdown for people (and the report)."""

from __future__ import annotations

import csv
import math
from pathlib import Path


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def markdown_cell(text: str) -> str:
    """``text`` as the content of a Markdown table cell, shown as written: on one line, the
    cell separator escaped and ``<``, ``>`` as character references (a Markdown viewer passes
    an HTML tag through)."""
    one_line = " ".join(text.split())
    return one_line.replace("|", "\\|").replace("<", "&lt;").replace(">", "&gt;")


def write_table(rows: list[dict], csv_path: str | Path, md_path: str | Path, *, title: str,
                notes: list[str] = (), markdown_cells=None) -> None:
    """Write ``rows`` (dicts with the same keys, in column order) as CSV and Markdown.

    CSV cells keep full precision; Markdown cells use 4 significant digits unless
    ``markdown_cells(row) -> dict`` overrides some of them.
    """
    columns = list(rows[0]) if rows else []
    with open(csv_path, "w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows({k: ("" if v is None else v) for k, v in row.items()} for row in rows)
    lines = [f"# {title}", ""] + [line for note in notes for line in (note, "")]
    lines += ["| " + " | ".join(map(markdown_cell, columns)) + " |", "|" + "---|" * len(columns)]
    for row in rows:
        cells = {k: _cell(v) for k, v in row.items()}
        if markdown_cells is not None:
            cells.update(markdown_cells(row))
        lines.append("| " + " | ".join(markdown_cell(cells[k]) for k in columns) + " |")
    Path(md_path).write_text("\n".join(lines) + "\n", encoding="utf-8")


def order_bound(x: float) -> str:
    """A round-off-sized quantity as the power of ten at or above it (``1.9e-15`` ->
    ``"1e-14"``): what it bounds, without the digits that move with the machine's arithmetic
    (the BLAS kernel, the order of a sum); ``"0"`` for 0."""
    if not math.isfinite(x) or x < 0:
        raise ValueError(f"a bound must be finite and >= 0, not {x!r}")
    return "0" if x == 0 else f"{10.0 ** math.ceil(math.log10(x)):.0e}"
