"""rotorvib.pipeline.snakemake_rules uses Snakemake's ``Rule`` objects beyond the documented
API: this fails loudly on a Snakemake whose ``Rule`` changed what it relies on."""

import inspect
import re

import snakemake
from snakemake.rules import Rule

from conftest import ROOT
from rotorvib.pipeline.snakemake_rules import USED


def test_the_pinned_snakemake_is_the_one_installed():
    pinned = re.search(r"^snakemake==([^ ;]+)", (ROOT / "environment.txt").read_text(), re.M)
    assert pinned and snakemake.__version__ == pinned.group(1)


def test_rule_still_has_the_methods_the_workflow_uses():
    for name, parameters in USED.items():
        method = getattr(Rule, name, None)
        assert callable(method), f"snakemake.rules.Rule.{name} is gone"
        assert tuple(inspect.signature(method).parameters) == parameters, name
    for attribute in ("script", "basedir", "params", "name"):
        assert attribute in inspect.getsource(Rule.__init__), attribute


def test_the_workflow_modifier_still_says_whether_a_module_has_its_own_config():
    """rotorvib.pipeline.snakemake_rules.module_config_given reads these two attributes."""
    from snakemake.modules import WorkflowModifier

    source = inspect.getsource(WorkflowModifier.__init__)
    assert "self.is_module = is_module" in source
    assert "self.skip_configfile = config is not None" in source


def test_a_rule_still_declares_what_the_plan_reads():
    """rotorvib.pipeline.snakemake_rules.declared reads a rule's priority, benchmark, resources
    (a mapping that answers ``in``), ``norun`` and the workflow's set of local rules."""
    import snakemake.api  # noqa: F401  (imported first: snakemake.workflow alone is circular)
    from snakemake.resources import Resources
    from snakemake.workflow import Workflow

    for attribute in ("self.priority = 0", "self._benchmark = None", "self.norun = False"):
        assert attribute in inspect.getsource(Rule.__init__), attribute
    assert isinstance(getattr(Rule, "benchmark"), property)
    resources = Resources.from_mapping({"batch": 1})
    assert "batch" in resources and "other" not in resources
    assert "self._localrules.add(name)" in inspect.getsource(Workflow.rule)


def test_the_workflow_still_keeps_the_calling_snakefiles_config_first():
    """rotorvib.pipeline.snakemake_rules.caller_config reads the config of the first modifier,
    the calling Snakefile's (a module's own config is in the modifiers after it)."""
    import snakemake.api  # noqa: F401  (imported first: snakemake.workflow alone is circular)
    from snakemake.modules import WorkflowModifier
    from snakemake.workflow import Workflow

    assert "self.modifier_stack = [" in inspect.getsource(Workflow)
    assert 'self.globals["config"] = config' in inspect.getsource(WorkflowModifier.__init__)
