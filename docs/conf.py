"""Sphinx configuration of the rotorvib documentation (Markdown pages through MyST, the API
reference from the package's docstrings).  Build: ``sphinx-build -W -b html docs
docs/_build/html``; the tests build it with warnings as errors (tests/test_docs.py)."""

from pathlib import Path

from rotorvib.pipeline.config import load_yaml
from rotorvib.pipeline.config_reference import reference

ROOT = Path(__file__).resolve().parents[1]

project = "rotorvib"
author = "rotorvib reproduction project"
copyright = "the rotorvib authors (code MIT, data CC-BY-4.0)"
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax"]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "_generated", "findings"]
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath"]
html_theme = "alabaster"
# the configuration reference is a wide table: use the window's width
html_theme_options = {"page_width": "95%", "body_max_width": "none"}
html_static_path = ["_static"]      # custom.css: long keys wrap inside their cells
autodoc_member_order = "bysource"
autodoc_typehints = "none"


def write_configuration_reference(app):
    """docs/_generated/configuration-reference.md from config/schema.yaml and the comments of
    config/config.yaml, on every build."""
    _write(ROOT / "docs/_generated/configuration-reference.md",
           reference(ROOT / "config/schema.yaml", ROOT / "config/config.yaml"))


def write_papers(app):
    """docs/_generated/papers.md: each paper's citation and summary from data/papers.yaml."""
    papers = load_yaml(ROOT / "data/papers.yaml")
    text = "\n".join(f"- **{letter}.** {paper['citation'].strip()} *Summary:* "
                      f"{paper['summary'].strip()}\n" for letter, paper in sorted(papers.items()))
    _write(ROOT / "docs/_generated/papers.md", text)


def write_outputs_table(app):
    """docs/_generated/outputs.md: where each paper item lands, from the papers' output
    declarations and the paper configuration's plan (``snakemake --summary``: each output file
    and its rule; rotorvib.pipeline.outputs_table), on every build."""
    import importlib
    import subprocess
    import sys

    from rotorvib.papers.outputs import PROJECT_TABLES
    from rotorvib.pipeline.outputs_table import outputs_rows, outputs_table, producers

    plan = subprocess.run([sys.executable, "-m", "snakemake", "--summary", "--nolock"],
                          cwd=ROOT, capture_output=True, text=True, check=True).stdout
    config = load_yaml(ROOT / "config/config.yaml")
    papers = {key.removeprefix("paper_"): section for key, section in config.items()
              if key.startswith("paper_")}
    declared = {p: importlib.import_module(f"rotorvib.papers.{p}.outputs") for p in papers}
    _write(ROOT / "docs/_generated/outputs.md", outputs_table(outputs_rows(
        producers(plan), {p: m.figures(papers[p]) for p, m in declared.items()},
        {**{p: m.tables(papers[p]) for p, m in declared.items()}, "all": PROJECT_TABLES})))


def write_api(app):
    """docs/api/<module>.md: a page per module of the package with its public members, and
    docs/_generated/api.md: their table of contents, in the order of the layers (a module added
    to the package appears by itself; the pages of modules that are gone are removed)."""
    import pkgutil

    import rotorvib

    modules = sorted(m.name for m in pkgutil.walk_packages(rotorvib.__path__, "rotorvib."))
    order = ["rotorvib.models", "rotorvib.methods", "rotorvib.papers.outputs",
             "rotorvib.papers.config_problems", "rotorvib.papers",
             "rotorvib.comparison.paper_values", "rotorvib.comparison.choices",
             "rotorvib.comparison.verdicts", "rotorvib.comparison.reproduced",
             "rotorvib.comparison.table", "rotorvib.comparison.reproduced_csv",
             "rotorvib.comparison.discrepancy", "rotorvib.comparison", "rotorvib.checks",
             "rotorvib.io", "rotorvib.pipeline"]
    modules.sort(key=lambda m: (next(i for i, p in enumerate(order) if m.startswith(p)), m))
    pages = ROOT / "docs/api"
    for stale in set(pages.glob("*.md")) - {pages / f"{m}.md" for m in modules}:
        stale.unlink()
    for m in modules:
        _write(pages / f"{m}.md",
               f"# `{m}`\n\n```{{eval-rst}}\n.. automodule:: {m}\n   :members:\n```\n")
    _write(ROOT / "docs/_generated/api.md", "```{toctree}\n:maxdepth: 1\n\n"
           + "".join(f"api/{m}\n" for m in modules) + "```\n")


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def check_findings(app):
    """docs/papers.md must be its template filled from the recorded paper run: a page edited
    by hand, or a record changed without regenerating it, fails the build."""
    from rotorvib.pipeline import findings

    expected = findings.render(findings.TEMPLATE.read_text(encoding="utf-8"),
                               findings.read_record(findings.RECORD))
    if findings.PAGE.read_text(encoding="utf-8") != expected:
        raise RuntimeError("docs/papers.md is not its template filled from the recorded run: "
                           "python -m rotorvib.pipeline.findings")


def setup(app):
    app.connect("builder-inited", check_findings)
    app.connect("builder-inited", write_configuration_reference)
    app.connect("builder-inited", write_papers)
    app.connect("builder-inited", write_api)
    app.connect("builder-inited", write_outputs_table)
