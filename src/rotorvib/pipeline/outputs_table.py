"""The user guide's table of where each paper item lands, written from what declares it: each
paper's outputs (``rotorvib.papers.<p>.outputs``) and the workflow's own plan, the output files
of ``snakemake --summary`` and the rule that makes each.  ``docs/conf.py`` writes it on every
build (``docs/_generated/outputs.md``), so it cannot drift from the rules."""

from __future__ import annotations

import csv
import io
import re

from rotorvib.pipeline.report import label


def producers(summary: str) -> dict[str, str]:
    """``{output file: rule}`` from the tab-separated table ``snakemake --summary`` prints."""
    rows = csv.DictReader(io.StringIO(summary), delimiter="\t")
    return {row["output_file"]: row["rule"] for row in rows if row.get("rule")}


def _first_sentence(text: str) -> str:
    """A declaration's ``shows`` up to the end of its first sentence (a full stop before a
    capital: "eq. (37)" ends none)."""
    return re.split(r"(?<=\.)\s+(?=[A-Z])", text, maxsplit=1)[0]


def _row(paper: str, item: str, shows: str, files: list[str],
         made: dict[str, str]) -> tuple[str, str, list[str], list[str]]:
    """A row: the paper item, the first sentence of what it shows, the rules that make its
    files (by :func:`producers`) and the files."""
    who = "All papers" if paper == "all" else paper.upper()
    return (f"{who}, {item}", _first_sentence(shows),
            list(dict.fromkeys(made[f] for f in files)), files)


def outputs_rows(made: dict[str, str], figures: dict, tables: dict,
                 results: str = "results") -> list[tuple[str, str, list[str], list[str]]]:
    """A row per figure and table declared (``figures`` and ``tables``: ``{paper: {name:
    declaration}}``, ``"all"`` for the whole project's tables): the paper item, what it shows,
    the rules that make it and the datasets it is drawn from, and its files; then a row per
    dataset no declaration names. ``made`` is :func:`producers` of the same configuration's
    plan."""
    rows, listed = [], set()
    for paper in sorted(figures.keys() | tables.keys(), key=lambda p: (p == "all", p)):
        folder = results if paper == "all" else f"{results}/paper_{paper}"
        for name, figure in figures.get(paper, {}).items():
            files = [f"{folder}/datasets/{d}.nc"
                     for d in dict.fromkeys(figure["datasets"].values())]
            files.append(f"{folder}/figures/{name}.png")
            rows.append(_row(paper, label(name), figure["shows"], files, made))
            listed.update(files)
        for name, table in tables.get(paper, {}).items():
            where = folder if paper == "all" else f"{folder}/tables"
            files = [f"{where}/{name}.{ext}" for ext in ("csv", "md")]
            rows.append(_row(paper, label(name, "table"), table["shows"], files, made))
            listed.update(files)
    for path in sorted(made):
        parts = path.split("/")
        if path not in listed and len(parts) == 4 and parts[2] == "datasets":
            rows.append(_row(parts[1].removeprefix("paper_"),
                             parts[3].removesuffix(".nc").replace("_", " "),
                             "A dataset no figure draws.", [path], made))
    return rows


def outputs_table(rows: list[tuple[str, str, list[str], list[str]]],
                  results: str = "results") -> str:
    """The rows (:func:`outputs_rows`) as a MyST list table, its columns sized to their
    contents; the files relative to ``results``."""
    lines = ["```{list-table}", ":header-rows: 1", ":widths: 12 44 18 26", "",
             "* - item", "  - what it shows", "  - rules", f"  - files (under `{results}/`)"]
    for item, shows, rules, files in rows:
        lines += [f"* - {item}", f"  - {shows}",
                  "  - " + ", ".join(f"`{r}`" for r in rules),
                  "  - " + ", ".join(f"`{f.removeprefix(results + '/')}`" for f in files)]
    return "\n".join(lines + ["```"]) + "\n"
