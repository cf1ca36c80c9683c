"""rotorvib.pipeline.snakemake_rules uses Snakemake's ``Rule`` objects beyond the documented
API: this fails loudly on a Snakemake whose ``Rule`` changed what it relies on."""

import inspect
import re

import snakemake
from snakemake.rules import Rule

from conftest import ROOT
from rotorvib.pipeline.snakemake_rules import USED


def test_the_pinned_snakemake_is_the_one_installed():
    pinned = re.search(r"^snakemake==(\S+)$", (ROOT / "environment.txt").read_text(), re.M)
    assert pinned and snakemake.__version__ == pinned.group(1)


def test_rule_still_has_the_methods_the_workflow_uses():
    for name, parameters in USED.items():
        method = getattr(Rule, name, None)
        assert callable(method), f"snakemake.rules.Rule.{name} is gone"
        assert tuple(inspect.signature(method).parameters) == parameters, name
    for attribute in ("script", "basedir", "params", "name"):
        assert attribute in inspect.getsource(Rule.__init__), attribute
