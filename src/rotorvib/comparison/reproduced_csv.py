"""The reproduced values' CSV: each paper's comparison-values script writes its rows with
:func:`write_reproduced`, the comparison and the discrepancy analysis read them back with
:func:`read_reproduced`, unchanged (claims' variants and margins, implied values, intervals,
calibrations included)."""

from __future__ import annotations

import csv
from pathlib import Path

from rotorvib.comparison.choices import CHOICE_SEPARATOR

from rotorvib.comparison.reproduced import MARGIN_COLUMNS, Margin, Reproduced

from rotorvib.comparison.paper_values import float_or_none

_HOLDS_TEXT = {True: "yes", False: "no", None: "undetermined"}

def _holds_from_text(text: str):
    inverse = {v: k for k, v in _HOLDS_TEXT.items()}
    pairs = [item.rsplit("=", 1) if "=" in item else ("", item)
             for item in text.split(";") if item]
    return tuple((k, inverse[v]) for k, v in pairs)


def _holds_to_text(holds) -> str:
    return ";".join(f"{k}={_HOLDS_TEXT[h]}" if k else _HOLDS_TEXT[h] for k, h in holds)


def _variants_from_text(text: str):
    return tuple((k, float(v)) for k, v in (item.rsplit("=", 1) for item in text.split(";")
                                            if item))


REPRODUCED_COLUMNS = ("paper", "quantity", "reproduced", "holds", "implied", "variants",
                      *MARGIN_COLUMNS, "interval", "calibrated", "cause",
                      "choices", "explanation")


def _choices_from_text(text: str) -> tuple[str, ...]:
    return tuple(text.split(CHOICE_SEPARATOR)) if text else ()


def _interval_from_text(text: str) -> tuple[float, float] | None:
    return None if not text else tuple(float(v) for v in text.split(" "))


def _interval_text(interval) -> str:
    return "" if interval is None else f"{interval[0]!r} {interval[1]!r}"


def _margin_from_text(r: dict) -> Margin | None:
    if not r["margin_basis"]:
        return None
    return Margin(float(r["margin"]), float(r["uncertainty"]), r["margin_unit"], r["margin_basis"])


def _margin_cells(margin: Margin | None) -> list:
    if margin is None:
        return ["", "", "", ""]
    return [repr(float(margin.value)), repr(float(margin.uncertainty)), margin.unit, margin.basis]


def read_reproduced(path: str | Path) -> list[Reproduced]:
    """The rows a paper's comparison-values script wrote (:func:`write_reproduced`)."""
    with open(path, newline="", encoding="utf-8") as fh:
        return [Reproduced(r["paper"], r["quantity"], float_or_none(r["reproduced"]),
                           r["explanation"], _holds_from_text(r["holds"]),
                           float_or_none(r["implied"]), _variants_from_text(r["variants"]),
                           _margin_from_text(r), _interval_from_text(r["interval"]),
                           r["calibrated"], r["cause"], _choices_from_text(r["choices"]))
                for r in csv.DictReader(fh)]


def write_reproduced(rows: list[Reproduced], path: str | Path) -> None:
    """Write reproduced rows as CSV (:data:`REPRODUCED_COLUMNS`); :func:`read_reproduced` reads
    them back unchanged."""
    with open(path, "w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(REPRODUCED_COLUMNS)
        for r in rows:
            writer.writerow([r.paper, r.quantity, "" if r.reproduced is None else repr(r.reproduced),
                             _holds_to_text(r.holds), "" if r.implied is None else repr(r.implied),
                             ";".join(f"{k}={v!r}" for k, v in r.variants),
                             *_margin_cells(r.margin), _interval_text(r.interval),
                             r.calibrated, r.cause, CHOICE_SEPARATOR.join(r.choices),
                             r.explanation])
