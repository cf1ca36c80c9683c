"""Progress of a long computation, in words a person can follow in its job's log.

A :class:`Progress` is called with the count done so far; it logs, through the standard
``logging`` library (logger ``rotorvib.progress``; a workflow job sends it to its log file,
rotorvib.pipeline.job), the count of the total, the time elapsed and an estimate of the time
left (the mean time per step so far, times the steps left), at the first step, the last, and
in between at most every ``every`` seconds.

Each message is one line of the log, whatever its words: a control character in the label or
a note (a newline would start a line that reads as another message, the job's CPU line say)
is written escaped, as Python writes it in a string (``\\n``). The total is checked when the
:class:`Progress` is made, so that a NaN, fractional or negative count fails there, naming the
computation, rather than as a logging error at its first step.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable

from rotorvib.checks import integer

LOGGER = logging.getLogger("rotorvib.progress")


class Progress:
    """``progress(done, note="")`` logs ``"<what>: <done> of <total>, <elapsed> s elapsed,
    about <left> s left[; <note>]"`` (module docstring)."""

    def __init__(self, what: str, total: int, *, every: float = 2.0,
                 clock: Callable[[], float] = time.monotonic):
        self.what, self.every, self.clock = one_line(what), every, clock
        self.total = integer(f"the total of progress {self.what!r}", total, 0)
        self.start = self.last = clock()
        self.logged_once = False

    def __call__(self, done: int, note: str = "") -> None:
        now = self.clock()
        if self.logged_once and done < self.total and now - self.last < self.every:
            return
        elapsed = now - self.start
        left = elapsed / done * (self.total - done) if done else float("nan")
        LOGGER.info("%s: %d of %d, %.1f s elapsed, about %.0f s left%s", self.what, done,
                    self.total, elapsed, left, f"; {one_line(note)}" if note else "")
        self.last, self.logged_once = now, True


def one_line(text: str) -> str:
    """``text`` with each character that is not printable (a line break, a tab, an escape
    sequence's start) escaped as Python's ``repr`` writes it."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(text))
