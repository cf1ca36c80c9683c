"""Where a ``snakemake`` command's configuration comes from, read as a configuration file is
(:mod:`rotorvib.pipeline.strict_yaml`) whatever door it came through, so that one configuration
gets one verdict: the files (the Snakefile's ``configfile:``, ``--configfile``), the raw text of
the ``--config`` entries (:func:`command_line_overrides`), and, where the workflow is another
workflow's module, that workflow's ``config:`` (:func:`module_config`). Snakemake reads each of
these with YAML 1.1 first (``0777`` is 511, ``1:30`` is 90, a duplicate key keeps its last
value); what it read is used only where no text is left to read again.
"""

from __future__ import annotations

import copy
import re
from typing import Any

import yaml

from rotorvib.pipeline.strict_yaml import (
    ConfigError,
    DuplicateKey,
    check_shape,
    check_value,
    load_value,
    load_yaml,
)


def _key(path) -> str:
    return ".".join(str(p) for p in path) or "<root>"


def merge(base: dict, override: dict) -> dict:
    """``base`` updated by ``override`` key by key at every depth (as Snakemake merges
    ``--configfile`` files)."""
    merged = copy.deepcopy(base)
    for key, value in override.items():
        if isinstance(value, dict) and isinstance(merged.get(key), dict):
            merged[key] = merge(merged[key], value)
        else:
            merged[key] = copy.deepcopy(value)
    return merged


def typed_overrides(overrides: dict) -> dict:
    """``--config`` overrides with the values inside nested keys read as YAML.

    Snakemake reads ``--config paper_c='{den_hartog: {d: 0.09}}'`` with YAML's base loader,
    which leaves every nested value a string ("0.09"); each such string is read again here as
    a value of a configuration file would be (:func:`rotorvib.pipeline.strict_yaml.load_value`:
    ``0.09`` and ``1e-9`` are numbers, ``printed`` stays a string, ``0777`` is refused naming
    its key). Top-level values, which Snakemake already types, are kept. The overrides' shape
    is checked first (:func:`rotorvib.pipeline.strict_yaml.check_value`: Snakemake keeps an
    alias as one shared object, which is typed once). Only ``--config`` values come here: a
    configuration file is read once, by :func:`load_yaml`."""
    check_value(overrides, "--config")
    typed_once: dict[int, Any] = {}

    def typed(value, path):
        if id(value) in typed_once:
            return typed_once[id(value)]
        if isinstance(value, dict):
            result = {key: typed(item, path + (key,)) for key, item in value.items()}
        elif isinstance(value, list):
            result = [typed(item, path + (str(i),)) for i, item in enumerate(value)]
        elif isinstance(value, str):
            try:
                result = load_value(value, f"--config {_key(path)}")
            except yaml.YAMLError:
                result = value
        else:
            result = value
        if isinstance(value, (dict, list)):
            typed_once[id(value)] = result
        return result

    return {key: typed(value, (key,)) if isinstance(value, (dict, list)) else value
            for key, value in overrides.items()}


#: A ``--config`` key as Snakemake accepts it (snakemake.cli.parse_config).
_TOP_KEY = re.compile(r"[a-zA-Z_][\w-]*\w$")


def command_line_overrides(entries) -> dict:
    """``--config KEY=VALUE ...`` entries as Snakemake reads them (an integer, a number,
    ``true``/``false``, else YAML read as text, else the text), each value's shape checked
    first and its text read strictly, so that a duplicate key inside it is refused as in a file
    (Snakemake keeps its last value); :class:`ConfigError` naming the entry for what Snakemake
    would stop on with a traceback: an entry without ``=`` (a target written after ``--config``
    is taken for one) and a key that is not a top-level name (``paper_b.shards=2``), and for a
    key given twice (Snakemake merges the two values)."""
    overrides: dict = {}
    for entry in entries:
        key, sep, text = entry.partition("=")
        if not sep:
            raise ConfigError(f"--config {entry!r}: not KEY=VALUE; a target written after "
                              "--config is read as one of its entries: put targets first")
        if not _TOP_KEY.match(key):
            raise ConfigError(f"--config {entry!r}: {key!r} is not a top-level key; write a "
                              "nested key as YAML, e.g. paper_b='{shards: 2}'")
        if key in overrides:
            raise DuplicateKey(f"--config {entry!r}: duplicate key {key!r} (Snakemake would "
                               "merge the two values); give each key once")
        overrides[key] = _snakemake_value(text, f"--config {key}")
    return typed_overrides(overrides)


