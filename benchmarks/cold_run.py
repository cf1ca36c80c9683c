"""The run a new user makes: a fresh clone, nothing compiled, ``snakemake -j2``, timed.

Clones the repository's committed state (HEAD) into a scratch folder, runs the paper
configuration there with ``--cores`` cores (its own ``src`` first on the path, so that every
compiled cache is built from scratch), and prints the wall time and the CPU time of the whole
process tree (the operating system's accounting of the finished children). With ``--record
FILE`` it also writes them, with the commit, the date and the machine, as JSON: the README's
expected run time is generated from ``benchmarks/records/cold_run.json``
(``python -m rotorvib.pipeline.readme``), never typed. Run from the repository root::

    python -m benchmarks.cold_run [--cores 2] [--record benchmarks/records/cold_run.json]

With ``--against REV`` it compares HEAD with another revision side by side, each from its own
fresh clone: ``--rounds`` rounds (2 unless given), the order alternating from one round to the
next (HEAD first, then REV first, ...) so that a machine that slows down or speeds up during
the comparison weighs on both alike, then the ratio of HEAD's CPU and wall time to REV's, in
each round and over all of them (a ratio of sums)::

    python -m benchmarks.cold_run --against 6ede2d7 --rounds 2

A run's CPU is also given job by job: a ``sitecustomize`` hook put on the run's path (for the
measurement only, :data:`JOB_HOOK`) records the CPU of every job process as it exits, and the
figures it draws, so that the comparison gives the ratio of the CPU of the jobs both revisions
have: those of the rules both have (a study's shards and gathering counted as its rule), and
the figure jobs, counted together as "figures" (revisions group figures into jobs
differently), that draw only figures both revisions draw. A figure job that draws a figure of
a study only one revision has is that study's cost, left out like its rule. A revision whose
jobs are forked from a server (6ede2d7's warm start) records none: set
``ROTORVIB_NO_WARM_START=1`` to run its jobs as fresh processes; the counts of jobs recorded
are printed.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

from benchmarks import children_cpu


def cpu_model() -> str:
    """The processor's model name (Linux), else what the platform says."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


#: The ``sitecustomize`` of a measured run: every process that runs a Snakemake script job
#: writes, as it exits, its rule, its CPU seconds (its threads and children included) and the
#: figures it draws (``paper_<p>/<name>`` of each PNG it writes) to a file in the folder
#: ``$ROTORVIB_JOB_CPU``.
JOB_HOOK = """import atexit, json, os, sys


def _job_cpu():
    job = getattr(sys.modules.get("__main__"), "snakemake", None)
    if job is not None:
        t = os.times()
        cpu = t.user + t.system + t.children_user + t.children_system
        figures = sorted(os.path.basename(os.path.dirname(os.path.dirname(str(path)))) + "/"
                         + os.path.basename(str(path))[:-4]
                         for path in getattr(job, "output", []) if str(path).endswith(".png"))
        with open(os.path.join(os.environ["ROTORVIB_JOB_CPU"], f"{os.getpid()}.json"), "w") as f:
            json.dump({"rule": job.rule, "cpu": cpu, "figures": figures}, f)


atexit.register(_job_cpu)
"""

#: The group of every figure job that draws only figures both revisions draw.
FIGURES = "figures"


def rule_group(rule: str) -> str:
    """The rule a job's CPU is counted under across revisions: a study's shard under the study's
    rule."""
    return rule.removesuffix("_shard")


def is_figure_job(job: dict) -> bool:
    """Whether a job's record (:data:`JOB_HOOK`) is a figure job's: a rule ``figures_*`` that
    drew figures."""
    return job["rule"].startswith("figures_") and bool(job.get("figures"))


def commit_of(repository: Path, revision: str) -> str:
    """The commit ``revision`` names in ``repository`` now."""
    return subprocess.run(["git", "rev-parse", "--verify", f"{revision}^{{commit}}"],
                          cwd=repository, check=True, capture_output=True,
                          text=True).stdout.strip()


