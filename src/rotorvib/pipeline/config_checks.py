"""The configuration's checks beyond its schema (:func:`problems`), one entry point for every
paper: each paper section ``paper_<p>`` of the configuration is checked by its package's
``rotorvib.papers.<p>.config_checks.problems`` (the papers are found from the configuration,
not from a list), which names each problem by its key within the section; this module writes
every message in one format.  The workflow runs them when it reads the configuration, before
any job, so they import numpy, the engine's limits and the integrators' tolerance floor only,
not the compiled engine."""

from __future__ import annotations

import importlib

PAPER_PREFIX = "paper_"


def message(key: str, problem: str) -> str:
    """The one format of a configuration problem: ``config key 'KEY': PROBLEM``."""
    return f"config key '{key}': {problem}"


def problems(config: dict) -> list[str]:
    """Every problem of a configuration that satisfies the schema, from the checks of each
    paper section's package, as messages naming the key."""
    found = []
    for section in sorted(k for k in config if k.startswith(PAPER_PREFIX)):
        checks = importlib.import_module(
            f"rotorvib.papers.{section.removeprefix(PAPER_PREFIX)}.config_checks")
        found += [message(f"{section}.{key}", problem)
                  for key, problem in checks.problems(config[section])]
    return found
