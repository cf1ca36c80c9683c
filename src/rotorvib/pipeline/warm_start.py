"""Warm start of the workflow's script jobs: one process that holds the libraries the jobs
import, and forks a copy of itself to run each job.

A script job is a fresh Python process, and most of a figure's or a table's job is its imports
(xarray, pandas, netCDF4, matplotlib: about half a CPU-second, more than drawing most figures).
While Snakemake runs jobs, :class:`Server` (started by the Snakefile's ``onstart``) listens on a
Unix socket; the job's own process (the *client*, started by Snakemake as ever) hands over its
standard streams, working directory, environment, arguments and script to it
(:func:`hand_over`, called as ``rotorvib.pipeline.job`` is imported, the first line of every
script), and the server forks a child that runs the script as that process would have, then
hands the child's exit status back; the client exits with it.

What the server holds is learnt, not listed: when a job comes, the server first imports the
installed libraries the children that have ended loaded (modules in Python's installation or
environment), so that this job and those that follow find them loaded (a command of one job
imports nothing twice).  Nothing of the workflow's own code (``rotorvib``, the
scripts) is ever loaded in the server: each child imports it afresh, as a new process would,
and an edited module is read as it now is.

Served are only the jobs that Snakemake does not benchmark: a ``benchmark:`` measures the
job's process and its children, and a forked child is the server's.  A job is run by its own
process, as without a server, when no server serves its Snakemake run (a dry run, a SLURM job,
the variable :data:`DISABLE` set), when the server is gone, could not listen (a socket's path
holds at most 107 bytes, which a deep TMPDIR exceeds; it says so) or refuses (it forks only
while it runs one Python thread), or when the job is benchmarked.  A child dies with its
client: Snakemake stopping a job (Ctrl-C, a failed job elsewhere) stops the child too.
"""

from __future__ import annotations

import gc
import importlib
import json
import os
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import types
from pathlib import Path

#: The variable that tells a job where the server of its Snakemake run listens:
#: ``<socket path>:<pid of that Snakemake process>``.
ADDRESS = "ROTORVIB_WARM_START"
#: Set (to anything) to run every job in its own process: no server is started.
DISABLE = "ROTORVIB_NO_WARM_START"
#: Set in a child: its script imports rotorvib.pipeline.job again, which must not hand over.
_SERVED = "ROTORVIB_WARM_STARTED"
_STATUS = struct.Struct("!i")
_LENGTH = struct.Struct("!I")
_PACKAGE = "rotorvib"
_FORKED = b"F"


# --- the client: a job's own process -----------------------------------------------------------

def hand_over() -> None:
    """Have this job run by the server of its Snakemake run and exit with the status of that
    run; return at once (the job then runs here) when no server serves it. The job is the
    script Snakemake runs as ``__main__``: its ``snakemake`` object (whose ``bench_iteration``
    is None unless the rule has a ``benchmark:``; tests/test_workflow.py checks that reading
    against the rule files on the pinned Snakemake) and its ``__real_file__``, the script file
    Snakemake wrote."""
    main = sys.modules["__main__"]
    job = getattr(main, "snakemake", None)
    if job is None or getattr(job, "bench_iteration", None) is not None or _SERVED in os.environ:
        return
    path, _, owner = os.environ.get(ADDRESS, "").rpartition(":")
    if not path or not owner.isdigit() or not _descends_from(int(owner)):
        return
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        conn.connect(path)
    except OSError:
        conn.close()
        return
    request = {"file": main.__real_file__, "argv": sys.argv, "cwd": os.getcwd(),
               "env": dict(os.environ), "path": sys.path, "umask": _umask()}
    message = json.dumps(request).encode()
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        socket.send_fds(conn, [_LENGTH.pack(len(message)) + message], [0, 1, 2])
        forked = conn.recv(1)
    except OSError:
        forked = b""
    if forked != _FORKED:
        conn.close()
        return            # refused before anything ran: the job runs here
    status = _receive_status(conn)
    if status is None:
        os.write(2, b"rotorvib.pipeline.warm_start: the server ended before the job did\n")
        os._exit(1)
    os._exit(status if status >= 0 else 128 - status)


