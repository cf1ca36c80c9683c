"""Text is data wherever the report shows it: a configuration string or a text of the data
files, pushed through every caption, the landing page, the summary and a table's page, and
rendered as Snakemake renders them (Jinja2, then docutils: snakemake/report/__init__.py,
``FileRecord.render`` and the global description), shows as written and does nothing: no
template expression evaluated, no raw block closed, no HTML tag, no file included."""

import os
import re
import subprocess
import sys

import jinja2
import pytest
from docutils.core import publish_parts

from conftest import ROOT
from rotorvib.io.tables import write_table
from rotorvib.pipeline import report, report_pages, report_tables


@pytest.fixture
def secret(tmp_path):
    """A local file whose content must never reach a page."""
    path = tmp_path / "secret.txt"
    path.write_text("TOP-SECRET-7f3a\n")
    return path


def payloads(secret) -> list[str]:
    return [
        "{{ 1000+337 }}",
        "{% endraw %}{{ 7*191 }}{% raw %}",
        "{{ snakemake.config.results }}",
        "{# a comment hides the rest",
        "<img src=x onerror=alert(1)>",
        "<script>alert(1)</script>",
        f"\n\n.. include:: {secret}\n\n",
        "\n\n.. raw:: html\n\n   <b id=raw>raw</b>\n\n",
        "`click <javascript:alert(1)>`_",
        "|sub| *em* **strong** [1]_ \\",
        "tab\there, nul\x00 and bell\x07",
    ]


class _Snakemake:
    """What Snakemake hands a caption's template (the parts a payload could reach)."""
    config = {"results": "LEAKED-RESULTS-DIR"}


def snakemake_renders(rst: str) -> str:
    """``rst`` as Snakemake's report renders a caption: a Jinja2 template (its environment's
    settings), then docutils with its default settings and no configuration file."""
    environment = jinja2.Environment(trim_blocks=True, lstrip_blocks=True)
    text = environment.from_string(rst).render(snakemake=_Snakemake, categories={}, files={})
    return publish_parts(text, writer="html",
                         settings_overrides={"_disable_config": True})["body"]


def assert_inert(page: str, secret) -> None:
    for evaluated in ("1337", "LEAKED-RESULTS-DIR", "TOP-SECRET"):
        assert evaluated not in page
    assert str(7 * 191) not in page
    for tag in ("<img src=x", "<script>alert", "<b id=raw", 'href="javascript:alert'):
        assert tag not in page
    assert 'class="system-message"' not in page


def test_every_caption_text_is_inert(secret, tmp_path):
    texts = payloads(secret)
    row = {"paper": "B", "item": "Fig 8", "quantity": texts[0], "unit": texts[4],
           "source": "printed", "paper_value": "9.04", "reproduced": "5.98",
           "rel_error": "0.3", "verdict": texts[1], "explanation": " | ".join(texts),
           "paper_says": texts[2], "margin": "", "uncertainty": "", "margin_unit": "",
           "margin_basis": ""}
    claims = {("B", texts[0]): texts[3]}
    for i, text in enumerate(texts):
        caption = report.caption(text, text, [row], claims, key=[text], parameters=text)
        report.write_caption(tmp_path / f"{i}.rst", caption)
        page = snakemake_renders((tmp_path / f"{i}.rst").read_text())
        assert_inert(page, secret)
        # shown as written: the words of the payload survive, escaped for HTML
        assert "1000+337" in snakemake_renders(report.caption(texts[0], "", None))


def test_the_landing_page_and_summary_are_inert(secret):
    texts = payloads(secret)
    table = [{"paper": "B", "item": t, "quantity": t, "unit": "", "source": "printed",
              "paper_value": "", "reproduced": "", "rel_error": "", "verdict": "MAJOR",
              "explanation": t, "finding": t, "paper_says": t, "margin": "",
              "uncertainty": "", "margin_unit": "", "margin_basis": ""} for t in texts]
    papers = {"A": {"title": " ".join(texts), "citation": texts[1], "summary": texts[6]}}
    links = "\n\n" + "\n".join(f".. _{name}: javascript:app.showCategory('{name}')"
                              for name in report.categories("a").values()) + "\n"
    landing = snakemake_renders(report.landing_page(table, papers) + links)
    assert_inert(landing, secret)
    assert "{{ 1000+337 }}" in landing
    summary = report_pages.rst_to_html(report.summary_text(table, {}, papers, texts[5]))
    assert_inert(summary, secret)


