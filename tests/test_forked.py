"""rotorvib.methods.forked: a job's independent tasks in forked processes, in order, their
errors raised in the job; the workers end with their job, however it ends."""

import os
import signal
import subprocess
import sys
import time
from functools import partial

import pytest

from conftest import ROOT
from rotorvib.methods.forked import map_forked


def _pid_and_square(offset, x):
    if x < 0:
        raise ArithmeticError(f"negative: {x}")
    return os.getpid(), (x + offset) ** 2


def test_results_come_in_the_items_order_from_other_processes_when_there_are_workers():
    items = list(range(7))
    serial = map_forked(partial(_pid_and_square, 1), items, workers=1)
    forked = map_forked(partial(_pid_and_square, 1), items, workers=3)
    assert [r for _, r in forked] == [r for _, r in serial] == [(x + 1) ** 2 for x in items]
    assert {pid for pid, _ in serial} == {os.getpid()}
    pids = {pid for pid, _ in forked}
    assert os.getpid() not in pids and 1 <= len(pids) <= 3


def test_one_item_runs_here_and_a_tasks_error_is_raised_here():
    assert map_forked(partial(_pid_and_square, 0), [3], workers=4) == [(os.getpid(), 9)]
    with pytest.raises(ArithmeticError, match="negative: -2"):
        map_forked(partial(_pid_and_square, 0), [1, -2, 3], workers=2)


@pytest.mark.parametrize("workers", [0, -1, 1.5, True])
def test_workers_must_be_a_positive_integer(workers):
    with pytest.raises(ValueError, match="workers"):
        map_forked(abs, [1, 2], workers)


# A job that shares out eight 30-second busy tasks over two forked workers; each worker says
# its PID as it starts a task.
JOB = r"""
import os, sys, time
from functools import partial
from rotorvib.methods.forked import map_forked

def busy(seconds, item):
    os.write(1, f"{os.getpid()}\n".encode())       # one write: the lines never interleave
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        pass
    return item

map_forked(partial(busy, 30.0), list(range(8)), 2)
"""


def _running(pid: int) -> bool:
    """Whether ``pid`` is a process that has not ended (a zombie has)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rpartition(")")[2].split()[0] != "Z"
    except FileNotFoundError:
        return False


def _wait_until(condition, seconds: float) -> bool:
    end = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > end:
            return False
        time.sleep(0.05)
    return True


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc and PR_SET_PDEATHSIG")
@pytest.mark.parametrize("stop, status", [(signal.SIGKILL, -signal.SIGKILL),
                                          (signal.SIGINT, -signal.SIGINT),
                                          (signal.SIGTERM, -signal.SIGTERM)],
                         ids=["killed", "interrupted", "terminated"])
def test_the_workers_end_with_their_job(stop, status):
    """Killed, interrupted or terminated mid-task, the job ends and so do its workers, within
    seconds (before, its killed or terminated job's workers ran on past 60 s and the
    interrupted one finished its running tasks first, 40 s; each task here takes 30 s); the job
    ends as Python's does on each signal."""
    # Ctrl-C's default restored: a pytest-xdist worker ignores SIGINT, and a child inherits that
    job = subprocess.Popen([sys.executable, "-c", JOB], stdout=subprocess.PIPE, text=True,
                           env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
                           preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    workers = set()
    try:
        workers = {int(job.stdout.readline()) for _ in range(2)}
        assert len(workers) == 2 and all(map(_running, workers))
        os.kill(job.pid, stop)
        assert job.wait(timeout=10) == status
        assert _wait_until(lambda: not any(map(_running, workers)), 10), \
            f"workers {sorted(filter(_running, workers))} outlived their job"
    finally:
        job.kill()
        for pid in filter(_running, workers):
            os.kill(pid, signal.SIGKILL)