def cold_run(repository: Path, cores: int, revision: str = "HEAD") -> dict:
    """Clone ``repository`` at ``revision`` into a scratch folder, run ``snakemake -j<cores>``
    there and return the record: commit, date, cores, machine, wall and CPU seconds, the CPU
    seconds of its jobs by :func:`rule_group` (``jobs_cpu_s``), those of its figure jobs with
    the figures each drew (``figure_jobs``), and how many jobs recorded theirs (``jobs``)."""
    commit = commit_of(repository, revision)
    with tempfile.TemporaryDirectory(prefix="rotorvib-cold-") as scratch:
        clone = Path(scratch) / "clone"
        subprocess.run(["git", "clone", "--quiet", "--no-checkout", str(repository), str(clone)],
                       check=True)
        subprocess.run(["git", "checkout", "--quiet", commit], cwd=clone, check=True)
        hook, records = Path(scratch) / "hook", Path(scratch) / "jobs"
        hook.mkdir()
        records.mkdir()
        (hook / "sitecustomize.py").write_text(JOB_HOOK)
        env = {**os.environ, "ROTORVIB_JOB_CPU": str(records), "PYTHONPATH": os.pathsep.join(
            filter(None, [str(clone / "src"), str(hook), os.environ.get("PYTHONPATH")]))}
        cpu, start = children_cpu(), time.perf_counter()
        with open(Path(scratch) / "snakemake.log", "w+") as log:
            done = subprocess.run([str(Path(sys.executable).parent / "snakemake"),
                                   f"-j{cores}", "--quiet", "rules"], cwd=clone, env=env,
                                  stdout=log, stderr=subprocess.STDOUT)
            wall, cpu = time.perf_counter() - start, children_cpu() - cpu
            if done.returncode:
                log.seek(0)
                raise RuntimeError(f"the cold run at {commit[:7]} failed:\n{log.read()[-3000:]}")
        jobs = [json.loads(p.read_text()) for p in sorted(records.glob("*.json"))]
    by_rule: dict[str, float] = {}
    for job in jobs:
        if not is_figure_job(job):
            group = rule_group(job["rule"])
            by_rule[group] = by_rule.get(group, 0.0) + job["cpu"]
    return {"commit": commit, "date": datetime.now(timezone.utc).date().isoformat(),
            "cores": cores, "machine": {"cpus": os.cpu_count(), "cpu": cpu_model(),
                                        "python": platform.python_version()},
            "wall_s": round(wall, 1), "cpu_s": round(cpu, 1), "jobs": len(jobs),
            "jobs_cpu_s": {rule: round(v, 2) for rule, v in sorted(by_rule.items())},
            "figure_jobs": [{"figures": job["figures"], "cpu_s": round(job["cpu"], 2)}
                            for job in jobs if is_figure_job(job)]}


def side_by_side(run, revisions: tuple[str, str], rounds: int) -> list[dict]:
    """``rounds`` rounds of ``run(revision) -> record`` for both ``revisions``, the order
    alternating from one round to the next; each record gains its ``round`` and ``revision``."""
    records = []
    for i in range(rounds):
        for revision in revisions if i % 2 == 0 else revisions[::-1]:
            records.append({**run(revision), "round": i + 1, "revision": revision})
    return records


def ratios(records: list[dict], key: str) -> tuple[list[float], float]:
    """The ratio of ``key`` (``cpu_s`` or ``wall_s``) of the first revision to the second's in
    each round of :func:`side_by_side`'s ``records``, and over all rounds (sum over sum)."""
    first, second = records[0]["revision"], records[1]["revision"]
    rounds = sorted({r["round"] for r in records})
    value = {(r["round"], r["revision"]): r[key] for r in records}
    per_round = [value[i, first] / value[i, second] for i in rounds]
    total = sum(value[i, first] for i in rounds) / sum(value[i, second] for i in rounds)
    return per_round, total


def job_seconds(record: dict) -> float:
    """The CPU seconds all the jobs of a run recorded, its figure jobs included."""
    return (sum(record["jobs_cpu_s"].values())
            + sum(job["cpu_s"] for job in record.get("figure_jobs", [])))


def shared_figures(records: list[dict]) -> set[str]:
    """The figures every run of ``records`` drew."""
    return set.intersection(*({name for job in r.get("figure_jobs", []) for name in job["figures"]}
                              for r in records))


def drew_only(job: dict, shared: set[str]) -> bool:
    """Whether a figure job (a record's ``figure_jobs``) drew only ``shared`` figures."""
    return set(job["figures"]) <= shared


