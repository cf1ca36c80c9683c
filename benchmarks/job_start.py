"""Benchmark of a job's start-up: the CPU time of fresh processes, each pair run alternately, for
what a job's start-up leaves out:

- the collector pause of ``rotorvib.pipeline.job``: a process that imports what a batch job and
  a figure job import (the engine, datasets, plotting) and exits, plain and paused;
- pint (``rotorvib.pipeline.pint_probe``): a process that writes and reads a dataset, as xarray
  does it by itself (importing pint to recognise quantities) and with the probe answered;
- sympy (``rotorvib.methods.codegen``): a process that evaluates the balancer's stability from
  the generated code's cache, with sympy imported besides (as when the derivation shared the
  module) and without.

Run from the repository root:

    python -m benchmarks.job_start [--repeat 7]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile

from benchmarks import children_cpu

IMPORTS = ("import rotorvib.models.balancer.simulate, rotorvib.io.datasets, "
           "rotorvib.io.plotting")
DATASET = ("import numpy as np, xarray as xr\n"
           "ds = xr.Dataset({'a': ('x', np.arange(3.0))}, coords={'x': [0.0, 1.0, 2.0]})\n"
           "ds.to_netcdf(PATH)\nxr.load_dataset(PATH)")
STABILITY = ("from rotorvib.models.balancer import stability\n"
             "stability.max_real_part(0.01, 0.75, 0.01, 0.5, 2.0)")
#: (what is measured, the code without the start-up's saving, the code with it)
PAIRS = {
    "collector paused": (
        f"import sys\n{IMPORTS}\nsys.stderr = open('{os.devnull}', 'w', buffering=1)",
        f"from rotorvib.pipeline import job\n{IMPORTS}\njob.start('{os.devnull}')"),
    "pint probe answered": (
        DATASET,
        f"import xarray\nfrom rotorvib.pipeline import pint_probe\npint_probe.skip()\n{DATASET}"),
    "stability without sympy": (f"import sympy\n{STABILITY}", STABILITY),
}


def cpu_seconds(code: str, path: str) -> float:
    """User plus system CPU seconds of ``python -c code`` (and its threads), ``PATH`` in it a
    file name it may write."""
    before = children_cpu()
    subprocess.run([sys.executable, "-c", f"PATH = {path!r}\n{code}"], check=True,
                   env={**os.environ,
                        "PYTHONPATH": os.pathsep.join(["src", os.environ.get("PYTHONPATH", "")])})
    return children_cpu() - before


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="pairs of runs (best of)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "d.nc")
        for what, (before, after) in PAIRS.items():
            cpu_seconds(after, path)  # caches warm (file system, generated code) for both
            pairs = [(cpu_seconds(before, path), cpu_seconds(after, path))
                     for _ in range(args.repeat)]
            without, with_ = (min(times) for times in zip(*pairs))
            print(f"{what}: CPU s of a job's process (best of {args.repeat}): without "
                  f"{without:.3f}, with {with_:.3f}, ratio {with_ / without:.2f}")


if __name__ == "__main__":
    main()
