"""A job's process (rotorvib.pipeline.job): its imports run without the cyclic collector, which then
works for the job with the imported objects frozen, and its standard error goes to its log."""

import subprocess
import sys

import pytest

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


BURN = """
import subprocess, sys, threading, time
from rotorvib.pipeline import job
job.start(sys.argv[1])

def burn(seconds):
    end = time.thread_time() + seconds       # this thread's CPU
    while time.thread_time() < end:
        pass

burner = threading.Thread(target=burn, args=(0.3,))
burner.start()
burn(0.3)
burner.join()
subprocess.run([sys.executable, "-c", "import time\\nend = time.process_time() + 0.3\\n"
                "while time.process_time() < end: pass"], check=True)
"""


def test_a_job_logs_the_cpu_of_its_threads_and_children_as_it_exits(tmp_path):
    """The log's last line states the CPU the operating system accounts to the job's process
    and the one it waited for: threads, child and start-up included (Snakemake's benchmark
    files keep their last sample, rotorvib.pipeline.job_logs)."""
    import resource

    from rotorvib.pipeline.job_logs import job_cpu

    log = tmp_path / "job.log"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run = subprocess.run([sys.executable, "-c", BURN, str(log)], capture_output=True, text=True,
                         env={"PYTHONPATH": str(ROOT / "src")})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert run.returncode == 0, log.read_text()
    accounted = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    logged = job_cpu(log)
    assert log.read_text().splitlines()[-1].startswith("job CPU: ")
    assert logged >= 0.9                                # two threads' and a child's 0.3 s each
    assert abs(logged - accounted) < 0.05 + 0.05 * accounted, (logged, accounted)


def test_a_log_without_the_cpu_line_states_none_and_is_never_counted_as_0(tmp_path):
    from rotorvib.pipeline.job_logs import job_cpu, jobs_cpu

    done, killed = tmp_path / "done.log", tmp_path / "killed.log"
    done.write_text("12:00:00 GA generations: 20 of 20\njob CPU: 12.500 s\n")
    killed.write_text("12:00:00 GA generations: 3 of 20\n")
    assert job_cpu(done) == 12.5 and job_cpu(killed) is None
    assert jobs_cpu([done, done]) == 25.0
    with pytest.raises(ValueError, match="killed.log: the job states no CPU"):
        jobs_cpu([done, killed])
