"""A fuzzer over the configuration: every number of a configuration, one at a time, moved to
values the schema may or may not allow (its bounds, just inside an open bound, zero, a sign
change, three orders of magnitude either way, an integer's neighbours).

Each such configuration is either refused before any job, by messages that each name a config
key, or accepted; an accepted one must then run: :func:`run_accepted` reruns what it changes in
a copy of a finished reduced run and records every command that fails.  The library's side
(``tests/test_config_fuzz.py``) checks the first half on every mutation in CI; the second half
runs jobs, minutes each, so it is a command (a copy of a finished reduced run, e.g. the
``repo`` folder that the workflow tests leave under pytest's temporary folder)::

    python tests/schema_fuzz.py RUN_DIR --budget 1800 --seed 1 --report fuzz.json

and what it finds becomes a case of the corpus (``tests/test_config_corpus.py``).
"""

from __future__ import annotations

import argparse
import copy
import json
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "src")]

from rotorvib.pipeline.config import ConfigError, check_config, load_yaml, merge  # noqa: E402

SCHEMA = load_yaml(ROOT / "config/schema.yaml")
#: The reduced configuration the workflow tests run (tests/workflow_runs.py).
REDUCED_FILES = ["config/config.yaml", "config/test/config.yaml",
                 "tests/config/results_at_root.yaml"]


def reduced_config() -> dict:
    config: dict = {}
    for name in REDUCED_FILES:
        config = merge(config, load_yaml(ROOT / name))
    return config


def numbers(config, path=()) -> list[tuple]:
    """The path (keys and list indices) of every number of ``config``; booleans are not
    numbers here."""
    if isinstance(config, dict):
        return [p for key, value in config.items() for p in numbers(value, path + (key,))]
    if isinstance(config, list):
        return [p for i, value in enumerate(config) for p in numbers(value, path + (i,))]
    if isinstance(config, (int, float)) and not isinstance(config, bool):
        return [path]
    return []


def schema_node(path: tuple) -> dict:
    """The schema node of a config path (``$ref`` resolved), or {} where the schema gives none."""
    node = SCHEMA
    for part in path:
        node = _resolved(node)
        if isinstance(part, int):
            node = node.get("items", {})
        elif part in node.get("properties", {}):
            node = node["properties"][part]
        elif isinstance(node.get("additionalProperties"), dict):
            node = node["additionalProperties"]
        else:
            return {}
    return _resolved(node)


def _resolved(node: dict) -> dict:
    ref = node.get("$ref", "")
    if ref.startswith("#/$defs/"):
        return {**SCHEMA["$defs"][ref.split("/")[-1]], **{k: v for k, v in node.items()
                                                           if k != "$ref"}}
    return node


def variants(value, node: dict) -> list:
    """The values a number is moved to: the schema's bounds and just inside an open one, zero,
    minus the value, the value times 1e-3, 0.1, 10 and 1e3 (a zero: -1, 1e-3, 1 and 1e3;
    integers: the neighbours, 0, 1, 2 and ten times)."""
    if isinstance(value, int):
        out = {0, 1, 2, value - 1, value + 1, 10 * value, -value}
        out |= {int(node[k]) for k in ("minimum", "maximum") if k in node}
        return sorted(out - {value})
    scale = value if value else 1.0
    out = {0.0, -scale, scale * 1e-3, scale * 0.1, scale * 10.0, scale * 1e3}
    for bound, inside in (("minimum", None), ("maximum", None),
                          ("exclusiveMinimum", math.inf), ("exclusiveMaximum", -math.inf)):
        if bound in node:
            out.add(float(node[bound]) if inside is None
                    else math.nextafter(float(node[bound]), inside))
    return sorted(v for v in out if v != value)


def mutate(config: dict, path: tuple, value) -> dict:
    out = copy.deepcopy(config)
    node = out
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value
    return out


def mutations(config: dict) -> list[tuple[tuple, object]]:
    """Every (path, value) of :func:`variants` over every number of ``config``."""
    return [(path, value) for path in numbers(config)
            for value in variants(_get(config, path), schema_node(path))]


#: What a node is replaced by in the structure fuzz: texts (empty, padded, with a newline, a
#: template tag, a number as text), the other YAML kinds, an empty and a deep container.
REPLACEMENTS = ["text", "", " padded", "line\n", "{{ 7*191 }}", "1e-9", None, True, [], {},
                [[[[["deep"]]]]], {"nested": {"deeper": 1}}]


def nodes(config, path=()) -> list[tuple]:
    """The path of every node of ``config`` (mappings, lists and scalars), the root left out."""
    found = [path] if path else []
    if isinstance(config, dict):
        found += [p for key, value in config.items() for p in nodes(value, path + (key,))]
    elif isinstance(config, list):
        found += [p for i, value in enumerate(config) for p in nodes(value, path + (i,))]
    return found


