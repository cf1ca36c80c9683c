"""The process of one workflow job: its start-up, its log and the configuration it records.

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

The module imports nothing of the workflow's machinery (the configuration's loader and checks,
the fingerprints, the report): a job's code fingerprint holds the science it runs and this
start-up, so that an edit of the machinery reruns no job.
"""

import atexit
import gc
import logging
import os
import sys

from rotorvib.pipeline import console, pint_probe

gc.disable()

#: The last line of a finished job's log: the CPU seconds its process spent, user and system, its
#: threads and the processes it waited for included (:func:`start`; read by
#: :func:`rotorvib.pipeline.job_logs.job_cpu`, which a job never imports).
CPU_LINE = "job CPU: {:.3f} s"

#: The parameter through which the workflow gives a job the rule that makes each input dataset
#: and the hash of that rule's configuration (checked by
#: :func:`rotorvib.io.datasets.read_dataset`).
INPUT_PRODUCERS_PARAM = "input_producers"


def job_config(params) -> dict:
    """The configuration a job records in its datasets: its rule's parameters (a mapping, e.g.
    ``snakemake.params``) without the input check :data:`INPUT_PRODUCERS_PARAM` itself."""
    return {k: v for k, v in params.items() if k != INPUT_PRODUCERS_PARAM}


def start(log: str) -> None:
    """End the job's start-up: the objects made so far frozen, the collector on again, and
    standard error (warnings, a traceback, the library's progress messages with their time:
    rotorvib.io.progress) written to the job's ``log`` file, line by line, ending, as the
    process exits, with the CPU it spent (:data:`CPU_LINE`); the progress messages also go,
    fewer and named after the job, to the console (:class:`rotorvib.pipeline.console.
    ConsoleProgress`).  xarray's probe for pint quantities is answered without importing pint
    (:mod:`rotorvib.pipeline.pint_probe`)."""
    pint_probe.skip()
    gc.freeze()
    gc.enable()
    terminal, sys.stderr = sys.stderr, open(log, "w", buffering=1)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(asctime)s %(message)s", datefmt="%H:%M:%S"))
    library = logging.getLogger("rotorvib")       # the package's messages only, not others'
    library.addHandler(handler)
    library.setLevel(logging.INFO)
    logging.getLogger("rotorvib.progress").addHandler(
        console.ConsoleProgress(terminal, console.job_name(log)))
    atexit.register(_log_cpu)


def _log_cpu() -> None:
    times = os.times()
    spent = times.user + times.system + times.children_user + times.children_system
    print(CPU_LINE.format(spent), file=sys.stderr, flush=True)
