"""The configuration files' YAML: one meaning for every text, or a refusal that says where.

PyYAML reads YAML 1.1, where ``0777`` is 511, ``1:30`` is 90, ``yes`` is true and ``1e-9`` is
text.  The loaders here resolve plain scalars by the YAML 1.2 core schema instead (``null``,
``true``/``false``, decimal, ``0o`` and ``0x`` integers, floats with or without an exponent,
``.inf``, ``.nan``) and refuse, with file, line and column, every plain scalar that YAML 1.1
would read otherwise (octal-looking and sexagesimal numbers, numbers with ``_``, ``0b``
binaries, ``yes``/``no``/``on``/``off``): quoting it makes it text.  They also
refuse a duplicate key (YAML keeps the last value silently), a key that is not text, the keys
of Snakemake's YTE templates (a template runs Python), anything but a regular file (a
directory, a device, a pipe: :func:`read_text` never blocks) and a file above
:data:`MAX_BYTES`, and, from the parser's events before any value is built
(:func:`check_shape`), a document nested deeper than :data:`MAX_DEPTH`, an alias inside the
value it names, or aliases that expand to more than :data:`MAX_NODES` values.
"""

from __future__ import annotations

import io
import os
import re
import stat
from pathlib import Path
from typing import Any

import yaml

#: Size of a configuration file at most (the project's own is 17 kB).
MAX_BYTES = 1_000_000
#: Values of a configuration at most, counting each alias as the whole value it repeats (the
#: project's configuration and schema: a few thousand each).
MAX_NODES = 100_000
#: Mappings and lists inside each other at most (the project's configuration nests 6 deep).
MAX_DEPTH = 64
#: Keys of Snakemake's YTE template engine, which evaluates Python in a configuration file.
TEMPLATE_KEYS = ("__use_yte__", "__definitions__", "__variables__")


class ConfigError(ValueError):
    """A configuration that cannot be read or does not satisfy the schema; the message says
    where and why."""


