"""A running job's progress on the console, beside its log.

A workflow job writes the library's progress messages (:mod:`rotorvib.io.progress`) to its log
(:func:`rotorvib.pipeline.job.start`); :class:`ConsoleProgress` sends them to the console too,
the terminal Snakemake runs in, so that a run shows which jobs are at work and how far they
are instead of falling silent for a minute: each line names the job (its log's name, the rule
with its wildcards) and is escaped as its log line is (:func:`rotorvib.io.progress.one_line`),
and a job writes at most one every :data:`EVERY` seconds, its first always.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from pathlib import Path

from rotorvib.io.progress import one_line

#: Seconds between two of a job's progress lines on the console (its log has them all).
EVERY = 10.0


class ConsoleProgress(logging.StreamHandler):
    """A logging handler that writes ``"[<job>] <message>"`` to ``stream`` (the console), the
    first record and then at most one every ``every`` seconds of ``clock``."""

    def __init__(self, stream, job: str, *, every: float = EVERY,
                 clock: Callable[[], float] = time.monotonic):
        super().__init__(stream)
        self.job, self.every, self.clock = one_line(job), every, clock
        self.last: float | None = None
        self.setFormatter(logging.Formatter(f"[{self.job}] %(message)s"))

    def filter(self, record: logging.LogRecord) -> bool:
        now = self.clock()
        if self.last is not None and now - self.last < self.every:
            return False
        self.last = now
        return super().filter(record)


def job_name(log: str | Path) -> str:
    """The name a job's console lines carry: its log's, without the folder and ``.log`` (the
    workflow names each job's log after its rule and wildcards, ``b_balance_beta``)."""
    return Path(log).name.removesuffix(".log")
