"""The report's reStructuredText as HTML: the summary page (rotorvib.pipeline.report) rendered
by docutils with its own stylesheet embedded, and the captions inside the table pages
(rotorvib.pipeline.report_tables)."""

from __future__ import annotations

from docutils.core import publish_parts, publish_string

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
