"""The papers' values (``data/paper_values.csv``): every number and claim each paper states,
with its ``source`` (:data:`SOURCES`) and, for a claim, the sentence it quotes."""

from __future__ import annotations

import csv
from pathlib import Path

SOURCES = ("printed", "chosen", "theory")


def float_or_none(text: str) -> float | None:
    """A CSV cell as a number, or None where it is empty."""
    return float(text) if text.strip() else None


def read_paper_values(path: str | Path) -> list[dict]:
    """The rows of the paper-values file; ``ValueError`` for a row with more fields than the
    header (an unquoted comma would cut a claim's text short) or an unknown source."""
    with open(path, newline="", encoding="utf-8") as fh:
        rows = [row for row in csv.DictReader(fh) if not row["paper"].startswith("#")]
    for row in rows:
        if None in row:
            raise ValueError(f"{path}: {row['quantity']}: more fields than the header "
                             f"({row[None]!r}): quote a text that holds a comma")
        row["value_text"] = row["value"]
        row["value"] = float_or_none(row["value"])
        if row["source"] not in SOURCES:
            raise ValueError(f"{path}: {row['quantity']}: source {row['source']!r} is not one of "
                             f"{SOURCES}")
    return rows


def paper_says(value_row: dict) -> str:
    """A claim's sentence as the paper words it (English rendering of the quote in the
    paper-values file, with where it stands), or empty for a number or a claim of our own."""
    quote, where = value_row.get("quote_en", ""), value_row.get("quote_where", "")
    if quote:
        return f'"{quote}" ({where})'
    return f"({where})" if where else ""


def paper_values_of(path: str | Path, paper: str) -> dict[str, float | None]:
    """``{quantity: value}`` of one paper from the paper-values file."""
    return {row["quantity"]: row["value"] for row in read_paper_values(path) if row["paper"] == paper}


def paper_value_texts_of(path: str | Path, paper: str) -> dict[str, str]:
    """``{quantity: value as printed}`` of one paper's numbers (its digits tell its precision)."""
    return {row["quantity"]: row["value_text"] for row in read_paper_values(path)
            if row["paper"] == paper and row["value"] is not None}


def decimals(text: str) -> int:
    """Decimals of a printed number: ``"9.04"`` -> 2, ``"4"`` -> 0, ``"7.5e-4"`` -> 5."""
    mantissa, _, exponent = text.strip().lower().partition("e")
    places = len(mantissa.partition(".")[2])
    return max(0, places - int(exponent or 0))
