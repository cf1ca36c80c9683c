"""Benchmark of a job's start-up: the CPU time of a fresh process that imports what a batch job
and a figure job import (the engine, datasets, plotting) and exits, with and without the
collector pause of ``rotorvib.pipeline.job``, paired and alternating. Run from the repository root:

    python -m benchmarks.job_start [--repeat 7]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys

IMPORTS = ("import rotorvib.models.balancer.simulate, rotorvib.io.datasets, "
           "rotorvib.io.plotting")
PLAIN = f"import sys\n{IMPORTS}\nsys.stderr = open('{os.devnull}', 'w', buffering=1)"
PAUSED = f"from rotorvib.pipeline import job\n{IMPORTS}\njob.start('{os.devnull}')"


def cpu_seconds(code: str) -> float:
    """User plus system CPU seconds of ``python -c code`` (and its threads)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", code], check=True, env={**os.environ,
                   "PYTHONPATH": os.pathsep.join(["src", os.environ.get("PYTHONPATH", "")])})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="pairs of runs (best of)")
    args = parser.parse_args()
    cpu_seconds(PLAIN)  # file system caches warm for both
    plain, paused = zip(*((cpu_seconds(PLAIN), cpu_seconds(PAUSED))
                          for _ in range(args.repeat)))
    print(f"job start-up and exit, CPU s (best of {args.repeat}): "
          f"plain {min(plain):.3f}, collector paused {min(paused):.3f}, "
          f"ratio {min(paused) / min(plain):.2f}")


if __name__ == "__main__":
    main()
