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


def _row(paper: str, item: str, shows: str, files: list[str], made: dict[str, str]) -> str:
    """A row of the table; a ``|`` in a text is escaped (it would end the cell)."""
    shows = _first_sentence(shows).replace("|", "\\|")
    rules = ", ".join(f"`{r}`" for r in dict.fromkeys(made[f] for f in files))
    paths = ", ".join(f"`{f}`" for f in files)
    who = "all" if paper == "all" else paper.upper()
    return f"| {who} | {item} | {shows} | {rules} | {paths} |"


def outputs_table(made: dict[str, str], figures: dict, tables: dict,
                  results: str = "results") -> str:
    """A Markdown table, a row per figure and table declared (``figures`` and ``tables``:
    ``{paper: {name: declaration}}``, ``"all"`` for the whole project's tables): the paper
    item, what it shows, the rules that make it and the datasets it is drawn from, and its
    files; then a row per dataset no declaration names. ``made`` is :func:`producers` of the
    same configuration's plan."""
    lines = ["| paper | item | what it shows | rules | files |", "|---|---|---|---|---|"]
    listed: set[str] = set()
    for paper in sorted(figures.keys() | tables.keys(), key=lambda p: (p == "all", p)):
        folder = results if paper == "all" else f"{results}/paper_{paper}"
        for name, figure in figures.get(paper, {}).items():
            files = [f"{folder}/datasets/{d}.nc"
                     for d in dict.fromkeys(figure["datasets"].values())]
            files.append(f"{folder}/figures/{name}.png")
            lines.append(_row(paper, label(name), figure["shows"], files, made))
            listed.update(files)
        for name, table in tables.get(paper, {}).items():
            where = folder if paper == "all" else f"{folder}/tables"
            files = [f"{where}/{name}.{ext}" for ext in ("csv", "md")]
            lines.append(_row(paper, label(name, "table"), table["shows"], files, made))
            listed.update(files)
    for path in sorted(made):
        parts = path.split("/")
        if path not in listed and len(parts) == 4 and parts[2] == "datasets":
            lines.append(_row(parts[1].removeprefix("paper_"),
                              parts[3].removesuffix(".nc").replace("_", " "),
                              "A dataset no figure draws.", [path], made))
    return "\n".join(lines) + "\n"