class DuplicateKey(ConfigError):
    """A key given twice in one mapping (YAML would keep the last value silently)."""


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
                raise DuplicateKey(f"{where}: duplicate key {key!r} (first at line "
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


def check_value(value: Any, name: str) -> None:
    """The limits of :func:`check_shape` on a value already built (Snakemake's reading of a
    ``--config`` override, or a module's ``config:``): at most :data:`MAX_DEPTH` deep, no
    value inside itself, at most :data:`MAX_NODES` values with every repeated object counted
    each time it appears (an alias bomb is measured, not expanded); and what a strict file
    cannot hold, where YAML 1.1 (Snakemake's reading) shows through: a key that is not text
    (``on:``, ``yes:`` and ``1:`` make a bool or an int key) and a value that is not text, a
    number, true/false, null, a list or a mapping (``2024-01-01`` makes a date);
    :class:`ConfigError` naming ``name`` otherwise."""
    sizes: dict[int, int] = {}
    inside: set[int] = set()

    def size(item, depth: int) -> int:
        if not isinstance(item, (dict, list)):
            if item is not None and not isinstance(item, (str, int, float)):
                raise ConfigError(f"{name}: {item!r} is a {type(item).__name__}, which no "
                                  "configuration file here holds (YAML 1.1 reads a date as "
                                  "one); quote it for text")
            return 1
        if isinstance(item, dict) and (keys := [k for k in item if not isinstance(k, str)]):
            raise ConfigError(f"{name}: key {keys[0]!r} is a {type(keys[0]).__name__}, not "
                              "text (YAML 1.1 reads on/off/yes/no as true/false); quote it")
        if id(item) in inside:
            raise ConfigError(f"{name}: a value inside itself")
        if id(item) not in sizes:
            if depth >= MAX_DEPTH:
                raise ConfigError(f"{name}: nested more than {MAX_DEPTH} levels deep")
            inside.add(id(item))
            children = item.values() if isinstance(item, dict) else item
            sizes[id(item)] = 1 + len(item) * isinstance(item, dict) + sum(
                size(child, depth + 1) for child in children)
            inside.discard(id(item))
        return sizes[id(item)]

    if (total := size(value, 0)) > MAX_NODES:
        raise ConfigError(f"{name}: {total:.3g} values with its repetitions; at most "
                          f"{MAX_NODES:.0e}")


def _named(text: str, name: str) -> io.StringIO:
    """``text`` as a stream whose marks name ``name`` (a file, or a ``--config`` key)."""
    stream = io.StringIO(text)
    stream.name = name
    return stream


def _at(name: str, event) -> str:
    mark = event.start_mark
    return f"{name}:{mark.line + 1}:{mark.column + 1}"


def check_shape(text: str, name: str) -> None:
    """Refuse, from the parser's events and before any value is built, a document nested deeper
    than :data:`MAX_DEPTH`, an alias inside the value it names (a value that contains itself)
    and one whose aliases expand to more than :data:`MAX_NODES` values (each alias counted as
    the whole value it repeats, known when its anchor's value ends). A syntax error is left to
    the loader, which says more."""
    frames: list[list] = []          # [size so far, anchor] of each open mapping or list
    sizes: dict[str, int] = {}       # anchor -> expanded size of its value
    total = 0

    def add(size: int, event) -> None:
        nonlocal total
        total += size
        if frames:
            frames[-1][0] += size
        if total > MAX_NODES:
            raise ConfigError(f"{_at(name, event)}: its aliases expand to more than "
                              f"{MAX_NODES:.0e} values; at most {MAX_NODES:.0e}")

    for loader in (FastStrictLoader, StrictLoader):
        frames.clear()
        sizes.clear()
        total = 0
        try:
            for event in yaml.parse(_named(text, name), Loader=loader):
                _shape_event(event, frames, sizes, add, name)
            return
        except yaml.YAMLError:
            # libyaml refuses deep nesting while it scans ahead, before the events that would
            # show where (a flow nesting past its own limit): walk the Python parser's events
            continue


def _shape_event(event, frames: list[list], sizes: dict[str, int], add, name: str) -> None:
    """One parser event of :func:`check_shape`."""
    if isinstance(event, yaml.AliasEvent):
        if any(frame[1] == event.anchor for frame in frames):
            raise ConfigError(f"{_at(name, event)}: alias *{event.anchor} inside the "
                              "value it names (a value cannot contain itself)")
        add(sizes.get(event.anchor, 1), event)
    elif isinstance(event, yaml.ScalarEvent):
        add(1, event)
        if event.anchor is not None:
            sizes[event.anchor] = 1
    elif isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
        if len(frames) >= MAX_DEPTH:
            raise ConfigError(f"{_at(name, event)}: nested more than {MAX_DEPTH} "
                              "levels deep")
        add(1, event)
        frames.append([0, event.anchor])
    elif isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
        size, anchor = frames.pop()
        if frames:
            frames[-1][0] += size
        if anchor is not None:
            sizes[anchor] = size + 1


def _load(stream, loader) -> Any:
    """The single document of ``stream`` (its ``name`` names the marks)."""
    reader = loader(stream)
    try:
        return reader.get_single_data()
    finally:
        reader.dispose()


def read_text(path: str | Path) -> str:
    """The text of a configuration file, read without trusting the path: a regular file
    (opened without blocking, so a pipe cannot hang the reader; a directory, a device or a pipe
    refused), at most :data:`MAX_BYTES` read, UTF-8; :class:`ConfigError` naming the file."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as error:
        raise ConfigError(f"{path}: cannot be read ({error.strerror})") from None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise ConfigError(f"{path}: not a regular file (a directory, a device or a pipe); "
                              "a configuration is a YAML file")
        data = b""
        while len(data) <= MAX_BYTES and (block := os.read(fd, MAX_BYTES + 1 - len(data))):
            data += block
    finally:
        os.close(fd)
    if len(data) > MAX_BYTES:
        raise ConfigError(f"{path}: more than {MAX_BYTES} bytes; a configuration file may "
                          f"have at most {MAX_BYTES}")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text ({error.reason} at byte {error.start})") \
            from None


def load_text(text: str, name: str) -> Any:
    """The value of a YAML document ``text`` read strictly (module docstring), its shape
    checked first (:func:`check_shape`); :class:`ConfigError` with ``name``, line and column
    otherwise."""
    check_shape(text, name)
    try:
        try:
            return _load(_named(text, name), FastStrictLoader)
        except yaml.YAMLError:  # read again for the more telling message
            return _load(_named(text, name), StrictLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        where = f"{name}:{mark.line + 1}:{mark.column + 1}" if mark else name
        problem = error.problem or error.context
        hint = "; tabs are not allowed for indentation" if "\\t" in str(problem) else ""
        raise ConfigError(f"{where}: {problem} (YAML syntax{hint})") from None
    except yaml.YAMLError as error:
        raise ConfigError(f"{name}: {error} (YAML)") from None


def load_yaml(path: str | Path) -> dict:
    """A YAML mapping from ``path``, read strictly (module docstring): :func:`read_text`, then
    :func:`load_text`; :class:`ConfigError` with file, line and column for a syntax error, an
    ambiguous scalar, a duplicate or non-text key or a template key, and for a file that is
    not a regular file or too large, a document too deep or too large, or one that is not a
    mapping."""
    data = load_text(read_text(path), str(path))
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: a configuration file must be a mapping of keys, not "
                          f"{type(data).__name__}")
    return data


def load_value(text: str, name: str = "--config") -> Any:
    """One text inside a ``--config`` override (``name``: where it came from) read as a value of
    a configuration file would be: its shape checked (:func:`check_shape`), then read strictly;
    a ``yaml.YAMLError`` when it is not YAML (the caller keeps the text)."""
    check_shape(text, name)
    return _load(_named(text, name), StrictLoader)
