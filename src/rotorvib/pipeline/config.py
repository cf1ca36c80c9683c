"""Loading, validating and fingerprinting the pipeline configuration.

Files are read by a strict YAML 1.2 loader (:mod:`rotorvib.pipeline.strict_yaml`): a duplicate
key, a syntax error or a scalar that YAML 1.1 reads otherwise is reported with its file, line
and column, and ``1e-9`` is a number rather than a string (at every door, the ``--config`` text
and a module's ``config:`` included: :mod:`rotorvib.pipeline.config_sources`).  The
configuration is then checked against a JSON Schema (``config/schema.yaml``) before any
computation: every number must be finite and 0 or within the library's magnitudes, every text
free of control, format and separator characters, an integer must be written as one, and the
schema's extensions add cross-field rules (``x-ordered``, ``x-at-most``, ``x-below``,
``x-at-least``, a cap on the points of a grid).  Defaults given in the schema are filled in,
and every violation is reported with the dotted key it concerns and what is allowed, e.g.::

    config key 'paper_c.rotor.M': -1.0 is not allowed; must be a number > 0 (disk mass, kg)

Snakemake parses ``--configfile`` files itself before the workflow starts and reports a YAML
syntax error without its place; ``python -m rotorvib.pipeline.config FILE...`` checks files as the
workflow would (later files override earlier ones) and gives file, line and column.
"""

from __future__ import annotations

import copy
import math
import unicodedata
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rotorvib.checks import MAGNITUDES
from rotorvib.pipeline.config_checks import problems
from rotorvib.pipeline.config_sources import command_line_overrides, merge
from rotorvib.pipeline.strict_yaml import ConfigError, load_yaml

if TYPE_CHECKING:
    import jsonschema


def _fill_defaults(instance: Any, schema: dict) -> None:
    """Insert schema defaults for absent properties, recursively (in place)."""
    if not isinstance(instance, dict) or schema.get("type") != "object":
        return
    for key, sub in schema.get("properties", {}).items():
        if key not in instance and "default" in sub:
            instance[key] = copy.deepcopy(sub["default"])
        if key in instance:
            _fill_defaults(instance[key], sub)


def _allowed(schema: dict) -> str:
    """A short human description of what a schema node admits."""
    parts = []
    kind = schema.get("type")
    if kind == "array":
        items = schema.get("items", {})
        n_min, n_max = schema.get("minItems"), schema.get("maxItems")
        size = (
            f"{n_min}" if n_min is not None and n_min == n_max else f"{n_min or 0}..{n_max or 'n'}"
        )
        parts.append(f"a list of {size} items, each {_allowed(items)}")
    elif kind is None and ("pattern" in schema or "maxLength" in schema):
        parts.append("a string")
    elif kind is not None:
        parts.append({"number": "a number", "integer": "an integer", "string": "a string",
                      "boolean": "true or false", "object": "a mapping"}.get(kind, str(kind)))
    bounds = []
    for word, sym in (("exclusiveMinimum", ">"), ("minimum", ">="),
                      ("exclusiveMaximum", "<"), ("maximum", "<=")):
        if word in schema:
            bounds.append(f"{sym} {schema[word]}")
    if bounds:
        parts.append(" and ".join(bounds))
    if "enum" in schema:
        parts.append("one of " + ", ".join(map(repr, schema["enum"])))
    if "maxLength" in schema:
        parts.append(f"of {schema.get('minLength', 0)} to {schema['maxLength']} characters")
    elif "minLength" in schema:
        parts.append(f"of at least {schema['minLength']} characters")
    if "pattern" in schema:
        parts.append(f"matching the pattern {schema['pattern']}")
    text = " ".join(parts) if parts else "any value"
    if "description" in schema:
        text += f" ({schema['description']})"
    return text


def _key(path) -> str:
    return ".".join(str(p) for p in path) or "<root>"


def _describe(error: jsonschema.ValidationError) -> str:
    path = list(error.absolute_path)
    if isinstance(error.instance, str) and _is_number(error.instance):
        return (f"config key '{_key(path)}': {error.instance!r} is a string, not a number "
                "(YAML 1.1 reads a number like 1e-9 as text: write 1.0e-9); must be "
                f"{_allowed(error.schema)}")
    if error.validator == "required":
        missing = error.message.split("'")[1]
        sub = error.schema.get("properties", {}).get(missing, {})
        return f"config key '{_key(path + [missing])}' is missing; must be {_allowed(sub)}"
    if error.validator == "additionalProperties":
        allowed = ", ".join(sorted(error.schema.get("properties", {})))
        extra = sorted(set(error.instance) - set(error.schema.get("properties", {})))
        return (f"config key '{_key(path)}' has unknown key(s) {', '.join(map(repr, extra))}; "
                f"allowed keys: {allowed}")
    if "propertyNames" in error.absolute_schema_path:    # a name of a mapping's entry
        return (f"config key '{_key(path)}': the name {_shown(error.instance)} is not allowed; "
                f"must be {_allowed(error.schema)}")
    return (f"config key '{_key(path)}': {_shown(error.instance)} is not allowed; "
            f"must be {_allowed(error.schema)}")


