"""The one-node SLURM script runs as root: it refuses what it did not make, before it installs
or starts anything (no SLURM needed for these tests)."""

import os
import subprocess

import pytest

from conftest import ROOT

SCRIPT = ROOT / "workflow/cluster/one-node-slurm"


def cluster(action, where) -> subprocess.CompletedProcess:
    return subprocess.run([str(SCRIPT), action, str(where)], capture_output=True, text=True,
                          timeout=60)


def test_start_refuses_a_directory_that_exists(tmp_path):
    prepared = tmp_path / "cluster"
    prepared.mkdir()
    (prepared / "slurm.conf").symlink_to(tmp_path / "victim")
    run = cluster("start", prepared)
    assert run.returncode == 2 and "exists: give a directory that does not exist yet" in run.stderr
    assert not (tmp_path / "victim").exists()


def test_start_refuses_a_symbolic_link(tmp_path):
    (tmp_path / "link").symlink_to(tmp_path / "elsewhere")
    run = cluster("start", tmp_path / "link")
    assert run.returncode == 2 and "exists" in run.stderr
    assert not (tmp_path / "elsewhere").exists()


def _made_by_start(where, mode=0o700):
    """A directory as ``start`` leaves it: its own, private, marked."""
    where.mkdir(mode=mode)
    os.chmod(where, mode)
    (where / ".made-by-one-node-slurm").write_text(f"{os.getuid()}\n")
    (where / "run").mkdir()
    return where


@pytest.mark.parametrize("prepare, refusal", [
    (lambda d: d.mkdir(), "was not made by one-node-slurm start"),
    (lambda d: _made_by_start(d, 0o777), "is writable by others"),
])
def test_stop_refuses_a_directory_start_did_not_make_or_others_can_write(tmp_path, prepare,
                                                                         refusal):
    prepare(tmp_path / "cluster")
    run = cluster("stop", tmp_path / "cluster")
    assert run.returncode == 2 and refusal in run.stderr


@pytest.mark.parametrize("pid_text", ["-1", "0", "1 2", "$(touch x)", "{sleeper}"])
def test_stop_kills_only_a_process_it_started(tmp_path, pid_text):
    """A pid file holding -1 (kill -9 -1 kills everything), 0, junk, or the PID of another
    program (here a `sleep` of this user, not slurmd): nothing is killed, a warning says why."""
    where = _made_by_start(tmp_path / "cluster")
    sleeper = subprocess.Popen(["sleep", "60"])
    try:
        (where / "run/slurmd.pid").write_text(pid_text.format(sleeper=sleeper.pid) + "\n")
        run = cluster("stop", where)
        assert run.returncode == 0, run.stderr
        assert sleeper.poll() is None, "a process the script did not start was killed"
        assert "left alone" in run.stderr
        assert not (where / "run/slurmd.pid").exists()
    finally:
        sleeper.kill()
        sleeper.wait()
