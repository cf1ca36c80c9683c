"""The one place the workflow uses Snakemake's objects beyond its documented API.

Snakemake documents rules as they are written in a Snakefile, not the ``Rule`` objects the
Snakefile can reach through ``workflow.rules``.  The workflow needs four things from them that no
public API gives: a rule's script path, to give the rule its code fingerprint as a parameter
(``Rule.set_params``), and, for an input dataset, the rule that makes it and its wildcards
(``Rule.is_producer``, ``Rule.get_wildcards``), to check on read that the dataset was made by
that rule under this run's configuration; and what a rule declares, as the workflow's plan
reads it (:func:`declared`: its inputs and outputs, resources, priority, benchmark, and whether
it is a ``localrule``).  And two things of the workflow: whether it is read as a module given
its own ``config:`` (:func:`module_config_given`), whose configuration is then that ``config:``
rather than the command's files, and the configuration of the workflow that reads it
(:func:`caller_config`), where that ``config:`` comes from.  Every such use is here;
``tests/test_snakemake_rules.py`` fails on a Snakemake that no longer has them, so an upgrade
breaks loudly, not silently.  This module does not import Snakemake: the Snakefile hands it the
objects.
"""

from __future__ import annotations

from pathlib import Path

from rotorvib.pipeline.plan import Maker

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


def declared(workflow, rule, root: Path) -> Maker:
    """What ``rule`` declares, as the plan reads it: its inputs (None for an input function)
    and outputs, whether it is a batch rule (``resources: batch=1``), whether it is a
    ``localrule`` (the workflow's set of them: ``Workflow.is_local`` says True of every rule when
    nothing is sent to a cluster), its priority, whether it has a benchmark, and its script
    relative to the workflow's folder ``root``."""
    script = script_path(rule)
    return Maker(
        name=rule.name,
        inputs=tuple(None if callable(item) else str(item) for item in rule.input),
        outputs=tuple(str(item) for item in rule.output),
        batch="batch" in rule.resources,
        local=rule.name in workflow._localrules or rule.norun,
        priority=rule.priority,
        benchmark=rule.benchmark is not None,
        script=None if script is None else str(Path(script).resolve().relative_to(root)),
    )


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