def _shown(value) -> str:
    """``repr(value)``, a long text cut to its first 40 characters and its length, so that a
    message stays one readable line (a 1 MB text is shown by what it starts with)."""
    if isinstance(value, str) and len(value) > 60:
        return f"{value[:40]!r}... ({len(value)} characters)"
    return repr(value)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _non_finite(config, path=()) -> list[str]:
    """Every number of the configuration that the library would refuse (JSON Schema bounds never
    reject NaN, and a subnormal passes any bound "> 0"): NaN, an infinity, or a number that is
    neither 0 nor within the library's magnitudes (:data:`rotorvib.checks.MAGNITUDES`, the bound
    every entry point applies to its arguments). Refused here, such a number is named by its
    key before any job; accepted, it failed inside a job naming a library field or a derived
    quantity (1e308 as a disk mass, 1e-300 as a stiffness: a hostile-input audit)."""
    if isinstance(config, dict):
        return [p for k, v in config.items() for p in _non_finite(v, path + (k,))]
    if isinstance(config, list):
        return [p for i, v in enumerate(config) for p in _non_finite(v, path + (str(i),))]
    if isinstance(config, float) and not math.isfinite(config):
        return [f"config key '{_key(path)}': {config!r} is not allowed; must be a finite number"]
    if (isinstance(config, (int, float)) and not isinstance(config, bool) and config != 0
            and not MAGNITUDES[0] <= abs(config) <= MAGNITUDES[1]):
        shown = f"{config:.6g}" if isinstance(config, int) else repr(config)
        return [(f"config key '{_key(path)}': {shown} is not allowed; must be 0 or between "
                 f"{MAGNITUDES[0]:g} and {MAGNITUDES[1]:g} in magnitude (beyond, products "
                 "underflow or overflow; a subnormal number has lost precision already)")]
    return []


#: Unicode categories refused in a key or a text: control characters (a newline among them),
#: format characters (the bidirectional overrides and isolates U+202A-U+202E and U+2066-U+2069,
#: which reorder what a reader sees, and zero-width characters), line and paragraph separators
#: (U+2028, U+2029: a line break to many readers of a CSV or a log), surrogates.
_HIDDEN = frozenset({"Cc", "Cf", "Zl", "Zp", "Cs"})


def _bad_text(config, path=()) -> list[str]:
    """Every key or string holding a character of :data:`_HIDDEN` or starting or ending with
    whitespace: a name or a text shown in the report, a table or a path must read as written
    (found by hostile-input audits: a study name ending in a newline was taken, and so were
    U+2028 and U+202E)."""

    def bad(text: str) -> bool:
        return text != text.strip() or any(unicodedata.category(ch) in _HIDDEN for ch in text)

    def problem(key, text, what):
        return (f"config key '{_key(key)}': {what} {_shown(text)} is not allowed; must be "
                "printable text without control characters (format, bidirectional override "
                "and line separator ones among them) or surrounding whitespace")

    found = []
    if isinstance(config, dict):
        for key, value in config.items():
            if isinstance(key, str) and bad(key):
                found.append(problem(path, key, "the key"))
            found += _bad_text(value, path + (key,))
    elif isinstance(config, list):
        for i, value in enumerate(config):
            found += _bad_text(value, path + (str(i),))
    elif isinstance(config, str) and bad(config):
        found.append(problem(path, config, "the text"))
    return found


def _lookup(config: dict, dotted: str):
    node = config
    for part in dotted.split("."):
        node = node[part]
    return node


def _resolve(schema: dict, root: dict) -> dict:
    ref = schema.get("$ref", "")
    if ref.startswith("#/$defs/"):
        return {**root["$defs"][ref.split("/")[-1]], **{k: v for k, v in schema.items()
                                                          if k != "$ref"}}
    return schema


def _ordered_problem(value, key) -> str | None:
    if isinstance(value, dict) and {"min", "max", "n"} <= set(value):
        if value["min"] > value["max"] or (value["n"] > 1 and value["min"] == value["max"]):
            return f"config key '{key}': min {value['min']!r} must be below max {value['max']!r}"
    elif isinstance(value, list) and any(a >= b for a, b in zip(value, value[1:])):
        return f"config key '{key}': interval {value!r} must have lower < upper"
    return None


