"""Benchmark of what a job of a batch study spends besides computing its runs: paper B's beta
study (Figs 8-10) at its size and at ``--factor`` times its runs, built by each kind of job of
``--shards`` shards -- the job that runs the whole study, one shard and the gathering
(:mod:`rotorvib.pipeline.shards`) -- with the engine replaced by a runner that answers zeros
(``Setup.runs`` still turns the inputs into arrays).  For each it prints the CPU time and the
peak memory (tracemalloc) of building the study, per run-up of the study: a cost that grows
with the study in a job that computes a fixed share of it is the overhead that sharding cannot
split.  Run from the repository root:

    python -m benchmarks.study_overhead [--factor 16] [--shards 4]

The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import time
import tracemalloc

import numpy as np

import rotorvib.papers.b.setup as setup_module
from rotorvib.models.balancer.layout import N_METRICS
from rotorvib.papers.b.setup import Setup
from rotorvib.papers.b.studies import balance_study_dataset
from rotorvib.pipeline.config import load_yaml, validate_config
from rotorvib.pipeline.shards import GatheredRuns, ShardRuns, shard_dataset

CONFIG = validate_config(load_yaml("config/config.yaml"), load_yaml("config/schema.yaml"))
B = CONFIG["paper_b"]
STUDY = B["balance_studies"]["beta"]


def no_engine(form, params, y0s, criterion, **kwargs):
    """Metrics of zeros (status OK) for every run: the engine left out."""
    return np.zeros((len(params), N_METRICS))


def build(setup: Setup, n: int, runs):
    """The beta study with ``n`` values of beta, its runs answered by ``runs``."""
    return balance_study_dataset(setup, kinematics=B["kinematics"], ics=B["initial_conditions"],
                                 axis="beta", values=np.linspace(0.1, 1.0, n),
                                 each=STUDY["each"], fixed=STUDY["fixed"], where="benchmark",
                                 runs=runs)


def measured(make):
    """``make()``'s result, CPU seconds and peak traced memory (bytes): two calls, as tracing
    the memory slows the allocations it traces several times."""
    start = time.process_time()
    result = make()
    cpu = time.process_time() - start
    tracemalloc.start()
    make()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return result, cpu, peak


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--factor", type=int, default=16, help="the larger size, in runs")
    parser.add_argument("--shards", type=int, default=4, help="shards of the sharded study")
    args = parser.parse_args()
    setup_module.run_batch = no_engine
    setup = Setup.from_paper_b(B)

    def runs(inputs):
        return setup.runs(inputs, progress=False)

    build(setup, 2, runs)                                      # imports and first calls
    print(f"{'size':>5} {'job':>14} {'run-ups':>8} {'CPU (s)':>8} {'us per run-up':>14} "
          f"{'peak (MB)':>10} {'bytes per run-up':>17}")
    for size in (1, args.factor):
        n = STUDY["range"]["n"] * size
        whole, *costs = measured(lambda: build(setup, n, runs))
        rows = {"whole study": costs}
        pieces = []
        for k in range(args.shards):
            runners = []

            def shard():
                runners.append(ShardRuns(runs, k, args.shards, N_METRICS))
                return build(setup, n, runners[-1])

            _, *costs = measured(shard)
            rows.setdefault(f"shard of {args.shards}", costs)
            pieces.append(shard_dataset(runners[0], "benchmark"))
        _, *rows["gathering"] = measured(lambda: build(setup, n, GatheredRuns(pieces)))
        total = whole.balance_time.size
        for job, (cpu, peak) in rows.items():
            print(f"{size:>4}x {job:>14} {total:>8} {cpu:>8.3f} {1e6 * cpu / total:>14.1f} "
                  f"{peak / 1e6:>10.1f} {peak / total:>17.0f}")


if __name__ == "__main__":
    main()
