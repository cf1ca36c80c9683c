"""Independent tasks of one job shared out over forked processes.

A job that runs independent searches whose time goes to Python itself (pymoo's bookkeeping of
paper C's broadband fronts, one search per seed) can use the threads Snakemake gives it only
in processes: threads would take turns on the interpreter. The processes are forked, so each
starts with the job's imports already made. They are not spawned: a spawned process runs the
job's script again, which Snakemake runs as ``__main__``. A forked process leaves by
``os._exit`` and runs none of the job's exit handlers; the CPU it spent counts in the job's
(``getrusage`` of the waited-for children).

The workers end with their job, however it ends. Killed outright (SIGKILL, which nothing can
catch), the job leaves them orphans: so each asks the kernel for SIGKILL when the process that
forked it dies (``prctl(PR_SET_PDEATHSIG)``, Linux), and leaves at once if that process is
already gone. Interrupted (Ctrl-C, which reaches the whole process group, or SIGTERM, which
Snakemake and SLURM send to the job alone), the job drops the tasks not yet done and kills its
workers before it exits, instead of finishing every task first: the workers ignore SIGINT,
which their job acts on for them, and SIGTERM raises ``SystemExit`` in the job while it waits
for them.
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from contextlib import contextmanager

from rotorvib.checks import integer

#: ``prctl`` option: the signal this process gets when its parent dies (``<linux/prctl.h>``).
PR_SET_PDEATHSIG = 1


def map_forked(function: Callable, items: Sequence, workers: int) -> list:
    """``[function(item) for item in items]``, in order, by up to ``workers`` forked processes
    (in this process where ``workers`` or the number of items is 1). ``function`` must be
    picklable (a module's function, or a ``functools.partial`` of one), and so must each item
    and result. An exception raised by a task is raised here; on any exception, an interrupt
    included, the tasks not yet done are dropped and the workers killed (module docstring)."""
    workers = min(integer("workers", workers, 1), len(items))
    if workers <= 1:
        return [function(item) for item in items]
    context = multiprocessing.get_context("fork")
    with _sigterm_exits(), context.Pool(workers, _worker_start, (os.getpid(),)) as pool:
        try:
            return pool.map(function, items, chunksize=1)
        finally:
            pool.terminate()               # done: idle workers; else: their tasks dropped
            pool.join()                    # waited for: their CPU counts in the job's


def _worker_start(job: int) -> None:
    """In each worker as it starts: die with the job (``job``, its PID), leave Ctrl-C to it."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != job:                # the job died before the request was made
        os._exit(1)


@contextmanager
def _sigterm_exits():
    """SIGTERM raises ``SystemExit`` (status 143, as the signal's own) in the job's main thread
    while the block runs, so that the workers are killed on the way out; Python's default
    would end the job at once and leave them."""
    if threading.current_thread() is not threading.main_thread():
        yield                              # only the main thread can handle signals
        return

    def exit_143(signum, frame):
        raise SystemExit(128 + signal.SIGTERM)

    previous = signal.signal(signal.SIGTERM, exit_143)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)