def test_a_papers_entry_that_is_not_a_letter_is_refused():
    with pytest.raises(ValueError, match="data/papers.yaml: paper 'A`_ x' is not one capital"):
        report.landing_page([], {"A`_ x": {"title": "t"}})


def test_a_tables_page_shows_its_cells_as_text(secret):
    texts = payloads(secret)
    csv_text = "name,value\n" + "".join(f'"{t.replace(chr(34), chr(34) * 2)}",1.5\n'
                                        for t in texts)
    caption = report_pages.rst_fragment(report.caption(texts[0], texts[4], None))
    page = report_tables.table_page(texts[5], caption, csv_text, texts[4])
    assert_inert(page, secret)
    assert "&lt;img src=x onerror=alert(1)&gt;" in page


def test_our_docutils_calls_refuse_directives_even_unescaped(secret):
    """Defence in depth: a text that reached reST unescaped includes no file and passes no
    raw HTML, in our pages (report_pages) and, through the project's docutils.conf, in
    Snakemake's own rendering when it runs in the project folder."""
    rst = f"x\n\n.. include:: {secret}\n\n.. raw:: html\n\n   <b id=raw>raw</b>\n"
    with pytest.raises(Exception, match="directive disabled"):
        report_pages.rst_fragment(rst)
    code = ("import sys; from docutils.core import publish_parts; "
            "sys.stdout.write(publish_parts(sys.stdin.read(), writer_name='html')['body'])")
    shown = subprocess.run([sys.executable, "-c", code], input=rst, capture_output=True,
                           text=True, cwd=ROOT, check=True, env={**os.environ}).stdout
    assert "TOP-SECRET" not in shown and "<b id=raw" not in shown
    assert '&quot;include&quot; directive disabled' in shown


def test_snakemakes_rendering_refuses_directives_in_another_folder(secret, tmp_path):
    """Run as another workflow's module, Snakemake renders the report in the caller's folder,
    whose docutils.conf may enable what the project's disables: the workflow makes the
    project's file the last docutils reads (common.smk), and it wins."""
    (tmp_path / "docutils.conf").write_text(
        "[general]\nraw_enabled: true\nfile_insertion_enabled: true\n")
    rst = f"x\n\n.. include:: {secret}\n\n.. raw:: html\n\n   <b id=raw>raw</b>\n"
    render = ("import sys; from docutils.core import publish_parts; "
              "sys.stdout.write(publish_parts(sys.stdin.read(), writer_name='html')['body'])")
    pinned = ("from pathlib import Path; from rotorvib.pipeline.report_pages import "
              f"read_docutils_settings_last; read_docutils_settings_last(Path({str(ROOT)!r}) / "
              "'docutils.conf'); ")
    env = {k: v for k, v in os.environ.items() if k != "DOCUTILSCONFIG"}
    shown = [subprocess.run([sys.executable, "-c", code], input=rst, capture_output=True,
                            text=True, cwd=tmp_path, check=True, env=env).stdout
             for code in (render, pinned + render)]
    assert "TOP-SECRET" in shown[0] and "<b id=raw" in shown[0]    # the caller's file alone
    assert "TOP-SECRET" not in shown[1] and "<b id=raw" not in shown[1]
    assert '&quot;include&quot; directive disabled' in shown[1]


def test_markdown_tables_show_their_cells_as_text(secret, tmp_path):
    texts = payloads(secret)
    write_table([{"what": t, "n": 1.0} for t in texts], tmp_path / "t.csv", tmp_path / "t.md",
                title="t")
    lines = (tmp_path / "t.md").read_text().splitlines()
    rows = lines[lines.index("|---|---|") + 1:]
    assert len(rows) == len(texts)                  # no cell breaks its row
    assert all(len(re.split(r"(?<!\\)\|", r)) == 4 for r in rows)   # two cells each
    assert not any("<img" in r or "<script" in r for r in rows)