def _descends_from(pid: int) -> bool:
    """Whether this process is a descendant of process ``pid`` (read from /proc): a job of
    that Snakemake run, not one it sent elsewhere with the variable in its environment."""
    current = os.getpid()
    while current > 1:
        try:
            stat = Path(f"/proc/{current}/stat").read_text()
        except OSError:
            return False
        current = int(stat.rpartition(")")[2].split()[1])
        if current == pid:
            return True
    return False


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _receive_status(conn: socket.socket) -> int | None:
    data = _receive(conn, _STATUS.size)
    return None if data is None else _STATUS.unpack(data)[0]


def _receive(conn: socket.socket, size: int, data: bytes = b"") -> bytes | None:
    """``size`` bytes from ``conn`` (``data`` of them already read), or None at its end."""
    while len(data) < size:
        chunk = conn.recv(size - len(data))
        if not chunk:
            return None
        data += chunk
    return data


# --- the server ----------------------------------------------------------------------------

class Server:
    """A server of the jobs of this Snakemake process: :meth:`start` it before the jobs run
    (sets :data:`ADDRESS` in this process's environment, which the jobs inherit), :meth:`stop`
    it after.  It also ends when this process does, however it ends (its standard input is a
    pipe from here)."""

    def __init__(self):
        self.process: subprocess.Popen | None = None

    def start(self) -> None:
        if DISABLE in os.environ or self.process is not None:
            return
        path = os.path.join(tempfile.mkdtemp(prefix="rotorvib-warm-"), "socket")  # mode 700
        self.process = subprocess.Popen(
            [sys.executable, "-m", __name__, path],
            stdin=subprocess.PIPE, start_new_session=True)
        os.environ[ADDRESS] = f"{path}:{os.getpid()}"

    def stop(self) -> None:
        if self.process is None:
            return
        os.environ.pop(ADDRESS, None)
        self.process.stdin.close()
        self.process.wait()
        self.process = None


def serve(path: str) -> None:
    """Serve jobs on the Unix socket ``path`` until standard input ends."""
    gc.disable()      # imports and forks only: nothing here is garbage worth a collection
    server = os.getpid()
    wake_read, wake_write = os.pipe()
    os.set_blocking(wake_write, False)
    signal.set_wakeup_fd(wake_write)
    signal.signal(signal.SIGCHLD, lambda *_: None)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        listener.bind(path)
    except OSError as error:    # a socket path is at most 107 bytes: a long TMPDIR
        print(f"rotorvib.pipeline.warm_start: cannot listen on {path} ({error}); every job "
              "runs in its own process", file=sys.stderr)
        listener.close()
        shutil.rmtree(Path(path).parent, ignore_errors=True)
        return
    listener.listen(16)
    clients: dict[int, tuple[socket.socket, str]] = {}
    learnt: list[str] = []      # what the ended children loaded, imported for the next job
    try:
        while True:
            ready = select.select([listener, sys.stdin, wake_read], [], [])[0]
            if sys.stdin in ready:
                break
            if wake_read in ready:
                os.read(wake_read, 512)
                for conn, modules in _reaped(clients):
                    conn.close()
                    learnt.append(modules)
            if listener in ready:
                conn = listener.accept()[0]
                while learnt:
                    _learn(learnt.pop())
                pid = _fork_job(conn, listener, path)
                if pid is not None:
                    clients[pid] = (conn, _learnt_file(path, pid))
                else:
                    conn.close()
    finally:
        if os.getpid() == server:      # a child leaves through here too (sys.exit)
            listener.close()
            for name in Path(path).parent.iterdir():
                name.unlink()
            Path(path).parent.rmdir()


def _reaped(clients: dict) -> list[tuple[socket.socket, str]]:
    """The ended children's clients, each told its child's exit status."""
    done = []
    while clients:
        try:
            pid, status = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            break
        if pid == 0:
            break
        conn, learnt = clients.pop(pid)
        try:
            conn.sendall(_STATUS.pack(os.waitstatus_to_exitcode(status)))
        except OSError:
            pass          # the client is gone (stopped by Snakemake)
        done.append((conn, learnt))
    return done