def structure_mutations(config: dict) -> list[tuple[str, tuple, object]]:
    """Every change of shape of ``config``, as (kind, path, value): a node replaced by each of
    :data:`REPLACEMENTS` or wrapped in a list, a mapping's key removed or renamed (``value``:
    the new name, with a space, a dot or a newline), a key added to a mapping."""
    found = []
    for path in nodes(config):
        found += [("replace", path, value) for value in REPLACEMENTS]
        found.append(("replace", path, [_get(config, path)]))
        if isinstance(path[-1], str):
            found.append(("remove", path, None))
            found += [("rename", path, path[-1] + suffix) for suffix in (" ", ".x", "\n", "_x")]
        if isinstance(_get(config, path), dict):
            found.append(("add", path + ("unknown",), 1.0))
    return found


def apply(config: dict, kind: str, path: tuple, value) -> dict:
    """``config`` with one of :func:`structure_mutations` applied (a copy)."""
    out = copy.deepcopy(config)
    parent = _get(out, path[:-1])
    if kind in ("replace", "add"):
        parent[path[-1]] = value
    elif kind == "remove":
        del parent[path[-1]]
    else:
        parent[value] = parent.pop(path[-1])
    return out


def _get(config, path):
    for part in path:
        config = config[part]
    return config


def verdict(config: dict) -> str | None:
    """None for an accepted configuration, the refusal's message otherwise; any other
    exception than :class:`ConfigError` propagates (the checks crashed)."""
    try:
        check_config(config, SCHEMA)
    except ConfigError as error:
        return str(error)
    return None


def dotted(path: tuple) -> str:
    return ".".join(map(str, path))


def override(config: dict, path: tuple, value) -> dict:
    """The smallest override file that sets ``path`` to ``value`` (a list is given whole)."""
    top = path[: next((i for i, p in enumerate(path) if isinstance(p, int)), len(path))]
    inner = _get(mutate(config, path, value), top)
    for part in reversed(top):
        inner = {part: inner}
    return inner


@dataclass
class Outcome:
    key: str
    value: float
    status: str          # "refused", "ran", "failed", "slow"
    seconds: float
    message: str = ""


def run_accepted(run_dir: Path, budget: float, seed: int, timeout: float) -> list[Outcome]:
    """Accepted mutations, in a random order of ``seed``, each run by ``snakemake -j2`` in a
    copy of the finished reduced run ``run_dir`` until ``budget`` seconds are spent; a run
    that takes more than ``timeout`` seconds is stopped and counted slow, not failed."""
    from workflow_runs import REDUCED, copy_run

    base = reduced_config()
    todo = mutations(base)
    random.Random(seed).shuffle(todo)
    outcomes: list[Outcome] = []
    spent = 0.0
    with tempfile.TemporaryDirectory() as scratch:
        for i, (path, value) in enumerate(todo):
            if spent > budget:
                break
            mutated = mutate(base, path, value)
            if (message := verdict(mutated)) is not None:
                outcomes.append(Outcome(dotted(path), value, "refused", 0.0, message))
                continue
            work = copy_run(run_dir, Path(scratch) / f"run{i}")
            (work / "fuzz.yaml").write_text(yaml.safe_dump(override(base, path, value)))
            start = time.perf_counter()
            code, log = _run_workflow(work, [*REDUCED, "fuzz.yaml"], timeout)
            status = {0: "ran", None: "slow"}.get(code, "failed")
            message = {"ran": "", "slow": f"stopped after {timeout:g} s",
                       "failed": _error_lines(log) if code else ""}[status]
            seconds = time.perf_counter() - start
            spent += seconds
            outcomes.append(Outcome(dotted(path), value, status, seconds, message))
            print(f"{status:7s} {seconds:6.1f} s  {dotted(path)} = {value!r}", flush=True)
            if message:
                print("        " + message.replace("\n", "\n        "), flush=True)
            shutil.rmtree(work, ignore_errors=True)
    return outcomes


def _run_workflow(work: Path, args: list[str], timeout: float) -> tuple[int | None, str]:
    """``snakemake -j2 args`` in ``work`` (as tests/workflow_runs.py runs it): its exit code
    and log, or None when it took longer than ``timeout`` seconds; then its whole process
    group is stopped, the jobs it started included."""
    from workflow_runs import BIN, environment

    with subprocess.Popen([str(BIN / "snakemake"), "-j2", *args], cwd=work, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          env=environment(work), start_new_session=True) as run:
        try:
            log, _ = run.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(run.pid, signal.SIGKILL)
            run.communicate()
            return None, ""
    return run.returncode, log


def _error_lines(log: str) -> str:
    keep = [line for line in log.splitlines()
            if any(w in line for w in ("Error", "error", "config key", "Exception"))]
    return "\n".join(keep[-12:])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", type=Path, help="a copy of a finished reduced run")
    parser.add_argument("--budget", type=float, default=1800.0, help="seconds of runs")
    parser.add_argument("--timeout", type=float, default=240.0, help="seconds per run")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--report", type=Path, default=Path("fuzz.json"))
    args = parser.parse_args()
    outcomes = run_accepted(args.run_dir, args.budget, args.seed, args.timeout)
    args.report.write_text(json.dumps([asdict(o) for o in outcomes], indent=1))
    counts = {s: sum(o.status == s for o in outcomes) for s in ("refused", "ran", "failed",
                                                                 "slow")}
    print(", ".join(f"{n} {s}" for s, n in counts.items()))


if __name__ == "__main__":
    main()
