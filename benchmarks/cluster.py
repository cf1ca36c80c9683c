"""Benchmark of the cluster path: the reduced workflow from scratch through the shipped SLURM
profile (``profiles/slurm``) against ``snakemake -j2`` on this machine, one after the
other; with ``--shards N`` also both ways with paper B's batch studies in N shards each, whose
shards the profile sends to SLURM.

Each case runs from scratch into its own results folder (``results/cluster_bench/<case>``,
benchmarks.reduced). It prints each case's wall time, the jobs it sent to SLURM (from
the executor plugin's log) and the ratio of the two ways. It needs a SLURM cluster
(``SLURM_CONF``; ``workflow/cluster/one-node-slurm`` makes one on this machine). Run from the
repository root:

    python -m benchmarks.cluster [--shards 3]

The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import sys
from pathlib import Path

from benchmarks.reduced import run_reduced

FOLDER = Path("results/cluster_bench")
WAYS = {"local": ["-j2"], "slurm": ["--workflow-profile", "profiles/slurm"]}


def run_case(name: str, way: str, shards: int) -> tuple[float, int]:
    """The reduced workflow from scratch, ``way`` ("local" or "slurm") with ``shards`` shards a
    batch study: its wall time (s) and the jobs it sent to SLURM."""
    run = run_reduced(FOLDER, name, WAYS[way], shards)
    return run.wall, len(re.findall(r"submitted with SLURM jobid", run.output))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shards", type=int, default=1,
                        help="also run both ways with this many shards a batch study")
    args = parser.parse_args()
    if "SLURM_CONF" not in os.environ and not Path("/etc/slurm/slurm.conf").exists():
        sys.exit("no SLURM cluster: set SLURM_CONF (workflow/cluster/one-node-slurm start DIR)")
    print(f"{'case':18s} {'wall (s)':>9} {'SLURM jobs':>11} {'slurm/local':>12}")
    for shards in sorted({1, args.shards}):
        walls = {}
        for way in WAYS:
            name = f"{way}_{shards}_shards"
            walls[way], sent = run_case(name, way, shards)
            ratio = f"{walls['slurm'] / walls['local']:12.2f}" if way == "slurm" else ""
            print(f"{name:18s} {walls[way]:9.1f} {sent:11d} {ratio}", flush=True)
    shutil.rmtree(FOLDER, ignore_errors=True)


if __name__ == "__main__":
    main()