def _learnt_file(path: str, pid: int) -> str:
    return f"{path}.{pid}.modules"


def _learn(learnt: str) -> None:
    """Import the libraries a child loaded (listed in the file ``learnt``), for the next
    children."""
    try:
        names = Path(learnt).read_text().split()
        os.unlink(learnt)
    except OSError:
        return
    for name in names:
        if name not in sys.modules:
            try:
                importlib.import_module(name)
            except Exception:   # noqa: BLE001 - a library that will not load here is not held
                continue


def _is_library(name: str, module) -> bool:
    """Whether module ``name`` is an installed library's (its file lies in this Python's
    installation or environment), not the workflow's (``rotorvib``, wherever it lies)."""
    file = getattr(module, "__file__", None)
    if file is None or name.partition(".")[0] == _PACKAGE:
        return False
    return any(Path(file).resolve().is_relative_to(Path(prefix).resolve())
               for prefix in {sys.prefix, sys.base_prefix})


def _fork_job(conn: socket.socket, listener: socket.socket, path: str) -> int | None:
    """Fork a child that runs the job ``conn`` asks for; its pid, or None when the job is
    refused (a malformed request, or a Python thread besides this one: a fork copies only the
    one; the native threads of a library's pool, OpenBLAS's, are stopped and started again
    around a fork by the library itself)."""
    fds: list[int] = []
    try:
        first, fds, _, _ = socket.recv_fds(conn, 1 << 16, 3)
        length = _LENGTH.unpack(first[:_LENGTH.size])[0]
        request = json.loads(_receive(conn, _LENGTH.size + length, first)[_LENGTH.size:])
    except (OSError, ValueError, TypeError, struct.error):
        request = None
    if request is None or len(fds) != 3 or threading.active_count() != 1:
        for fd in fds:
            os.close(fd)
        return None
    sys.stdout.flush()
    sys.stderr.flush()
    gc.freeze()       # no collection in a child scans (and so copies) the server's objects
    pid = os.fork()
    if pid == 0:
        listener.close()
        _run_job(conn, request, fds, _learnt_file(path, os.getpid()))
    for fd in fds:
        os.close(fd)
    conn.sendall(_FORKED)
    return pid


def _run_job(conn: socket.socket, request: dict, fds: list[int], learnt: str) -> None:
    """In the child: become the client's process (streams, folder, environment, arguments,
    module path, umask), run its script as ``__main__`` and exit as Python exits."""
    signal.set_wakeup_fd(-1)
    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
    for target, fd in enumerate(fds):
        os.dup2(fd, target)
        os.close(fd)
    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"], **{_SERVED: "1"})
    os.umask(request["umask"])
    sys.argv[:] = request["argv"]
    sys.path[:] = request["path"]
    threading.Thread(target=_die_with, args=(conn,), daemon=True).start()
    for name in [name for name in sys.modules if name.partition(".")[0] == _PACKAGE]:
        del sys.modules[name]     # the server's own package (``-m``), imported afresh
    before = set(sys.modules)
    main = types.ModuleType("__main__")
    main.__file__ = request["file"]
    sys.modules["__main__"] = main
    gc.enable()
    code = 0
    try:
        source = Path(request["file"]).read_bytes()
        exec(compile(source, request["file"], "exec"), main.__dict__)
    except SystemExit as stop:
        code = stop.code
    except BaseException as error:  # noqa: BLE001 - said as Python says an uncaught one
        error.with_traceback(error.__traceback__.tb_next)      # from the script's frame on
        sys.excepthook(type(error), error, error.__traceback__)
        code = 1
    finally:
        libraries = [name for name in set(sys.modules) - before
                     if _is_library(name, sys.modules[name])]
        Path(learnt).write_text("\n".join(sorted(libraries)))
    sys.exit(code)


def _die_with(conn: socket.socket) -> None:
    """End this child when its client ends (it never sends: a read returns at its end)."""
    try:
        conn.recv(1)
    finally:
        os.kill(os.getpid(), signal.SIGKILL)


if __name__ == "__main__":
    serve(sys.argv[1])
