"""Paper A's configuration checks beyond the schema (:func:`problems`), each named by its key
within ``paper_a``; the workflow runs them when it reads the configuration, before any job
(:mod:`rotorvib.pipeline.config_checks`, which writes the messages)."""

from __future__ import annotations

from rotorvib.papers.config_problems import tolerance_problem


def problems(a: dict) -> list[tuple[str, str]]:
    """Every problem of the ``paper_a`` section of a configuration that satisfies the schema,
    as ``(key within paper_a, what is wrong)``: a Runge-Kutta tolerance finer than double
    precision."""
    problem = tolerance_problem(a["rk"]["rtol"])
    return [("rk.rtol", problem)] if problem else []
