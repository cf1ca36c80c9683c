"""Benchmark of how a batch study's cost grows: paper B's beta study (Figs 8-10) at its size
and at ``--factor`` times its runs, as one job and split into ``--shards`` shards.

Each case runs through Snakemake (``-j2``) into its own results folder and is read back from
the jobs' logs (the CPU seconds each states, :mod:`rotorvib.pipeline.job_logs`) and the dataset
(its runs).  It prints the
run-ups per CPU-second of every case, their ratio between the sizes (1 means a cost linear in
the runs) and the shards' overhead per job (the CPU a shard costs beyond its share of the
unsharded job: imports, loading the compiled engine, writing its file), and a fit of the CPU
to a fixed cost per job plus a cost per run-up, whose residuals say whether the cost is linear
in the runs.  Run from the
repository root:

    python -m benchmarks.scaling [--factor 8] [--shards 4]

The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from rotorvib.pipeline.job_logs import jobs_cpu

STUDY = "beta"


def run_case(name: str, n: int, shards: int) -> tuple[int, float, int]:
    """Run the study with ``n`` values of beta in ``shards`` shards: its run-ups, the CPU
    seconds of its jobs (shards and gathering) and how many jobs ran."""
    folder = Path("results") / f"scaling_{name}"
    shutil.rmtree(folder, ignore_errors=True)
    config = folder.with_suffix(".yaml")
    config.parent.mkdir(parents=True, exist_ok=True)
    config.write_text(f"results: {folder}\npaper_b:\n  shards: {shards}\n  balance_studies:\n"
                      f"    {STUDY}:\n      range: {{min: 0.1, max: 1.0, n: {n}}}\n")
    target = folder / f"paper_b/datasets/balance_{STUDY}.nc"
    try:
        subprocess.run([Path(sys.executable).parent / "snakemake", "-j2", "--quiet",
                        "--configfile", "config/config.yaml", str(config), "--", str(target)],
                       check=True)
        runs = xr.open_dataset(target).balance_time.size
        logs = sorted((folder / "logs").glob(f"b_balance_{STUDY}*.log"))
        return runs, jobs_cpu(logs), len(logs)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        config.unlink(missing_ok=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", type=int, default=46, help="values of beta at size 1")
    parser.add_argument("--factor", type=int, default=8, help="the larger size, in runs")
    parser.add_argument("--shards", type=int, default=4, help="shards of the sharded cases")
    args = parser.parse_args()
    cases = {}
    for size in (1, args.factor):
        for shards in (1, args.shards):
            cases[size, shards] = run_case(f"{size}x_{shards}", args.base * size, shards)
    print(f"{'size':>5} {'shards':>6} {'jobs':>5} {'run-ups':>8} {'CPU (s)':>8} "
          f"{'run-ups per CPU-s':>18}")
    rate = {}
    for (size, shards), (runs, cpu, jobs) in cases.items():
        rate[size, shards] = runs / cpu
        print(f"{size:>4}x {shards:>6} {jobs:>5} {runs:>8} {cpu:>8.1f} {rate[size, shards]:>18.1f}")
    for shards in (1, args.shards):
        print(f"run-ups per CPU-s, {args.factor}x / 1x, {shards} shard(s): "
              f"{rate[args.factor, shards] / rate[1, shards]:.3f}")
    # CPU = a jobs + b runs: a fixed cost per job (imports, the compiled engine's cache, the
    # file) and a cost per run-up; a cost linear in the runs leaves small residuals
    jobs, runs, cpu = (np.array([c[i] for c in cases.values()], float) for i in (2, 0, 1))
    (a, b), *_ = np.linalg.lstsq(np.stack([jobs, runs], axis=1), cpu, rcond=None)
    worst = np.max(np.abs(jobs * a + runs * b - cpu) / cpu)
    print(f"fit CPU = a jobs + b run-ups: a = {a:.2f} CPU-s per job, 1/b = {1 / b:.1f} run-ups "
          f"per CPU-s; largest relative residual {worst:.3f}")
    for shards in (1, args.shards):
        (r1, c1, _), (r8, c8, _) = cases[1, shards], cases[args.factor, shards]
        print(f"marginal run-ups per CPU-s from 1x to {args.factor}x, {shards} shard(s): "
              f"{(r8 - r1) / (c8 - c1):.1f}")
    for size in (1, args.factor):
        runs1, one, _ = cases[size, 1]
        _, split, n_jobs = cases[size, args.shards]
        print(f"shard overhead at {size}x: {(split - one) / (n_jobs - 1):.2f} CPU-s per extra "
              f"job ({n_jobs} jobs against 1)")

if __name__ == "__main__":
    main()
