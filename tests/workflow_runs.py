"""The reduced workflow runs that the end-to-end tests share, and the helpers that drive them.

Two reduced runs (config/test/config.yaml), each in its own copy of the repository, are built
once per test session by :func:`shared_run`, the second with every batch study of paper B in
three shards (:data:`REDUCED_SHARDED`): the first pytest-xdist worker to need a run builds it
while any other waits on its lock, then all use it.  Most tests read the first run only, so
they start as soon as it exists; the second is built when a test first compares the two.  The
tests that read them live in several files (test_workflow.py, test_reruns.py, test_shards.py,
test_delivery.py, test_archive_runs.py, test_cluster.py) so that the workers share them; a test
never changes a run in place (it works in a copy, :func:`copy_run`), as another worker may be
reading or copying it at the same time.
"""

import fcntl
import hashlib
import json
import os
import shutil
import subprocess
import sys
from functools import partial
from pathlib import Path

from conftest import ROOT
from rotorvib.models.balancer import dop853, layout
from rotorvib.models.balancer.criteria import BalanceCriterion, StopRule
from rotorvib.models.balancer.parameters import (
    Balancer,
    SpeedProfile,
    fixed_parameters,
    fixed_state,
)
from rotorvib.models.balancer.simulate import run_batch

BIN = Path(sys.executable).parent
#: The reduced configuration, its outputs under results/ (tests/config/results_at_root.yaml).
REDUCED = ["--configfile", "config/config.yaml", "config/test/config.yaml",
           "tests/config/results_at_root.yaml"]
#: The reduced configuration with paper B's batch studies in three shards each.
REDUCED_SHARDED = [*REDUCED, "tests/config/three_shards.yaml"]
RECORDER = ROOT / "tests/oracles/job_recorder"
RECORDS = "job_records"


def copy_repository(dest: Path) -> Path:
    """The repository's files (as git lists them) and the package's caches in
    ``src/**/__pycache__`` (numba's, the sympy code generator's, the fingerprint memo), each
    valid only for its sources (rotorvib.methods.numba_cache, rotorvib.methods.codegen,
    rotorvib.pipeline.fingerprint). The library's own tests build them in the working tree; copied,
    the workflow runs here do not compile them again."""
    for cache in (ROOT / "src").rglob("__pycache__"):
        shutil.copytree(cache, dest / cache.relative_to(ROOT), dirs_exist_ok=True)
    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                            cwd=ROOT, capture_output=True, text=True)
    if listed.returncode == 0:
        for name in listed.stdout.splitlines():
            if (ROOT / name).is_file():
                (dest / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(ROOT / name, dest / name)
    else:
        shutil.copytree(ROOT, dest, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("results", ".snakemake", ".git", ".venv"))
    return dest


def environment(cwd: Path, env: dict | None = None) -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(cwd / "src"), str(RECORDER)]),
            "ROTORVIB_JOB_RECORDS": str(cwd / RECORDS), **(env or {})}


def snakemake(cwd: Path, *args, check=True, env=None, timeout=None) -> subprocess.CompletedProcess:
    """Run Snakemake in ``cwd`` with its own ``src`` first on the path (and ``env`` added); every
    script job records what it loaded into ``cwd/job_records`` (tests/oracles/job_recorder)."""
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=environment(cwd, env), timeout=timeout)
    if check and run.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{run.stdout}\n{run.stderr}")
    return run


def job_counts(run: subprocess.CompletedProcess) -> dict[str, int]:
    """Jobs per rule in the 'Job stats' table of a run (empty when nothing is to be done)."""
    lines = (run.stdout + run.stderr).splitlines()
    if "Job stats:" not in lines:
        return {}
    jobs = {}
    for line in lines[lines.index("Job stats:") + 3:]:
        name, count = line.split() if line.strip() else ("total", 0)
        if name == "total":
            break
        jobs[name] = int(count)
    return jobs


def planned_jobs(run: subprocess.CompletedProcess) -> set[str]:
    """Rule names in the 'Job stats' table of a dry run (empty when nothing is to be done)."""
    return set(job_counts(run))


def planned_outputs(cwd: Path, *args, command=None) -> set[str]:
    """Output files that Snakemake plans to (re)create, from ``--summary`` (run by ``command``,
    a :class:`forked_snakemake.ForkedSnakemake` of ``cwd``, when given)."""
    run = (command or partial(snakemake, cwd))("--summary", *REDUCED, *args)
    assert run.returncode == 0, run.stdout + run.stderr
    return to_update(run.stdout)


