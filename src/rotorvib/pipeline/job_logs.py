"""What a finished job's log says of the job: the CPU it spent, the line
:func:`rotorvib.pipeline.job.start` has it write last, as its process exits.

Snakemake's ``benchmark:`` files are no measure of a job's CPU: they sample the job every 0.5 s
for its first 15 s and every 30 s after, and keep the last sample, so that a job of 25 s
reports the CPU of its first 15 s. The measurements that add up jobs' CPU (the estimate's
counting pass, ``benchmarks/pipeline.py``, ``benchmarks/scaling.py``) read the logs instead.
"""

from __future__ import annotations

import re
from pathlib import Path

#: :data:`rotorvib.pipeline.job.CPU_LINE` as written (tests/test_job.py writes and reads one).
_CPU_LINE = re.compile(r"^job CPU: ([0-9]+\.[0-9]+) s$", re.MULTILINE)


def job_cpu(log: str | Path) -> float | None:
    """The CPU seconds a finished job's ``log`` states, or None where it states none (a job
    killed before it exited, a log older than the line)."""
    found = _CPU_LINE.findall(Path(log).read_text(encoding="utf-8", errors="replace"))
    return float(found[-1]) if found else None


def jobs_cpu(logs) -> float:
    """The CPU seconds of the jobs whose ``logs`` are given, together; ``ValueError`` naming a
    log that states none (its CPU is unknown, never 0)."""
    total = 0.0
    for log in logs:
        if (cpu := job_cpu(log)) is None:
            raise ValueError(f"{log}: the job states no CPU (killed before it exited?)")
        total += cpu
    return total
