"""Benchmarks of the reproduction, each a module run as ``python -m benchmarks.<name>``."""

import resource


def children_cpu() -> float:
    """User + system seconds of every child process this process has waited for so far: the
    difference across a ``subprocess.run`` is that command's CPU, its threads and children
    included."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime
