"""A job's process (rotorvib.pipeline.job): its imports run without the cyclic collector, which then
works for the job with the imported objects frozen, and its standard error goes to its log."""

import subprocess
import sys

from conftest import ROOT

JOB = """
import gc, sys, weakref, warnings
from rotorvib.pipeline import job
assert not gc.isenabled()
import xarray
job.start(sys.argv[1])
assert gc.isenabled() and gc.get_freeze_count() > 10_000, gc.get_freeze_count()

class Node:
    pass

a, b = Node(), Node()
a.other, b.other = b, a
alive = weakref.ref(a)
del a, b
gc.collect()
assert alive() is None  # the job's own cycles are collected
warnings.warn("to the log")
print("done")
"""


def test_a_job_imports_without_the_collector_and_logs_to_its_file(tmp_path):
    log = tmp_path / "job.log"
    run = subprocess.run([sys.executable, "-c", JOB, str(log)], capture_output=True, text=True,
                         env={"PYTHONPATH": str(ROOT / "src")})
    assert run.returncode == 0, log.read_text() if log.exists() else run.stderr
    assert run.stdout == "done\n" and run.stderr == ""
    assert "UserWarning: to the log" in log.read_text()
