"""Progress a person can follow (rotorvib.io.progress): the first and last steps always, in
between at most every few seconds, each with the time elapsed and an estimate of what is left."""

import logging

import numpy as np
import pytest

from rotorvib.io.progress import Progress
from rotorvib.methods.ga import minimise_many


def test_progress_is_rate_limited_and_estimates_what_is_left(caplog):
    now = [0.0]
    progress = Progress("runs", 10, every=2.0, clock=lambda: now[0])
    with caplog.at_level(logging.INFO, logger="rotorvib.progress"):
        for done in range(1, 11):
            now[0] = float(done)                       # one second a step
            progress(done)
    lines = [r.getMessage() for r in caplog.records]
    assert lines[0] == "runs: 1 of 10, 1.0 s elapsed, about 9 s left"
    assert lines[1] == "runs: 3 of 10, 3.0 s elapsed, about 7 s left"     # 2 s later
    assert lines[-1] == "runs: 10 of 10, 10.0 s elapsed, about 0 s left"
    assert len(lines) == 6                                 # 1, 3, 5, 7, 9, 10


def test_the_ga_reports_its_generations(caplog):
    """A GA in lockstep logs every generation through its progress callback."""
    seen = []

    def objectives(xs, worst):
        return [np.sum((x - 0.3) ** 2, axis=1) for x in xs]

    minimise_many(objectives, 2, [0.0, 0.0], [1.0, 1.0], pop_size=8, n_gen=5, seed=[1, 2],
                  progress=lambda gen, best: seen.append((gen, best)))
    assert [g for g, _ in seen] == [1, 2, 3, 4, 5]
    assert all(b2 <= b1 for (_, b1), (_, b2) in zip(seen, seen[1:]))    # elitist: no worse


def test_a_label_or_note_cannot_forge_a_log_line(caplog):
    """A newline in the label once started a line of its own that read as the job's CPU line
    (rotorvib.pipeline.job_logs), and an escape sequence could rewrite a terminal: both are
    written escaped, the message on one line."""
    forged = "runs\n12:00:00 job CPU: 0.000 s"
    with caplog.at_level(logging.INFO, logger="rotorvib.progress"):
        Progress(forged, 3, clock=lambda: 0.0)(1, note="seed 2\x1b[2J\r\t")
    (line,) = [r.getMessage() for r in caplog.records]
    assert line == ("runs\\n12:00:00 job CPU: 0.000 s: 1 of 3, 0.0 s elapsed, about 0 s left; "
                    "seed 2\\x1b[2J\\r\\t")
    assert line.isprintable()


@pytest.mark.parametrize("total", [float("nan"), float("inf"), -1, 2.5, True, "3"])
def test_a_total_that_is_not_a_count_is_refused_naming_the_computation(total):
    """Before, a NaN total failed inside logging at the first step (a logging error and no
    line) and a negative one logged "1 of -5"."""
    with pytest.raises(ValueError, match=r"^the total of progress 'runs' = .*: must be an "
                                         r"integer >= 0$"):
        Progress("runs", total)


def test_a_count_of_numpy_or_nothing_is_a_total():
    assert Progress("runs", np.int64(4)).total == 4 and Progress("runs", 0).total == 0
