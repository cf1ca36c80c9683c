"""The one-node SLURM script runs as root: it refuses what it did not make, before it installs
or starts anything (no SLURM needed for these tests)."""

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

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


# Another user moving the cluster's folder away as soon as it appears and planting a link to a
# folder of root's in its place (run as nobody, by setpriv).
RACER = """
import os, sys, time
parent, target, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
print("ready", flush=True)
end, won = time.monotonic() + seconds, 0
while time.monotonic() < end:
    try:
        os.rename(f"{parent}/cluster", f"{parent}/moved{won}")
        os.symlink(target, f"{parent}/cluster")
        won += 1
    except OSError:
        pass
print(won)
"""


@pytest.fixture
def shared(tmp_path):
    """A folder that another user (nobody) can reach, and root's folder that must stay as it is
    (the racer's target)."""
    if os.geteuid() != 0 or not shutil.which("setpriv"):
        pytest.skip("racing as another user needs root and setpriv")
    top = Path(tempfile.mkdtemp(prefix="one-node-race-", dir="/tmp"))
    os.chmod(top, 0o755)
    (top / "roots").mkdir(mode=0o755)
    yield top
    shutil.rmtree(top, ignore_errors=True)


def _start_against_a_racer(parent: Path, target: Path, path: str) -> tuple[str, int]:
    racer = subprocess.Popen(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups",
                              sys.executable, "-c", RACER, str(parent), str(target), "3"],
                             stdout=subprocess.PIPE, text=True)
    assert racer.stdout.readline().strip() == "ready"
    run = subprocess.run([str(SCRIPT), "start", str(parent / "cluster")], capture_output=True,
                         text=True, timeout=60, env={**os.environ, "PATH": path})
    racer.terminate()
    racer.wait(timeout=10)
    return run.stderr, run.returncode


@pytest.mark.parametrize("attempt", range(4))
def test_a_parent_others_can_write_is_refused_before_anything_is_made(shared, attempt):
    parent = shared / "open"
    parent.mkdir()
    os.chmod(parent, 0o777)
    stderr, code = _start_against_a_racer(parent, shared / "roots", os.environ["PATH"])
    assert code == 2 and "is writable by others and not sticky" in stderr
    assert list((shared / "roots").iterdir()) == []
    assert not any(p.name.startswith("moved") for p in parent.iterdir())   # nothing was made


def test_a_parent_of_another_user_is_refused(shared):
    parent = shared / "theirs"
    parent.mkdir(mode=0o755)
    os.chown(parent, 65534, 65534)
    run = cluster("start", parent / "cluster")
    assert run.returncode == 2 and "belongs to another user (uid 65534)" in run.stderr
    assert list(parent.iterdir()) == []


@pytest.mark.parametrize("attempt", range(4))
def test_in_a_sticky_parent_the_racer_cannot_move_the_folder(shared, attempt, tmp_path):
    """As /tmp: others may create there but not move root's folder; start makes and marks its
    folder, and stops (77: no SLURM on the PATH given) with root's folder untouched."""
    parent = shared / "sticky"
    parent.mkdir()
    os.chmod(parent, 0o1777)
    tools = tmp_path / "bin"             # what the folder checks need, and no SLURM or apt-get
    tools.mkdir()
    for tool in ("bash", "stat", "mkdir", "dirname", "id"):
        (tools / tool).symlink_to(shutil.which(tool))
    stderr, code = _start_against_a_racer(parent, shared / "roots", str(tools))
    assert code == 77 and "SLURM is not installed" in stderr and "there is no apt-get" in stderr
    assert list((shared / "roots").iterdir()) == []
    made = parent / "cluster"
    assert not made.is_symlink() and (made / ".made-by-one-node-slurm").read_text() == "0\n"
    assert [p.name for p in parent.iterdir()] == ["cluster"]
