"""Independent tasks of one job shared out over forked processes.

A job that runs independent searches whose time goes to Python itself (pymoo's bookkeeping of
paper C's broadband fronts, one search per seed) can use the threads Snakemake gives it only
in processes: threads would take turns on the interpreter. The processes are forked, so each
starts with the job's imports already made. They are not spawned: a spawned process runs the
job's script again, which Snakemake runs as ``__main__``. A forked process leaves by
``os._exit`` and runs none of the job's exit handlers; the CPU it spent counts in the job's
(``getrusage`` of the waited-for children).
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from typing import Callable, Sequence

from rotorvib.checks import integer


def map_forked(function: Callable, items: Sequence, workers: int) -> list:
    """``[function(item) for item in items]``, in order, by up to ``workers`` forked processes
    (in this process where ``workers`` or the number of items is 1). ``function`` must be
    picklable (a module's function, or a ``functools.partial`` of one), and so must each item
    and result. An exception raised by a task is raised here."""
    workers = min(integer("workers", workers, 1), len(items))
    if workers <= 1:
        return [function(item) for item in items]
    context = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
        return list(pool.map(function, items))