def _check_extensions(config, schema: dict, root: dict, path=()) -> list[str]:
    """Honour the schema extensions ``x-ordered: true`` (an interval ``[lo, hi]`` or a range
    ``{min, max, n}`` must increase), ``x-at-most: other.key`` (this value <= that one),
    ``x-below`` (<) and ``x-at-least`` (>=), and
    the naming rule ``*_min < *_max`` for sibling keys."""
    problems = []
    schema = _resolve(schema, root)
    if schema.get("x-ordered"):
        problem = _ordered_problem(config, _key(path))
        problems += [problem] if problem else []
    for word, holds, relation in (("x-at-most", lambda a, b: a <= b, "<="),
                                  ("x-below", lambda a, b: a < b, "<"),
                                  ("x-at-least", lambda a, b: a >= b, ">=")):
        if word in schema:
            other = _lookup(root["__config__"], schema[word])
            largest = max(config) if isinstance(config, list) else config
            if not holds(largest, other):
                problems.append(f"config key '{_key(path)}': {config!r} must be {relation} "
                                f"'{schema[word]}' = {other!r}")
    if isinstance(config, dict):
        points = math.prod(v["n"] for v in config.values()
                           if isinstance(v, dict) and {"min", "max", "n"} <= set(v))
        if points > root.get("x-max-grid-points", math.inf):
            problems.append(f"config key '{_key(path)}': its grids have {points} points in all; "
                            f"at most {root['x-max-grid-points']} are allowed")
        for key, value in config.items():
            if key.endswith("_min") and key[:-4] + "_max" in config:
                if not value < config[key[:-4] + "_max"]:
                    problems.append(f"config key '{_key(path + (key,))}': {value!r} must be "
                                    f"smaller than '{key[:-4]}_max' = {config[key[:-4] + '_max']!r}")
            sub = schema.get("properties", {}).get(key)
            if sub is None and isinstance(schema.get("additionalProperties"), dict):
                sub = schema["additionalProperties"]
            if sub is not None:
                problems += _check_extensions(value, sub, root, path + (key,))
    elif isinstance(config, list) and "items" in schema:
        for i, value in enumerate(config):
            problems += _check_extensions(value, schema["items"], root, path + (str(i),))
    return problems


@cache
def _validator_class():
    """The JSON Schema validator whose "integer" is an int (401.0 is not an integer here).
    jsonschema is imported here, on the first validation: a workflow job reads its part of a
    configuration that Snakemake validated, and never pays for the import."""
    import jsonschema

    return jsonschema.validators.extend(
        jsonschema.Draft202012Validator,
        type_checker=jsonschema.Draft202012Validator.TYPE_CHECKER.redefine(
            "integer", lambda _, value: isinstance(value, int) and not isinstance(value, bool)))


def validate_config(config: dict, schema: dict) -> dict:
    """Return a validated copy of ``config`` with the schema's defaults filled in.

    Raises :class:`ConfigError` naming every offending key and its allowed values.
    """
    filled = copy.deepcopy(config)
    _fill_defaults(filled, schema)
    errors = sorted(_validator_class()(schema).iter_errors(filled),
                    key=lambda e: list(map(str, e.absolute_path)))
    # a value that breaks two rules described alike (a name too long for both its pattern and
    # its maxLength) is reported once
    messages = list(dict.fromkeys(_non_finite(filled) + _bad_text(filled)
                                  + [_describe(e) for e in errors]))
    if not messages:
        messages = _check_extensions(filled, schema, {**schema, "__config__": filled})
    if messages:
        raise ConfigError("invalid configuration:\n  " + "\n  ".join(messages))
    return filled


def check_config(config: dict, schema: dict) -> dict:
    """The workflow's configuration, validated: the schema (:func:`validate_config`), then the
    checks beyond it (:func:`rotorvib.pipeline.config_checks.problems`); :class:`ConfigError`
    listing every problem otherwise. Where key ``papers`` names the papers of the run, the
    section ``paper_<p>`` of each other paper is checked, then left out of the result: the
    workflow makes the rules, results and comparison rows of the papers whose sections it
    holds."""
    checked = validate_config(config, schema)
    found = problems(checked)
    sections = {key.removeprefix("paper_") for key in checked if key.startswith("paper_")}
    papers = checked.get("papers", sorted(sections))
    found += [f"config key 'papers': paper {p!r} has no section 'paper_{p}'"
              for p in papers if p not in sections]
    if found:
        raise ConfigError("invalid configuration:\n  " + "\n  ".join(found))
    return {key: value for key, value in checked.items()
            if not key.startswith("paper_") or key.removeprefix("paper_") in papers}


def check_files(paths, schema_path: str | Path = "config/schema.yaml", overrides=()) -> dict:
    """The checked configuration (:func:`check_config`) of ``paths`` merged in order, then the
    ``--config`` entries ``overrides`` (:func:`command_line_overrides`); :class:`ConfigError`
    otherwise."""
    config: dict = {}
    for path in paths:
        config = merge(config, load_yaml(path))
    config = merge(config, command_line_overrides(overrides))
    return check_config(config, load_yaml(schema_path))


def main(argv=None) -> int:
    """``python -m rotorvib.pipeline.config [--schema S] FILE... [--config KEY=VALUE...]``: 0 and
    "valid" or 1 and the errors."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m rotorvib.pipeline.config",
                                     description="Check configuration files and --config "
                                                 "entries as the workflow does.")
    parser.add_argument("--schema", default="config/schema.yaml")
    parser.add_argument("files", nargs="+")
    parser.add_argument("--config", nargs="*", default=[], metavar="KEY=VALUE")
    args = parser.parse_args(argv)
    try:
        check_files(args.files, args.schema, args.config)
    except ConfigError as error:
        print(error)
        return 1
    print(f"valid: {' + '.join(args.files + [f'--config {c}' for c in args.config])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
