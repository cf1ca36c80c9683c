"""Loading, validating and fingerprinting the pipeline configuration.

The configuration is checked against a JSON Schema (``config/schema.yaml``) before any
computation.  Defaults given in the schema are filled in, and every violation is reported
with the dotted key it concerns and what the schema allows, e.g.::

    config key 'paper_c.rotor.M': -1.0 is not allowed; must be a number > 0 (disk mass, kg)
"""

from __future__ import annotations

import copy
import hashlib
import json
from pathlib import Path
from typing import Any

import jsonschema
import yaml


class ConfigError(ValueError):
    """The configuration does not satisfy the schema; the message lists every violation."""


def load_yaml(path: str | Path) -> dict:
    with open(path, encoding="utf-8") as fh:
        return yaml.safe_load(fh) or {}


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
    text = " ".join(parts) if parts else "any value"
    if "description" in schema:
        text += f" ({schema['description']})"
    return text


def _key(path) -> str:
    return ".".join(str(p) for p in path) or "<root>"


def _describe(error: jsonschema.ValidationError) -> str:
    path = list(error.absolute_path)
    if error.validator == "required":
        missing = error.message.split("'")[1]
        sub = error.schema.get("properties", {}).get(missing, {})
        return f"config key '{_key(path + [missing])}' is missing; must be {_allowed(sub)}"
    if error.validator == "additionalProperties":
        allowed = ", ".join(sorted(error.schema.get("properties", {})))
        extra = sorted(set(error.instance) - set(error.schema.get("properties", {})))
        return (f"config key '{_key(path)}' has unknown key(s) {', '.join(map(repr, extra))}; "
                f"allowed keys: {allowed}")
    return (f"config key '{_key(path)}': {error.instance!r} is not allowed; "
            f"must be {_allowed(error.schema)}")


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
    ``{min, max, n}`` must increase) and ``x-at-most: other.key`` (this value <= that one), and
    the naming rule ``*_min < *_max`` for sibling keys."""
    problems = []
    schema = _resolve(schema, root)
    if schema.get("x-ordered"):
        problem = _ordered_problem(config, _key(path))
        problems += [problem] if problem else []
    if "x-at-most" in schema:
        other = _lookup(root["__config__"], schema["x-at-most"])
        if not config <= other:
            problems.append(f"config key '{_key(path)}': {config!r} must be <= "
                            f"'{schema['x-at-most']}' = {other!r}")
    if isinstance(config, dict):
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


def validate_config(config: dict, schema: dict) -> dict:
    """Return a validated copy of ``config`` with the schema's defaults filled in.

    Raises :class:`ConfigError` naming every offending key and its allowed values.
    """
    filled = copy.deepcopy(config)
    _fill_defaults(filled, schema)
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(filled), key=lambda e: list(map(str, e.absolute_path)))
    messages = [_describe(e) for e in errors]
    if not messages:
        messages = _check_extensions(filled, schema, {**schema, "__config__": filled})
    if messages:
        raise ConfigError("invalid configuration:\n  " + "\n  ".join(messages))
    return filled


def canonical_json(obj: Any) -> str:
    """Key-sorted, compact JSON: the canonical text of a configuration (section)."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def config_hash(obj: Any) -> str:
    """SHA-256 of :func:`canonical_json`; equal configs give equal hashes."""
    return hashlib.sha256(canonical_json(obj).encode()).hexdigest()
