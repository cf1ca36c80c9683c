"""The configuration files' YAML: one meaning for every text, or a refusal that says where.

PyYAML reads YAML 1.1, where ``0777`` is 511, ``1:30`` is 90, ``yes`` is true and ``1e-9`` is
text.  The loaders here resolve plain scalars by the YAML 1.2 core schema instead (``null``,
``true``/``false``, decimal, ``0o`` and ``0x`` integers, floats with or without an exponent,
``.inf``, ``.nan``) and refuse, with file, line and column, every plain scalar that YAML 1.1
would read otherwise (octal-looking and sexagesimal numbers, numbers with ``_``, ``0b``
binaries, ``yes``/``no``/``on``/``off``): quoting it makes it text.  They also
refuse a duplicate key (YAML keeps the last value silently), a key that is not text, the keys
of Snakemake's YTE templates (a template runs Python), a file above :data:`MAX_BYTES` and a
document whose aliases expand to more than :data:`MAX_NODES` values.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

#: Size of a configuration file at most (the project's own is 17 kB).
MAX_BYTES = 1_000_000
#: Values of a configuration at most, counting each alias as the whole value it repeats.
MAX_NODES = 1_000_000
#: Keys of Snakemake's YTE template engine, which evaluates Python in a configuration file.
TEMPLATE_KEYS = ("__use_yte__", "__definitions__", "__variables__")


class ConfigError(ValueError):
    """A configuration that cannot be read or does not satisfy the schema; the message says
    where and why."""


_CORE = [   # YAML 1.2 core schema: (tag, pattern, first characters)
    ("tag:yaml.org,2002:null", r"^(?:~|null|Null|NULL|)$", ["~", "n", "N", ""]),
    ("tag:yaml.org,2002:bool", r"^(?:true|True|TRUE|false|False|FALSE)$", list("tTfF")),
    ("tag:yaml.org,2002:int", r"^(?:[-+]?(?:0|[1-9][0-9]*)|0o[0-7]+|0x[0-9a-fA-F]+)$",
     list("-+0123456789")),
    ("tag:yaml.org,2002:float",
     r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
     r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$", list("-+0123456789.")),
]
_AMBIGUOUS_TAG = "tag:rotorvib,2026:yaml-1.1-only"
# plain scalars YAML 1.1 types differently from YAML 1.2 (checked before the core patterns)
_AMBIGUOUS = re.compile(
    r"^(?:[-+]?0[0-9]+(?:\.[0-9]*)?(?:[eE][-+]?[0-9]+)?"          # 0777: octal in 1.1
    r"|[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+(?:\.[0-9_]*)?"          # 1:30: sexagesimal
    r"|[-+]?(?:[0-9]+_[0-9_]*|0b[01_]+)(?:\.[0-9_]*)?"            # 1_000, 0b101
    r"|yes|Yes|YES|no|No|NO|on|On|ON|off|Off|OFF)$")


def _core_resolvers(loader: type) -> None:
    loader.yaml_implicit_resolvers = {}
    loader.add_implicit_resolver(_AMBIGUOUS_TAG, _AMBIGUOUS, list("-+0123456789yYnNoO"))
    for tag, pattern, first in _CORE:
        loader.add_implicit_resolver(tag, re.compile(pattern), first)


def _ambiguous(loader, node):
    mark = node.start_mark
    raise ConfigError(
        f"{mark.name}:{mark.line + 1}:{mark.column + 1}: {node.value!r} reads differently in "
        "YAML 1.1 and 1.2 (an octal or sexagesimal number, a number with '_', or a yes/no/on/off "
        "word); write the number in decimal, true or false, or quote it for text")


class _Strict:
    """Mappings with text keys, each once; the YTE template keys refused."""

    def construct_mapping(self, node, deep=False):
        seen = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=deep)
            mark = key_node.start_mark
            where = f"{mark.name}:{mark.line + 1}:{mark.column + 1}"
            if not isinstance(key, str):
                raise ConfigError(f"{where}: key {key!r} is a {type(key).__name__}, not text; "
                                  "quote it")
            if key in TEMPLATE_KEYS:
                raise ConfigError(f"{where}: {key!r} asks for Snakemake's YTE templates, which "
                                  "run Python from the file; configuration files here are data")
            if key in seen:
                raise ConfigError(f"{where}: duplicate key {key!r} (first at line "
                                  f"{seen[key] + 1}); YAML would silently keep the last value")
            seen[key] = mark.line
        return super().construct_mapping(node, deep=deep)


class StrictLoader(_Strict, yaml.SafeLoader):
    """The strict YAML 1.2 loader on PyYAML's own parser, whose syntax errors say most (that a
    tab cannot indent, for one)."""


class FastStrictLoader(_Strict, getattr(yaml, "CSafeLoader", yaml.SafeLoader)):
    """The same on libyaml's parser, where PyYAML has it: a fifth of the time on the
    configuration and the schema, which every ``snakemake`` command reads."""


for _loader in (StrictLoader, FastStrictLoader):
    _core_resolvers(_loader)
    _loader.add_constructor(_AMBIGUOUS_TAG, _ambiguous)


def expanded_size(value: Any, memo: dict | None = None) -> int:
    """The number of values in ``value`` with every alias counted as the whole value it repeats
    (computed once per distinct object, so an alias bomb is measured without expanding it)."""
    memo = {} if memo is None else memo
    if id(value) in memo:
        return memo[id(value)]
    if isinstance(value, dict):
        size = 1 + sum(expanded_size(v, memo) for v in value.values()) + len(value)
    elif isinstance(value, list):
        size = 1 + sum(expanded_size(v, memo) for v in value)
    else:
        size = 1
    memo[id(value)] = size
    return size


def _load(stream, loader) -> Any:
    """The single document of ``stream`` (an open file names its marks)."""
    reader = loader(stream)
    try:
        return reader.get_single_data()
    finally:
        reader.dispose()


def _load_file(path: str | Path, loader) -> Any:
    with open(path, encoding="utf-8") as fh:
        return _load(fh, loader)


def load_yaml(path: str | Path) -> dict:
    """A YAML mapping from ``path``, read strictly (module docstring); :class:`ConfigError`
    with file, line and column for a syntax error, an ambiguous scalar, a duplicate or
    non-text key or a template key, and for a file too large, an alias expansion too large or
    a document that is not a mapping."""
    size = Path(path).stat().st_size
    if size > MAX_BYTES:
        raise ConfigError(f"{path}: {size} bytes; a configuration file may have at most "
                          f"{MAX_BYTES}")
    try:
        try:
            data = _load_file(path, FastStrictLoader)
        except yaml.YAMLError:  # read again for the more telling message
            data = _load_file(path, StrictLoader)
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text ({error.reason} at byte {error.start})") \
            from None
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        problem = error.problem or error.context
        hint = "; tabs are not allowed for indentation" if "\\t" in str(problem) else ""
        raise ConfigError(f"{where}: {problem} (YAML syntax{hint})") from None
    except yaml.YAMLError as error:
        raise ConfigError(f"{path}: {error} (YAML)") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: a configuration file must be a mapping of keys, not "
                          f"{type(data).__name__}")
    nodes = expanded_size(data)
    if nodes > MAX_NODES:
        raise ConfigError(f"{path}: its aliases expand to {nodes:.3g} values; at most "
                          f"{MAX_NODES:.0e}")
    return data


def load_value(text: str) -> Any:
    """One value of a ``--config`` override, read as in a configuration file."""
    return _load(text, StrictLoader)
