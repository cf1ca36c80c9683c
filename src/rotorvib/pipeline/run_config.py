"""The configuration of a run, as the Snakefile sets it before any rule is read: read strictly
(:mod:`rotorvib.pipeline.config_sources`: YAML 1.2, every door read again from its text) and
checked (:func:`rotorvib.pipeline.config.check_config`), or a :class:`ConfigError` naming the
key, file, line and column."""

from __future__ import annotations

from pathlib import Path

from rotorvib.pipeline.config import check_config
from rotorvib.pipeline.config_sources import (
    command_line_overrides,
    merge,
    module_config,
    workflow_config,
)
from rotorvib.pipeline.strict_yaml import load_yaml


def run_config(settings, configfiles, root: Path, module: tuple[dict, dict] | None) -> dict:
    """The checked configuration of a run of the workflow in ``root``.

    Read from the same files in the same order as Snakemake read them: the Snakefile's
    ``configfile:`` (those of ``configfiles``, Snakemake's list of every file it read, not given
    on the command line), each ``--configfile`` of ``settings`` (Snakemake's ``ConfigSettings``),
    then the ``--config`` entries from their text (``config_args``, which Snakemake hands to every
    job it spawns), not from its parsed values, in which a duplicate key is already gone. Where
    the workflow is another's module given a ``config:`` of its own, ``module`` is that
    ``config:`` and the caller's configuration as Snakemake read them: that configuration, read
    again from the caller's files where it came from them
    (:func:`rotorvib.pipeline.config_sources.module_config`), over the shipped defaults."""

    def files_and_entries() -> dict:
        given = [Path(f).resolve() for f in settings.configfiles]
        return workflow_config(
            [f for f in configfiles if Path(f).resolve() not in given], settings.configfiles,
            command_line_overrides(settings.config_args or ()),
            replace_base=settings.replace_workflow_config)

    if module is None:
        read = files_and_entries()
    else:
        read = merge(load_yaml(root / "config/config.yaml"),
                     module_config(*module, files_and_entries))
    return check_config(read, load_yaml(root / "config/schema.yaml"))
