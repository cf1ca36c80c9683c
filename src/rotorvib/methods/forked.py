"""Independent tasks of one job shared out over forked processes.

A job that runs independent searches whose time goes to Python itself (pymoo's bookkeeping of
paper C's broadband fronts, one search per seed) can use the threads Snakemake gives it only
in processes: threads would take turns on the interpreter. The processes are forked, so each
starts with the job's imports already made. They are not spawned: a spawned process runs the
job's script again, which Snakemake runs as ``__main__``. A forked process leaves by
``os._exit`` and runs none of the job's exit handlers; the CPU it spent counts in the job's
(``getrusage`` of the waited-for children).

Worker ``k`` of ``n`` computes the items ``k, k + n, ...`` and sends their results (or the first
error) through a pipe of its own when it is done; the job reads the pipes in turn and puts the
results back in order. No thread, queue or lock is shared with the workers, so nothing the job
waits on can be left held by a worker that died.

The workers end with their job, however it ends. Killed (SIGKILL) or terminated (SIGTERM,
which Snakemake and SLURM send to the job alone), the job leaves them orphans: so each asks the
kernel for SIGKILL when the process that forked it dies (``prctl(PR_SET_PDEATHSIG)``, Linux),
and leaves at once if that process is already gone. Interrupted (Ctrl-C, which reaches the
whole process group), the workers ignore it and the job, on any exception, kills them and
reaps them before it raises.
"""

from __future__ import annotations

import ctypes
import os
import pickle
import signal
import sys
from collections.abc import Callable, Sequence

from rotorvib.checks import integer

#: ``prctl`` option: the signal this process gets when its parent dies (``<linux/prctl.h>``).
PR_SET_PDEATHSIG = 1


def map_forked(function: Callable, items: Sequence, workers: int) -> list:
    """``[function(item) for item in items]``, in order, by up to ``workers`` forked processes
    (in this process where ``workers`` or the number of items is 1). Each item's result must be
    picklable. An exception raised by a task is raised here; on any exception, an interrupt
    included, the workers are killed first (module docstring)."""
    workers = min(integer("workers", workers, 1), len(items))
    if workers <= 1:
        return [function(item) for item in items]
    pipes = {}
    try:
        for k in range(workers):
            read, write = os.pipe()
            pid = os.fork()
            if pid == 0:
                os.close(read)
                _work(function, items[k::workers], write, os.getppid())
            os.close(write)
            pipes[pid] = read
        shares = [_received(read) for read in pipes.values()]
    except BaseException:
        for pid in pipes:
            os.kill(pid, signal.SIGKILL)
        raise
    finally:
        for pid, read in pipes.items():
            os.close(read)
            os.waitpid(pid, 0)             # reaped: their CPU counts in the job's
    results = [None] * len(items)
    for k, share in enumerate(shares):
        results[k::workers] = share
    return results


def _work(function: Callable, share: Sequence, write: int, job: int) -> None:
    """In a worker: die with the job (``job``, its PID), leave Ctrl-C to it, compute ``share``
    and send ``(True, results)`` or ``(False, the first error)`` through ``write``; never
    returns."""
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        if sys.platform.startswith("linux"):
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        if os.getppid() != job:            # the job died before the request was made
            os._exit(1)
        try:
            message = pickle.dumps((True, [function(item) for item in share]))
        except Exception as error:         # the job raises it
            message = pickle.dumps((False, _picklable(error)))
        with os.fdopen(write, "wb") as fh:
            fh.write(message)
        os._exit(0)
    finally:
        os._exit(1)                        # never back into the job's code


def _picklable(error: Exception) -> Exception:
    """``error``, or a RuntimeError saying what it was where it cannot be pickled."""
    try:
        pickle.loads(pickle.dumps(error))
        return error
    except Exception:
        return RuntimeError(f"{type(error).__name__}: {error}")


def _received(read: int) -> list:
    """A worker's results from its pipe; its error raised here; a RuntimeError where it ended
    without sending them."""
    with os.fdopen(read, "rb", closefd=False) as fh:
        data = fh.read()
    if not data:
        raise RuntimeError("a forked worker ended without its results")
    ok, payload = pickle.loads(data)
    if not ok:
        raise payload
    return payload
