"""Benchmark of the whole workflow: the makespan of ``snakemake -j2`` and where the time goes.

Prints every job of the last run, largest CPU first, with the sums: its CPU seconds as its log
states them (``results/logs/*.log``, :mod:`rotorvib.pipeline.job_logs`; Snakemake's
``benchmark:`` files keep a sample taken up to 30 s before a job ends) and, for a rule with a
``benchmark:`` file (``results/benchmarks/*.tsv``), its wall seconds; with ``--run`` it first
reruns every job (``snakemake -j2 --forceall``, extra arguments passed on) and reports the
makespan, the wall time of that command. Run from the repository root:

    python -m benchmarks.pipeline [--run] [-- --configfile config/config.yaml my.yaml]

The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import time
from pathlib import Path

from rotorvib.pipeline.job_logs import job_cpu

BENCHMARKS = Path("results/benchmarks")
LOGS = Path("results/logs")


def job_times(logs: Path = LOGS, benchmarks: Path = BENCHMARKS
              ) -> dict[str, tuple[float | None, float]]:
    """``{job: (wall s or None, CPU s)}``: the CPU each job's log states, the wall time from
    its rule's benchmark file where it has one; a job whose log states no CPU (killed, or a
    ``run:`` block) is left out."""
    times = {}
    for log in sorted(logs.glob("*.log")):
        if (cpu := job_cpu(log)) is None:
            continue
        bench = benchmarks / f"{log.stem}.tsv"
        wall = None
        if bench.is_file():
            with open(bench, newline="") as fh:
                wall = sum(float(r["s"]) for r in csv.DictReader(fh, delimiter="\t"))
        times[log.stem] = (wall, cpu)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run", action="store_true", help="rerun every job first, timed")
    parser.add_argument("snakemake_args", nargs="*", help="passed to snakemake with --run")
    args = parser.parse_args()
    if args.run:
        start = time.perf_counter()
        subprocess.run([Path(sys.executable).parent / "snakemake", "-j2", "--forceall",
                        "--quiet", *args.snakemake_args], check=True)
        print(f"makespan of snakemake -j2 --forceall: {time.perf_counter() - start:.1f} s")
    times = job_times()
    if not times:
        sys.exit(f"no job logs stating their CPU in {LOGS}: run the workflow first")
    print(f"{'job':32s} {'wall (s)':>9} {'CPU (s)':>9}")
    for name, (wall, cpu) in sorted(times.items(), key=lambda item: -item[1][1]):
        print(f"{name:32s} {'-' if wall is None else f'{wall:.1f}':>9} {cpu:9.1f}")
    print(f"{'sum over the jobs':32s} {'':>9} {sum(cpu for _, cpu in times.values()):9.1f}")
    print(f"{'sum over the benchmarked jobs':32s} "
          f"{sum(w for w, _ in times.values() if w is not None):9.1f} "
          f"{sum(c for w, c in times.values() if w is not None):9.1f}")


if __name__ == "__main__":
    main()
