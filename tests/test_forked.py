"""rotorvib.methods.forked: a job's independent tasks in forked processes, in order, their
errors raised in the job."""

import os
from functools import partial

import pytest

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
