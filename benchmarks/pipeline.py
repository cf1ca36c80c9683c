"""Benchmark of the whole workflow: the makespan of ``snakemake -j2`` and where the time goes.

Reads the rules' ``benchmark:`` files (``results/benchmarks/*.tsv``: wall and CPU seconds of
each job) and prints them, largest first, with their sum; with ``--run`` it first reruns every
job (``snakemake -j2 --forceall``, extra arguments passed on) and reports the makespan, the
wall time of that command. Run from the repository root:

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

BENCHMARKS = Path("results/benchmarks")


def job_times(directory: Path = BENCHMARKS) -> dict[str, tuple[float, float]]:
    """``{job: (wall s, CPU s)}`` from the benchmark files (a rerun overwrites its file)."""
    times = {}
    for path in sorted(directory.glob("*.tsv")):
        with open(path, newline="") as fh:
            rows = list(csv.DictReader(fh, delimiter="\t"))
        times[path.stem] = (sum(float(r["s"]) for r in rows),
                            sum(float(r["cpu_time"]) for r in rows))
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
        sys.exit(f"no benchmark files in {BENCHMARKS}: run the workflow first")
    print(f"{'job':28s} {'wall (s)':>9} {'CPU (s)':>9}")
    for name, (wall, cpu) in sorted(times.items(), key=lambda item: -item[1][0]):
        print(f"{name:28s} {wall:9.1f} {cpu:9.1f}")
    wall, cpu = (sum(t[i] for t in times.values()) for i in (0, 1))
    print(f"{'sum over benchmarked jobs':28s} {wall:9.1f} {cpu:9.1f}")


if __name__ == "__main__":
    main()
