"""The warm start of script jobs (rotorvib.pipeline.warm_start): a job handed over to the server
runs as its own process would, and only the jobs that should be are handed over.

Each test starts a server from this process (as the Snakefile's ``onstart`` does from
Snakemake's) and runs jobs as Snakemake runs a script: a child process whose ``__main__`` holds a
``snakemake`` object and the script's ``__real_file__``, whose first import is
``rotorvib.pipeline.job``.
"""

import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from conftest import ROOT
from rotorvib.pipeline import warm_start

PREAMBLE = """\
import types
snakemake = types.SimpleNamespace(bench_iteration={bench})
__real_file__ = __file__
from rotorvib.pipeline import job
import os
served = os.getppid() == int(os.environ["SERVER"])
"""


@pytest.fixture
def server(monkeypatch):
    monkeypatch.delenv(warm_start.DISABLE, raising=False)
    monkeypatch.setenv("PYTHONPATH", str(ROOT / "src"))
    started = warm_start.Server()
    started.start()
    path = os.environ[warm_start.ADDRESS].rpartition(":")[0]
    wait_until(Path(path).exists, 30)
    monkeypatch.setenv("SERVER", str(started.process.pid))
    yield started
    started.stop()


def wait_until(holds, seconds: float) -> None:
    """Poll ``holds()`` until it is true or ``seconds`` have passed (the caller asserts)."""
    deadline = time.monotonic() + seconds
    while not holds() and time.monotonic() < deadline:
        time.sleep(0.01)


def running(pid) -> bool:
    """Whether process ``pid`` runs (exists and is not a zombie waiting for its parent)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()[0] != "Z"
    except OSError:
        return False


def job(tmp_path: Path, body: str, *args: str, bench=None, env=None, stdin=None):
    """Run ``body`` as a script job (``served`` says whether the server ran it)."""
    script = tmp_path / "job.py"
    script.write_text(PREAMBLE.format(bench=bench) + body)
    return subprocess.run([sys.executable, str(script), *args], cwd=tmp_path, text=True,
                          input=stdin, capture_output=True, env={**os.environ, **(env or {})},
                          timeout=60)


WORK = """\
import sys
print(served, os.getcwd(), sys.argv[1:], os.environ["GIVEN"], sys.stdin.read())
print("to stderr", file=sys.stderr)
"""


@pytest.mark.parametrize("ending, code, said", [
    ("sys.exit(3)", 3, ""),
    ("sys.exit('stopped: a message')", 1, "stopped: a message\n"),
    ("raise ValueError('no such case')", 1, "ValueError: no such case\n"),
])
def test_a_served_job_runs_and_ends_as_its_own_process(server, tmp_path, monkeypatch, ending,
                                                       code, said):
    """Folder, arguments, environment, standard input and output, exit status and an uncaught
    exception's traceback (from the script's line on) are those of the job's own process."""
    runs = {}
    for case in ("served", "own"):
        if case == "own":
            monkeypatch.delenv(warm_start.ADDRESS)
        runs[case] = job(tmp_path, WORK + ending + "\n", "a", "b c", env={"GIVEN": "given"},
                         stdin="from stdin")
    assert runs["served"].stdout == f"True {tmp_path} ['a', 'b c'] given from stdin\n"
    assert runs["own"].stdout == runs["served"].stdout.replace("True", "False", 1)
    assert runs["served"].returncode == runs["own"].returncode == code
    assert runs["served"].stderr == runs["own"].stderr
    assert runs["served"].stderr.startswith("to stderr\n") and runs["served"].stderr.endswith(said)
    assert "warm_start" not in runs["served"].stderr


def test_the_server_holds_the_libraries_a_job_loaded_and_none_of_the_workflow(server, tmp_path):
    first = job(tmp_path, "import sys, xml.dom.minidom, rotorvib.checks\nprint(served)\n")
    assert (first.returncode, first.stdout) == (0, "True\n"), first.stderr
    second = job(tmp_path, "import sys\nprint(served, 'xml.dom.minidom' in sys.modules, "
                           "sorted(m for m in sys.modules if m.startswith('rotorvib')))\n")
    # the library held; of the package, only what this job imported itself (afresh)
    assert second.stdout == ("True True ['rotorvib', 'rotorvib.pipeline', 'rotorvib.pipeline.job',"
                             " 'rotorvib.pipeline.warm_start']\n"), second.stderr


