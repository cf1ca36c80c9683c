"""The outputs declared as data: what each figure draws and shows, what each table shows.
Each paper package declares its own in ``rotorvib.papers.<p>.outputs`` as pure functions of
its configuration section (``figures(section)``, ``tables(section)``), and this module the
whole project's (:data:`PROJECT_TABLES`); the workflow reads them to make its figure jobs,
report entries and final files, the docs their table of outputs, and no job imports them."""

from __future__ import annotations


def figure(function: str, datasets: dict[str, str], shows: str, items=(), **options) -> dict:
    """A figure drawn by ``rotorvib.papers.<p>.figures.<function>(**datasets, paper=<the
    paper's printed values>, **options)``: ``datasets`` maps the function's arguments to the
    names of the paper's datasets it reads, ``shows`` is the first sentence of its caption and
    ``items`` the comparison items it shows beyond those its name numbers ("Fig 8" for
    ``fig8``)."""
    return {"function": function, "datasets": dict(datasets), "shows": shows,
            "items": list(items), "options": options}


def table(shows: str, items=()) -> dict:
    """A table the report shows: what it shows and the comparison items beyond those its name
    numbers ("Table 2" for ``table2``)."""
    return {"shows": shows, "items": list(items)}


#: The whole project's tables (results/<name>.csv and .md), written by rule comparison.
PROJECT_TABLES = {
    "comparison": table(
        "Every value and claim the papers state (data/paper_values.csv) beside the "
        "reproduced value, with the relative error, the verdict and the explanation of each "
        "difference."),
    "discrepancies": table(
        "Each printed number the reproduction misses, tested against alternative readings of "
        "the paper (definitions, variants, parameter slips, units, rounding): the value each "
        "hypothesis gives and whether it reproduces the printed one (within the MATCH "
        "tolerance); an inversion gives the single parameter value that would."),
}
