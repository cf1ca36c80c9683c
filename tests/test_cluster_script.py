"""The one-node SLURM script runs as root: it refuses what it did not make, before it installs
or starts anything (no SLURM needed for these tests)."""

import os
import shutil
import stat
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
    for tool in ("bash", "stat", "mkdir", "dirname", "id", "readlink"):
        (tools / tool).symlink_to(shutil.which(tool))
    stderr, code = _start_against_a_racer(parent, shared / "roots", str(tools))
    assert code == 77 and "SLURM is not installed" in stderr and "there is no apt-get" in stderr
    assert list((shared / "roots").iterdir()) == []
    made = parent / "cluster"
    assert not made.is_symlink() and (made / ".made-by-one-node-slurm").read_text() == "0\n"
    assert [p.name for p in parent.iterdir()] == ["cluster"]


def _start_through(parent: Path, tools: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(SCRIPT), "start", str(parent / "cluster")], check=False,
                          capture_output=True, text=True, timeout=60,
                          env={**os.environ, "PATH": str(tools)})


def _tools(where: Path, names=("bash", "stat", "mkdir", "dirname", "id", "readlink")) -> Path:
    """A PATH of the tools the folder checks need, and no SLURM or apt-get (start then stops,
    77, once its folder is made)."""
    where.mkdir()
    for tool in names:
        (where / tool).symlink_to(shutil.which(tool))
    return where


@pytest.mark.parametrize("nested", [False, True], ids=["theirs", "mine-through-theirs"])
def test_a_symbolic_link_of_another_user_on_the_way_is_refused(shared, tmp_path, nested):
    """A link of nobody's on the way to DIR, or in the target of root's own link, is refused
    before anything is made: its owner could point it at a folder of theirs between the checks
    and the writes. A link of root's own is followed (the folder is made in its target)."""
    (shared / "sticky").mkdir()
    os.chmod(shared / "sticky", 0o1777)
    theirs = shared / "sticky/theirs"
    subprocess.run(["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", "ln", "-s",
                    str(shared / "roots"), str(theirs)], check=True)
    assert theirs.lstat().st_uid == 65534
    tools = _tools(tmp_path / "bin")
    via = theirs
    if nested:
        via = shared / "mine"
        via.symlink_to(theirs)
    run = _start_through(via, tools)
    assert run.returncode == 2, run.stderr
    assert f"{theirs} is a symbolic link of another user (uid 65534)" in run.stderr
    assert list((shared / "roots").iterdir()) == []
    (shared / "own").symlink_to(shared / "roots")
    run = _start_through(shared / "own", tools)
    assert run.returncode == 77 and (shared / "roots/cluster/.made-by-one-node-slurm").is_file()


# `mkdir` as a racer that wins at once: it makes the folders asked for, then plants a link to
# the victim at PLANT inside the cluster's folder as soon as PLANT's folder exists.
PLANTING_MKDIR = """#!/bin/bash
{mkdir} "$@" || exit
plant=$CLUSTER/$PLANT
[[ -d $(dirname -- "$plant") && ! -L $plant ]] && ln -s "$VICTIM" "$plant"
exit 0
"""


@pytest.mark.parametrize("plant", [".made-by-one-node-slurm", "slurm.conf", "run/munge.key"])
def test_a_file_of_the_cluster_is_created_never_written_through_a_link(tmp_path, plant):
    """The mark, the configuration and the munge key are created (noclobber), so that a link
    planted in their place is refused, not followed: the victim keeps its bytes and its mode
    (before, the key's `dd` overwrote it and `chmod 400` made it root's key). Past the mark,
    start needs root (it writes the configuration only as root)."""
    if plant != ".made-by-one-node-slurm" and os.geteuid() != 0:
        pytest.skip("start writes its configuration and key only as root")
    victim = tmp_path / "victim"
    victim.write_text("precious\n")
    os.chmod(victim, 0o644)
    tools = _tools(tmp_path / "bin", ("bash", "stat", "dirname", "id", "readlink", "ln",
                                      "hostname", "nproc", "awk", "python3", "cat", "head",
                                      "chmod", "seq", "sleep"))
    (tools / "mkdir").write_text(PLANTING_MKDIR.format(mkdir=shutil.which("mkdir")))
    (tools / "mkdir").chmod(0o755)
    for fake in ("slurmctld", "slurmd", "sbatch", "munged"):     # "installed", never reached
        (tools / fake).write_text("#!/bin/sh\nexit 1\n")
        (tools / fake).chmod(0o755)
    (tmp_path / "top").mkdir(mode=0o755)
    cluster_dir = tmp_path / "top/cluster"
    run = subprocess.run([str(SCRIPT), "start", str(cluster_dir)], check=False,
                         capture_output=True, text=True, timeout=60,
                         env={**os.environ, "PATH": str(tools), "CLUSTER": str(cluster_dir),
                              "PLANT": plant, "VICTIM": str(victim)})
    assert (cluster_dir / plant).is_symlink(), run.stderr          # the racer did plant it
    assert run.returncode == 1 and "cannot overwrite existing file" in run.stderr
    assert victim.read_text() == "precious\n" and stat.S_IMODE(victim.stat().st_mode) == 0o644
