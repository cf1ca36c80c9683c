"""Many Snakemake commands in one directory for the start-up of one.

A ``snakemake`` command spends about two thirds of a dry run importing Snakemake and collecting
its plugins (the SLURM executor's imports pandas), the same work every time. Run as a script in
the workflow's directory, this module does that work once, then serves commands read from its
standard input, one JSON list of arguments a line: each runs in a child forked from the prepared
process, through Snakemake's own command-line entry point (``snakemake.cli.main``), and its exit
code, standard output and standard error come back as one JSON line. A child starts from the
state of a fresh ``snakemake`` process whose imports are done: nothing of the workflow (the
Snakefile, the ``rotorvib`` modules it imports, their caches in memory) is loaded before the
fork, so an edited file is read as a fresh command would read it. The libraries a command
imports from outside the workflow's directory (jsonschema, Snakemake's lazy imports) the server
imports after it, for the children that follow.

:class:`ForkedSnakemake` starts and drives such a server from a test.
"""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path


def _serve() -> None:
    import snakemake.cli

    snakemake.cli.get_argument_parser()  # collects the plugins, kept by their registries
    workflow = Path.cwd().resolve()
    for line in sys.stdin:
        with (tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err,
              tempfile.TemporaryFile("w+") as loaded):
            pid = os.fork()
            if pid == 0:
                os.dup2(out.fileno(), 1)
                os.dup2(err.fileno(), 2)
                before, code = set(sys.modules), 1
                try:
                    snakemake.cli.main(json.loads(line))
                except SystemExit as exit:
                    code = exit.code or 0
                finally:
                    sys.stdout.flush()
                    sys.stderr.flush()
                    loaded.write("\n".join(_libraries(set(sys.modules) - before, workflow)))
                    loaded.flush()
                    os._exit(code)
            code = os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])
            out.seek(0)
            err.seek(0)
            print(json.dumps({"returncode": code, "stdout": out.read(), "stderr": err.read()}),
                  flush=True)
            loaded.seek(0)
            for name in loaded.read().split():
                importlib.import_module(name)


def _libraries(names, workflow: Path) -> list[str]:
    """The modules among ``names`` loaded from files outside the ``workflow`` directory: the
    libraries a command imported (jsonschema for the configuration, Snakemake's own lazy
    imports), which the server then imports for the next children; the workflow's code
    (its ``src``, rules and scripts) stays unloaded."""
    return sorted(name for name in names
                  if (path := getattr(sys.modules.get(name), "__file__", None))
                  and not Path(path).resolve().is_relative_to(workflow))


class ForkedSnakemake:
    """A server of Snakemake commands in ``cwd`` (environment ``env``); call it with a
    command's arguments for a :class:`subprocess.CompletedProcess`."""

    def __init__(self, cwd: Path, env: dict[str, str]):
        self.process = subprocess.Popen([sys.executable, __file__], cwd=cwd, env=env,
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def __call__(self, *args: str) -> subprocess.CompletedProcess:
        self.process.stdin.write(json.dumps(list(args)) + "\n")
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        if not line:
            raise RuntimeError("the Snakemake server stopped; its error is printed above")
        reply = json.loads(line)
        return subprocess.CompletedProcess(["snakemake", *args], reply["returncode"],
                                           reply["stdout"], reply["stderr"])

    def __enter__(self) -> ForkedSnakemake:
        return self

    def __exit__(self, *exc) -> None:
        self.process.stdin.close()
        self.process.wait(timeout=60)


if __name__ == "__main__":
    sys.path[0] = str(Path(sys.executable).parent)  # as for the ``snakemake`` script there
    _serve()
