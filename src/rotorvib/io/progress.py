"""Progress of a long computation, in words a person can follow in its job's log.

A :class:`Progress` is called with the count done so far; it logs, through the standard
``logging`` library (logger ``rotorvib.progress``; a workflow job sends it to its log file,
rotorvib.pipeline.job), the count of the total, the time elapsed and an estimate of the time
left (the mean time per step so far, times the steps left), at the first step, the last, and
in between at most every ``every`` seconds.
"""

from __future__ import annotations

import logging
import time
from typing import Callable

LOGGER = logging.getLogger("rotorvib.progress")


class Progress:
    """``progress(done, note="")`` logs ``"<what>: <done> of <total>, <elapsed> s elapsed,
    about <left> s left[; <note>]"`` (module docstring)."""

    def __init__(self, what: str, total: int, *, every: float = 2.0,
                 clock: Callable[[], float] = time.monotonic):
        self.what, self.total, self.every, self.clock = what, total, every, clock
        self.start = self.last = clock()
        self.logged_once = False

    def __call__(self, done: int, note: str = "") -> None:
        now = self.clock()
        if self.logged_once and done < self.total and now - self.last < self.every:
            return
        elapsed = now - self.start
        left = elapsed / done * (self.total - done) if done else float("nan")
        LOGGER.info("%s: %d of %d, %.1f s elapsed, about %.0f s left%s", self.what, done,
                    self.total, elapsed, left, f"; {note}" if note else "")
        self.last, self.logged_once = now, True
