"""The process of one workflow job: its start-up and its log.

Every job script imports this module before anything else and calls :func:`start` once its
imports are done (a module it imports by name included). A job is a fresh Python process whose
imports (numpy, pandas, xarray, matplotlib, numba, pymoo) create over a hundred thousand
container objects, almost none of them garbage; Python's cyclic collector, triggered every 700
net container allocations, scans them hundreds of times while they are created, and once more
when the process exits. So importing this module switches the collector off, and :func:`start`
moves everything the imports made into the permanent generation (:func:`gc.freeze`), which no
later collection scans, the one at exit included, then switches the collector on for the job's
own work. ``python -m benchmarks.job_start`` measures what this saves a job that imports the
engine, xarray and matplotlib.

Before that, a job that the server of its Snakemake run can run (rotorvib.pipeline.warm_start:
a process that has imported those libraries already) is handed over to it, and this process
only waits for its exit status.
"""

import gc
import sys

from rotorvib.pipeline.warm_start import hand_over

hand_over()       # returns when this process is to run the job itself
gc.disable()


def start(log: str) -> None:
    """End the job's start-up: the objects made so far frozen, the collector on again, and
    standard error (warnings, a traceback) written to the job's ``log`` file, line by line."""
    gc.freeze()
    gc.enable()
    sys.stderr = open(log, "w", buffering=1)
