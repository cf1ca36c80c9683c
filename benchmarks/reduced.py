"""The reduced workflow as the benchmarks run it (benchmarks.cluster):
each case in its own results folder under ``results/<bench>/``, with the
compiled engine's cache of the working tree (run the workflow or the tests once first, so that
no case compiles it)."""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from benchmarks import children_cpu

REDUCED = ["config/config.yaml", "config/test/config.yaml"]


@dataclass(frozen=True)
class Run:
    """A finished run: wall and CPU time (s; the CPU of Snakemake and every process it waited
    for) and what it printed."""

    wall: float
    cpu: float
    output: str


def run_reduced(folder: Path, name: str, options: list[str], shards: int = 1,
                env: dict[str, str] | None = None, fresh: bool = True) -> Run:
    """``snakemake <options>`` on the reduced configuration into ``folder/name`` (from scratch,
    or, not ``fresh``, on what a run there left), with paper B's batch studies in ``shards``
    shards and environment ``env``; exits naming the command when it fails."""
    results = folder / name
    if fresh:
        shutil.rmtree(results, ignore_errors=True)
        results.mkdir(parents=True)
    config = folder / f"{name}.yaml"
    config.write_text(f"results: {results}\npaper_b:\n  shards: {shards}\n")
    command = [str(Path(sys.executable).parent / "snakemake"), *options,
               "--configfile", *REDUCED, str(config)]
    cpu, start = children_cpu(), time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    wall, cpu = time.perf_counter() - start, children_cpu() - cpu
    if done.returncode:
        sys.exit(f"{' '.join(command)} failed:\n{done.stdout[-3000:]}{done.stderr[-3000:]}")
    return Run(wall, cpu, done.stdout + done.stderr)
