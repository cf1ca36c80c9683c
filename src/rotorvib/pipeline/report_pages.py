"""The report's reStructuredText as HTML: the summary page (rotorvib.pipeline.report) rendered
by docutils with its own stylesheet embedded, and the captions inside the table pages
(rotorvib.pipeline.report_tables)."""

from __future__ import annotations

import os
from pathlib import Path

from docutils.core import publish_parts, publish_string
from docutils.frontend import OptionParser

#: docutils settings of every page written here: any warning raises, and no directive may
#: include a file or pass raw HTML through (the texts are escaped, rotorvib.pipeline.report.rst_text;
#: this holds even where one is not).
_SETTINGS = {"halt_level": 2, "report_level": 2, "_disable_config": True,
             "raw_enabled": False, "file_insertion_enabled": False}


#: What a page adds to docutils' own stylesheet: the report's sans-serif face (docutils' is
#: a serif), the frame's whole width (docutils keeps 50em), and a table that fits it, or
#: scrolls inside its own box where it cannot, instead of being cut at the page's edge (the
#: summary's verdict table, at 1400 pixels and on a phone).
PAGE_STYLE = """<style>
body { font: 15px/1.5 system-ui, sans-serif; color: #1e293b; }
main { max-width: none; padding: 0 1em; }
p, li { overflow-wrap: anywhere; }
table { display: block; max-width: 100%; overflow-x: auto; font-size: .9em; }
th, td { padding: .2em .4em; }
</style>
"""


def rst_to_html(text: str) -> str:
    """``text`` (reStructuredText) as a standalone HTML page (with :data:`PAGE_STYLE`); any
    docutils warning raises."""
    page = publish_string(text, writer_name="html5", settings_overrides={
        **_SETTINGS, "embed_stylesheet": True, "output_encoding": "unicode"}).strip() + "\n"
    return page.replace("</head>", PAGE_STYLE + "</head>", 1)


def rst_fragment(text: str) -> str:
    """``text`` (reStructuredText) as an HTML fragment (a caption inside a page)."""
    return publish_parts(text, writer_name="html5", settings_overrides=_SETTINGS)["body"]


def read_docutils_settings_last(config_file: Path) -> None:
    """Make ``config_file`` the last settings file of every docutils call in this process
    (``DOCUTILSCONFIG``: the files docutils reads, each later one overriding), so that its
    settings win over any ``docutils.conf`` in the working directory.

    Snakemake renders the report's landing page and captions with docutils and passes no
    settings, so docutils takes them from its files, ``./docutils.conf`` among them: run as
    another workflow's module, the working directory is the caller's folder, and the project's
    ``docutils.conf`` (no ``include``, no ``raw``) was not read there. The calls written here
    pass their settings themselves (:data:`_SETTINGS`, no file read)."""
    files = os.environ.get("DOCUTILSCONFIG", os.pathsep.join(OptionParser.standard_config_files))
    kept = [f for f in files.split(os.pathsep) if f.strip() and f != str(config_file)]
    os.environ["DOCUTILSCONFIG"] = os.pathsep.join([*kept, str(config_file)])