def test_a_benchmarked_job_and_a_job_of_another_run_run_in_their_own_process(server, tmp_path):
    assert job(tmp_path, "print(served)\n").stdout == "True\n"
    assert job(tmp_path, "print(served)\n", bench=0).stdout == "False\n"
    # the variable reached a process that Snakemake's process did not start (a SLURM job)
    path = os.environ[warm_start.ADDRESS].rpartition(":")[0]
    other = {warm_start.ADDRESS: f"{path}:{server.process.pid}"}
    assert job(tmp_path, "print(served)\n", env=other).stdout == "False\n"


def test_a_malformed_request_is_refused_and_the_server_serves_on(server, tmp_path):
    path = os.environ[warm_start.ADDRESS].rpartition(":")[0]
    for garbage in (b"", b"\x00\x00\x00\x05{not", b"\xff" * 64):
        with socket.socket(socket.AF_UNIX) as conn:
            conn.connect(path)
            conn.sendall(garbage)
            conn.shutdown(socket.SHUT_WR)
            assert conn.recv(1) == b""        # refused: closed without a fork
    assert job(tmp_path, "print(served)\n").stdout == "True\n"


def test_a_job_stops_when_its_process_is_killed(server, tmp_path):
    script = tmp_path / "job.py"
    script.write_text(PREAMBLE.format(bench=None)
                      + "import pathlib, time\n"   # the pid file whole when it appears
                      "pathlib.Path('pid.part').write_text(str(os.getpid()))\n"
                      "os.replace('pid.part', 'pid')\ntime.sleep(60)\n")
    client = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path)
    wait_until((tmp_path / "pid").exists, 30)
    child = int((tmp_path / "pid").read_text())
    assert child != client.pid
    client.send_signal(signal.SIGKILL)
    client.wait()
    wait_until(lambda: not running(child), 10)
    assert not running(child)


def test_the_server_ends_with_the_process_that_started_it(tmp_path):
    """However that process ends (here killed), the server ends and removes its socket."""
    starter = subprocess.Popen(
        [sys.executable, "-c", "import os, sys, time\n"
         "from rotorvib.pipeline.warm_start import ADDRESS, Server\n"
         "server = Server(); server.start()\n"
         "print(server.process.pid, os.environ[ADDRESS], flush=True); time.sleep(60)"],
        stdout=subprocess.PIPE, text=True, env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    pid, address = starter.stdout.readline().split()
    starter.send_signal(signal.SIGKILL)
    starter.wait()
    folder = Path(address.rpartition(":")[0]).parent
    wait_until(lambda: not folder.exists() and not running(pid), 10)
    assert not folder.exists() and not running(pid)



def test_a_socket_path_too_long_is_said_and_every_job_runs_in_its_own_process(tmp_path,
                                                                              monkeypatch, capfd):
    """A Unix socket's path holds at most 107 bytes: under a deep TMPDIR the server says so in
    one line and ends by itself, leaving nothing behind; the jobs run in their own processes."""
    deep = tmp_path / ("d" * 60) / ("e" * 60)
    deep.mkdir(parents=True)
    monkeypatch.setenv("TMPDIR", str(deep))
    monkeypatch.setattr(tempfile, "tempdir", None)      # read TMPDIR again
    monkeypatch.setenv("PYTHONPATH", str(ROOT / "src"))
    monkeypatch.delenv(warm_start.DISABLE, raising=False)
    started = warm_start.Server()
    started.start()
    assert started.process.wait(timeout=30) == 0        # ended by itself
    assert "cannot listen on" in capfd.readouterr().err
    monkeypatch.setenv("SERVER", str(started.process.pid))
    assert job(tmp_path, "print(served)\n").stdout == "False\n"
    started.stop()
    assert list(deep.iterdir()) == []