def _snakemake_value(text: str, name: str):
    """One ``--config`` value read as Snakemake reads it, its YAML shape checked first."""
    for parse in (int, float):
        try:
            return parse(text)
        except ValueError:
            pass
    if text in ("true", "false", "True", "False"):
        return text.lower() == "true"
    check_shape(text, name)
    try:
        load_value(text, name)            # a key given twice, which Snakemake would drop
    except (yaml.YAMLError, ConfigError) as error:
        if isinstance(error, DuplicateKey):
            raise
    try:
        return yaml.load(text, Loader=yaml.BaseLoader)
    except yaml.YAMLError:
        return text


def workflow_config(base_files, files, overrides: dict, *, replace_base: bool = False) -> dict:
    """The configuration of a ``snakemake`` command, read here rather than taken from
    Snakemake's own reading (YAML 1.1, templates evaluated): the workflow's ``configfile``
    ``base_files`` (unless ``replace_base``, Snakemake's ``--replace-workflow-config``), then
    each ``--configfile`` of ``files`` in order, then the ``--config`` ``overrides`` (as
    :func:`command_line_overrides` reads them), merged key by key as Snakemake merges them."""
    config: dict = {}
    for path in ([] if replace_base else list(base_files)) + list(files):
        config = merge(config, load_yaml(path))
    return merge(config, overrides)


def module_config(given: dict, caller: dict, read_caller) -> dict:
    """The ``config:`` that another workflow gives this one as a module, read as a file is.

    Snakemake hands the module the value the caller's Snakefile computed, typically a part of
    the caller's configuration (``config: config["rotorvib"]``, or the whole of it, as
    ``snakedeploy`` writes), which Snakemake read from the caller's files with YAML 1.1. Where
    ``given`` is such a part (the very object, found in ``caller``, the caller's configuration
    as Snakemake read it), that part of ``read_caller()`` (the caller's files and ``--config``
    read strictly, :func:`workflow_config`) is returned instead: ``0777``, ``1:30``, a duplicate
    key or a syntax error is refused with its file, line and column, as in a file given to
    this workflow. A part the caller's Snakefile changed after reading is refused naming the
    key (its change would be lost); a mapping the caller builds in Python is taken as given,
    with the checks a value already built allows
    (:func:`rotorvib.pipeline.strict_yaml.check_value`: no key that is not text, as YAML 1.1
    makes of ``on:``, ``yes:`` or ``1:``; no date or other value a file here cannot hold)."""
    check_value(given, "the module's config")
    path = _path_of(given, caller)
    if path is None:
        return given
    strict = read_caller()
    for part in path:
        strict = strict.get(part) if isinstance(strict, dict) else None
    if (where := _changed(given, strict)) is not None:
        raise ConfigError(f"config key '{_key(where)}' of the module's config (the caller's "
                          f"'{_key(path + where)}') differs from the files it was read from "
                          "(changed by the calling Snakefile?): give the module a mapping of its "
                          "own, config: {...}")
    return strict


def _path_of(target, tree, path=()) -> tuple | None:
    """The keys leading from ``tree`` to the object ``target`` itself, or None."""
    if tree is target:
        return path
    if isinstance(tree, dict):
        for key, value in tree.items():
            if isinstance(value, dict) and (found := _path_of(target, value, path + (key,))):
                return found
    return None


def _changed(given, strict, path=()) -> tuple | None:
    """The first key where ``given`` (Snakemake's YAML 1.1 reading, perhaps edited) and
    ``strict`` (the files read strictly) differ beyond the one reading that differs in an
    accepted file (YAML 1.1 reads ``1e-9``, an exponent without a dot, as text), or None."""
    if isinstance(given, dict) and isinstance(strict, dict):
        for key in given.keys() | strict.keys():
            if key not in given or key not in strict:
                return path + (key,)
            if (where := _changed(given[key], strict[key], path + (key,))) is not None:
                return where
        return None
    if isinstance(given, list) and isinstance(strict, list) and len(given) == len(strict):
        return next((where for i, (a, b) in enumerate(zip(given, strict))
                     if (where := _changed(a, b, path + (str(i),))) is not None), None)
    if isinstance(given, str) and isinstance(strict, float):
        try:
            return None if float(given) == strict else path
        except ValueError:
            return path
    return None if given == strict and type(given) is type(strict) else path
