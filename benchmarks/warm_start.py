"""Benchmark of the warm start of script jobs (rotorvib.pipeline.warm_start): with
``snakemake -j2``, every job in its own process (``ROTORVIB_NO_WARM_START``) and with the warm
start, alternately, ``--pairs`` times: the reduced workflow from scratch, then every figure of it
redrawn (the loop of a user who edits a figure's code).

Each way runs in its own results folder (``results/warm_start_bench/``, benchmarks.reduced).
It prints each run's wall time and CPU time (Snakemake, its jobs and the server) and, for each
pair, the warm run's over its own-process neighbour's, then the median ratios. Run from the
repository root:

    python -m benchmarks.warm_start [--pairs 2]

The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

from benchmarks.reduced import run_reduced
from rotorvib.pipeline.warm_start import DISABLE

FOLDER = Path("results/warm_start_bench")


def figure_rules() -> list[str]:
    """The workflow's figure rules (``figures_*``), as Snakemake lists them."""
    listed = subprocess.run([str(Path(sys.executable).parent / "snakemake"), "--list-rules"],
                            capture_output=True, text=True, check=True).stdout.split()
    return [name for name in listed if name.startswith("figures_")]


def compare(label: str, pairs: int, run) -> None:
    """``pairs`` pairs of ``run(name, env)``, own processes first, and their ratios."""
    own = {**os.environ, DISABLE: "1"}
    warm = {name: value for name, value in os.environ.items() if name != DISABLE}
    print(f"{label}\n{'pair':>4} {'own wall':>9} {'warm wall':>10} {'ratio':>6}   "
          f"{'own CPU':>8} {'warm CPU':>9} {'ratio':>6}")
    walls, cpus = [], []
    for pair in range(pairs):
        first, second = run("own", own), run("warm", warm)
        walls.append(second.wall / first.wall)
        cpus.append(second.cpu / first.cpu)
        print(f"{pair + 1:4d} {first.wall:9.1f} {second.wall:10.1f} {walls[-1]:6.2f}   "
              f"{first.cpu:8.1f} {second.cpu:9.1f} {cpus[-1]:6.2f}", flush=True)
    print(f"median warm/own: wall {statistics.median(walls):.2f}, "
          f"CPU {statistics.median(cpus):.2f}\n")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=2, help="pairs of runs (default 2)")
    args = parser.parse_args()
    compare("the reduced workflow from scratch", args.pairs,
            lambda name, env: run_reduced(FOLDER, name, ["-j2"], env=env))
    redraw = ["-j2", "--forcerun", *figure_rules()]
    compare("every figure redrawn (--forcerun figures_*)", args.pairs,
            lambda name, env: run_reduced(FOLDER, name, redraw, env=env, fresh=False))
    shutil.rmtree(FOLDER, ignore_errors=True)


if __name__ == "__main__":
    main()