def figures_cpu(record: dict, shared: set[str]) -> float:
    """The CPU seconds of a run's figure jobs that drew only ``shared`` figures."""
    return sum(job["cpu_s"] for job in record.get("figure_jobs", []) if drew_only(job, shared))


def rules_cpu(records: list[dict], revision: str, rules) -> dict[str, float]:
    """The CPU seconds of each of ``rules`` in ``revision``'s runs of ``records``, summed over
    the rounds; :data:`FIGURES`: its figure jobs that drew only figures every run drew."""
    shared = shared_figures(records)
    mine = [r for r in records if r["revision"] == revision]
    return {rule: sum(figures_cpu(r, shared) if rule == FIGURES else r["jobs_cpu_s"][rule]
                      for r in mine) for rule in rules}


def common_jobs_ratio(records: list[dict]) -> tuple[float, list[str]]:
    """The ratio of the CPU of the first revision's jobs to the second's over the rules both
    recorded in every round (:func:`rule_group`) and :data:`FIGURES` (sums over the rounds), and
    those rules."""
    first, second = records[0]["revision"], records[1]["revision"]
    common = sorted(set.intersection(*(set(r["jobs_cpu_s"]) for r in records)))
    if shared_figures(records):
        common = sorted([*common, FIGURES])
    total = {rev: sum(rules_cpu(records, rev, common).values()) for rev in (first, second)}
    return total[first] / total[second], common


def figures_left_out(records: list[dict], revision: str) -> tuple[list[str], float]:
    """The figures ``revision`` drew that not every run drew, and the CPU seconds of its figure
    jobs that drew any of them (summed over its rounds)."""
    shared = shared_figures(records)
    mine = [r for r in records if r["revision"] == revision]
    jobs = [job for r in mine for job in r.get("figure_jobs", []) if not drew_only(job, shared)]
    return (sorted({name for job in jobs for name in job["figures"]} - shared),
            sum(job["cpu_s"] for job in jobs))


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--record", type=Path, help="write the record (JSON) here")
    parser.add_argument("--against", metavar="REV",
                        help="compare HEAD with this revision, side by side")
    parser.add_argument("--rounds", type=int, default=2,
                        help="rounds of the comparison (with --against)")
    args = parser.parse_args(argv)
    if args.against:
        if args.rounds < 1:
            parser.error(f"--rounds: at least 1, not {args.rounds}")
        # both revisions pinned to their commits now: a commit made while it runs (an hour for
        # a few rounds) changes neither side
        pinned = {rev: commit_of(Path.cwd(), rev) for rev in ("HEAD", args.against)}
        records = side_by_side(lambda rev: cold_run(Path.cwd(), args.cores, pinned[rev]),
                               ("HEAD", args.against), args.rounds)
        for r in records:
            print(f"round {r['round']}, {r['revision']} ({r['commit'][:7]}): {r['wall_s']} s "
                  f"wall, {r['cpu_s']} s CPU; {r['jobs']} jobs recorded their CPU, "
                  f"{job_seconds(r):.1f} s")
        for key, name in (("cpu_s", "CPU"), ("wall_s", "wall")):
            per_round, total = ratios(records, key)
            print(f"HEAD / {args.against}, {name}: {total:.3f} (rounds: "
                  f"{', '.join(f'{x:.3f}' for x in per_round)})")
        if all(r["jobs"] for r in records):
            ratio, common = common_jobs_ratio(records)
            print(f"HEAD / {args.against}, CPU of the jobs of the {len(common)} rules both "
                  f"have: {ratio:.3f}")
            head, other = (rules_cpu(records, rev, common) for rev in ("HEAD", args.against))
            for rule in common:
                print(f"  {rule:28s} {head[rule]:8.1f} {other[rule]:8.1f}")
            for rev in ("HEAD", args.against):
                names, cpu = figures_left_out(records, rev)
                if names:
                    print(f"left out, {rev}'s figure jobs drawing figures the other does not "
                          f"draw ({', '.join(names)}): {cpu:.1f} s")
        return
    record = cold_run(Path.cwd(), args.cores)
    print(f"cold snakemake -j{args.cores} at {record['commit'][:7]}: {record['wall_s']} s wall, "
          f"{record['cpu_s']} s CPU ({record['machine']['cpus']} CPUs, "
          f"{record['machine']['cpu']})")
    if args.record:
        args.record.parent.mkdir(parents=True, exist_ok=True)
        args.record.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
