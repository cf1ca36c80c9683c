"""A run stopped mid-job needs no manual step that its message does not name: Snakemake killed
while a job writes leaves that job's output flagged incomplete (and, killed outright, its lock);
the same command, after the ``--unlock`` the lock's message names, reruns the job."""

import os
import signal
import subprocess
import time

import pytest

from workflow_runs import BIN, REDUCED, copy_repository, environment

TARGET = "results/paper_c/datasets/ga.nc"      # REDUCED writes to results/


def _wait(condition, seconds: float, what: str) -> None:
    end = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > end:
            raise AssertionError(f"waited {seconds} s for {what}")
        time.sleep(0.1)


def _gone(group: int) -> bool:
    try:
        os.killpg(group, 0)
    except ProcessLookupError:
        return True
    return False


@pytest.mark.parametrize("stop", [signal.SIGKILL, signal.SIGINT], ids=["killed", "interrupted"])
def test_an_interrupted_run_resumes_with_the_same_command(tmp_path, stop):
    work = copy_repository(tmp_path / "repo")
    command = [str(BIN / "snakemake"), "-j1", TARGET, *REDUCED]
    run = subprocess.Popen(command, cwd=work, env=environment(work), start_new_session=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    marks = work / ".snakemake/incomplete"
    _wait(lambda: (marks.is_dir() and any(marks.iterdir())) or run.poll() is not None, 120,
          "the job to start")
    assert run.poll() is None, "Snakemake ended before its job started"
    os.kill(run.pid, stop)                          # Snakemake alone, not its job
    run.wait(timeout=60)
    _wait(lambda: _gone(run.pid), 120, "the job Snakemake left to end")
    again = subprocess.run(command, cwd=work, env=environment(work), capture_output=True,
                           text=True, timeout=300)
    if again.returncode != 0:                       # a killed Snakemake leaves its lock
        assert "--unlock" in again.stdout + again.stderr, again.stderr[-2000:]
        subprocess.run([*command, "--unlock"], cwd=work, env=environment(work), check=True,
                       capture_output=True, timeout=120)
        again = subprocess.run(command, cwd=work, env=environment(work), capture_output=True,
                               text=True, timeout=300)
    assert again.returncode == 0, again.stderr[-3000:]
    assert (work / TARGET).is_file() and not any(marks.iterdir())