def summary_rows(summary: str) -> list[dict]:
    """The rows of a ``--summary`` or ``--detailed-summary`` table, by column name."""
    lines = summary.splitlines()
    header = lines[0].split("\t")
    return [dict(zip(header, line.split("\t"))) for line in lines[1:] if "\t" in line]


def to_update(summary: str) -> set[str]:
    """The output files of a ``--summary`` table whose plan is not 'no update'."""
    return {row["output_file"] for row in summary_rows(summary) if row["plan"] != "no update"}


def job_records(cwd: Path) -> list[dict]:
    """What each job of the run loaded and read and wrote (tests/oracles/job_recorder)."""
    return [json.loads(p.read_text()) for p in sorted((cwd / RECORDS).glob("*.json"))]


def run_block_jobs(cwd: Path, recorded: list[dict]) -> list[dict]:
    """The jobs the recorder cannot see (``run:`` blocks run inside Snakemake's own process),
    as job records from Snakemake's ``--detailed-summary`` of the run; they load no library
    module of their own."""
    run = snakemake(cwd, "--detailed-summary", *REDUCED)
    seen = {r["rule"] for r in recorded}
    jobs: dict[str, dict] = {}
    for row in summary_rows(run.stdout):
        if row["rule"] in seen or row["rule"] == "-":
            continue
        job = jobs.setdefault(row["rule"], {"rule": row["rule"], "output": [], "modules": [],
                                            "input": row["input-file(s)"].split(",")})
        job["output"].append(row["output_file"])
    return list(jobs.values())


def digests(root: Path) -> dict[str, str]:
    return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted((root / "results").glob("paper_*/**/*"))
            if p.suffix in {".nc", ".csv", ".md", ".png"}}


def copy_run(run_dir: Path, dest: Path) -> Path:
    """A copy of a run to change (a run is shared and read by tests in both workers)."""
    shutil.copytree(run_dir, dest, symlinks=True)
    return dest


def compile_the_engine() -> None:
    """A short stopped batch with each integrator, in this process: it compiles the engine into
    numba's cache in the working tree (under the package's compile lock) before the repository
    is copied, so that the copies carry it and the library tests beside (pytest-xdist) load it:
    one compilation instead of three side by side."""
    b = Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=0.01, eps_bar=0.012, zeta=0.01,
                              beta=1.0)
    p = fixed_parameters(b, SpeedProfile(200.0, "runup"))[None]
    y0 = fixed_state(2, r0=1e-3, theta0=0.0, phi0=[0.5, -0.5])[None]
    for method in dop853.METHODS:
        run_batch(layout.FIXED, p, y0, BalanceCriterion(1e-4, 1.0, 0.05, 1e-3), method=method,
                  stop=StopRule(margin=0.5, check_dt=0.02, neutral=1e-9),
                  progress=False)


#: The two runs, by the folder each is built in, and their configurations. Their results must
#: agree byte for byte: one comparison checks that a run is deterministic, and that sharding
#: changes no result.
RUNS = {"repo": REDUCED, "sharded": REDUCED_SHARDED}


def build_run(root: Path, name: str) -> Path:
    """The reduced run ``name`` of :data:`RUNS`, in its own copy of the repository under
    ``root``. The two runs are built one after the other, not side by side: side by side, on
    two cores, they took 245 CPU-s and 127 s where one after the other took 216 CPU-s and 119 s
    (the mean of two alternating rounds each), and the tests that read the first run alone can
    start before the second exists."""
    compile_the_engine()
    work = copy_repository(root / name)
    snakemake(work, "-j2", *RUNS[name])
    return work


def shared_run(root: Path, name: str) -> Path:
    """The run of :func:`build_run` under ``root``, a folder every worker of the session sees:
    built by the first caller, which holds a lock on ``root/<name>.lock`` meanwhile, and read
    by the others from ``root/<name>.json`` (which holds the error instead when the build
    failed)."""
    built = root / f"{name}.json"
    with open(root / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not built.exists():
            try:
                built.write_text(json.dumps(str(build_run(root, name))))
            except Exception as error:
                built.write_text(json.dumps({"error": str(error)}))
                raise
    work = json.loads(built.read_text())
    if isinstance(work, dict):
        raise AssertionError(f"the reduced run {name!r} failed in another worker:\n"
                             f"{work['error']}")
    return Path(work)
