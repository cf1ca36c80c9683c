"""The report stylesheet (profiles/report.css) overrides a view of the pinned Snakemake's
report by its classes: it fails here, not silently in a browser, when Snakemake's template
changes them."""

import re
from pathlib import Path

import snakemake

from conftest import ROOT

TEMPLATE = Path(snakemake.__file__).parent / "report/html_reporter/template/components"


def test_the_stylesheet_selects_snakemakes_content_view():
    css = (ROOT / "profiles/report.css").read_text()
    selectors = re.findall(r"^([.\w-]+(?:\.[\w-]+)*)\s*\{", css, flags=re.MULTILINE)
    assert selectors, "no rule in the stylesheet"
    template = (TEMPLATE / "content.js").read_text()
    class_lists = [set(c.split()) for c in re.findall(r"className:\s*\"([^\"]+)\"", template)]
    for selector in selectors:
        wanted = set(selector.strip(".").split("."))
        assert any(wanted <= classes for classes in class_lists), (
            f"{selector} matches no element of the pinned Snakemake's content view")


def test_every_shipped_profile_ships_the_stylesheet():
    """A --workflow-profile replaces the default profile: each shipped one names the
    stylesheet, from its own folder (Snakemake finds a profile's path there first), so that
    the report looks the same whichever is given, and in a deployment, which copies
    profiles/ whole."""
    profiles = sorted((ROOT / "profiles").glob("*/config.yaml"))
    assert {p.parent.name for p in profiles} == {"default", "slurm"}
    for path in profiles:
        named = re.search(r"^report-stylesheet:\s*(\S+)\s*$", path.read_text(), re.MULTILINE)
        assert named and (path.parent / named.group(1)).resolve() == ROOT / "profiles/report.css"
