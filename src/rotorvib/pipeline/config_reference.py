"""The configuration reference of the documentation, generated: every key of
``config/schema.yaml`` with what it admits, its value in ``config/config.yaml`` and the
comment that gives that value's source there.  ``docs/conf.py`` writes it on every build, so
the reference cannot drift from the schema or the configuration.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from rotorvib.pipeline.config import _allowed, _resolve, load_yaml

_KEY = re.compile(r"^(?P<indent> *)(?P<key>[A-Za-z_][\w-]*):(?P<rest>.*)$")


def source_comments(text: str) -> dict[str, str]:
    """``{dotted key: comment}`` of a YAML file: the comment on a key's line, else the comment
    lines just above it."""
    comments: dict[str, str] = {}
    stack: list[tuple[int, str]] = []
    above: list[str] = []
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            above.append(stripped.lstrip("#").strip())
            continue
        match = _KEY.match(line)
        if not match:
            above = [] if not stripped else above
            continue
        indent = len(match["indent"])
        while stack and stack[-1][0] >= indent:
            stack.pop()
        stack.append((indent, match["key"]))
        key = ".".join(k for _, k in stack)
        inline = match["rest"].split(" #", 1)[1].strip() if " #" in match["rest"] else ""
        if inline or above:
            comments[key] = inline or " ".join(above)
        above = []
    return comments


def _rows(schema: dict, root: dict, config, comments: dict, path: tuple) -> list[tuple]:
    schema = _resolve(schema, root)
    key = ".".join(path)
    rows = []
    properties = schema.get("properties", {})
    extra = schema.get("additionalProperties")
    if properties or isinstance(extra, dict):
        if path:
            rows.append((key, "a mapping", "", comments.get(key, schema.get("description", ""))))
        for name, sub in properties.items():
            value = config.get(name) if isinstance(config, dict) else None
            rows += _rows(sub, root, value, comments, path + (name,))
        if isinstance(extra, dict):
            rows += _rows(extra, root, None, comments, path + ("<name>",))
        return rows
    value = "" if config is None else json.dumps(config)
    return [(key, _allowed(schema), value, comments.get(key, ""))]


def reference(schema_path: str | Path, config_path: str | Path) -> str:
    """The configuration reference as a Markdown table."""
    schema = load_yaml(schema_path)
    text = Path(config_path).read_text(encoding="utf-8")
    rows = _rows(schema, schema, load_yaml(config_path), source_comments(text), ())

    def cell(text: str) -> str:
        return text.replace("|", "\\|").replace("\n", " ")

    lines = ["| key | allowed | value in config/config.yaml | source (its comment) |",
             "|---|---|---|---|"]
    lines += [f"| `{k}` | {cell(a)} | {'`' + cell(v) + '`' if v else ''} | {cell(c)} |"
              for k, a, v, c in rows]
    return "\n".join(lines) + "\n"
