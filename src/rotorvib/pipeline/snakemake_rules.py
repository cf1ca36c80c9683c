"""The one place the workflow uses Snakemake's objects beyond its documented API.

Snakemake documents rules as they are written in a Snakefile, not the ``Rule`` objects the
Snakefile can reach through ``workflow.rules``.  The workflow needs four things from them that no
public API gives: a rule's script path, to give the rule its code fingerprint as a parameter
(``Rule.set_params``), and, for an input dataset, the rule that makes it and its wildcards
(``Rule.is_producer``, ``Rule.get_wildcards``), to check on read that the dataset was made by
that rule under this run's configuration.  And three things of the workflow: whether it is read
as a module given its own ``config:`` (:func:`module_config_given`), whose configuration is
then that ``config:`` rather than the command's files, the configuration of the workflow
that reads it (:func:`caller_config`), where that ``config:`` comes from, and the name a rule
has in a module (:func:`rule_name`: the figure jobs are grouped by the batch rules they wait for).  Every such
use is here; ``tests/test_snakemake_rules.py`` fails on a Snakemake that no longer has them, so
an upgrade breaks loudly, not silently.  This module does not import Snakemake: the Snakefile hands it the
objects.
"""

from __future__ import annotations

#: The ``Rule`` methods used here, as the pinned Snakemake defines them (name: parameters).
USED = {"set_params": ("self", "params", "kwparams"), "is_producer": ("self", "requested_output"),
        "get_wildcards": ("self", "requested_output", "wildcards_dict")}


def script_path(rule) -> str | None:
    """The path of ``rule``'s script, or None for a rule without one; a path naming one of
    its parameters (``"../scripts/{params.script}.py"``, as Snakemake formats it when the job
    runs) with that parameter's value."""
    if not rule.script:
        return None
    return rule.basedir.join(rule.script.format(params=rule.params)).get_path_or_uri(
        secret_free=True)


def add_params(rule, **params) -> None:
    """Give ``rule`` more parameters (values or functions of the wildcards), as if written in
    its ``params:``."""
    rule.set_params(**params)


def producer(rules, path: str):
    """The rule of ``rules`` that makes ``path``, or None for a file no rule makes (one of the
    workflow's own, such as the papers' values)."""
    return next((rule for rule in rules if rule.is_producer(path)), None)


def rule_name(workflow, name: str) -> str:
    """The name that the rule written as ``name`` has in this run: prefixed where the workflow
    is read as another's module (``use rule * from rotorvib as rotorvib_*``)."""
    return workflow.modifier.modify_rulename(name)


def module_config_given(workflow) -> bool:
    """Whether the Snakefile being read is a module of another workflow given a ``config:`` of
    its own (Snakemake then skips the module's ``configfile:``, ``WorkflowModifier``)."""
    modifier = workflow.modifier
    return bool(modifier.is_module and modifier.skip_configfile)


def caller_config(workflow) -> dict:
    """The configuration of the workflow that reads this one as a module, as Snakemake read it
    (the globals of its first ``WorkflowModifier``, the calling Snakefile's), where the module's
    ``config:`` is looked for (:func:`rotorvib.pipeline.config_sources.module_config`)."""
    return workflow.modifier_stack[0].globals["config"]


def wildcards(rule, path: str) -> dict:
    """The wildcards of ``rule`` that make ``path``."""
    return dict(rule.get_wildcards(path))
