"""The makespan of a finished run on any number of cores, from Snakemake's own job records.

Snakemake keeps, for every output file, a record of the job that made it (``.snakemake/
metadata``: its rule, inputs, start and end). This reads the records of one results folder,
joins each job's outputs, links a job to the jobs that made its inputs, and prints:

- the total job time (the sum of every job's wall time, as measured in that run);
- the critical chain: the longest path of jobs through their dependencies, which no number of
  cores can shorten, and its share of the total;
- the simulated makespan on 2, 4, 8, 16 and 64 cores (or ``--cores``): jobs started as their
  inputs are made, longest remaining chain first, with the durations measured; a batch job (a
  rule declaring ``resources: batch=1``, as Snakemake reads the rules:
  :func:`rotorvib.pipeline.slurm_profile.batch_rules`) gets half the cores, as
  the workflow gives it, and takes ``T (s + (1 - s) / threads)`` for its recorded time ``T``
  (Amdahl's law, ``s`` the serial share, ``--serial``), every other job one core.

Run from the repository root after a run of the paper configuration with ``-j2`` (every job on
one thread, as recorded)::

    python -m benchmarks.makespan [--results results] [--cores 2 4 8 16 64] [--serial 0.1]

The serial share of a batch job is measured by running it with one and with two threads
(``snakemake -j2 --forcerun b_ga --set-threads b_ga=1`` and ``=2``, then ``s = 2 T2 / T1 -
1`` from the two ``results/benchmarks/b_ga.tsv``); docs/developer.md keeps the figure. The
durations are the run's own (on the machine and with the ``-j`` it had): a job that shared its
core ran longer than it would alone, so the simulation is an upper bound where the run was
crowded. The README quotes no timing: this script measures it on the machine at hand.
"""

from __future__ import annotations

import argparse
import ast
import base64
import heapq
import json
from dataclasses import dataclass, field
from pathlib import Path

from rotorvib.pipeline.slurm_profile import batch_rules

METADATA = Path(".snakemake/metadata")


@dataclass
class Job:
    """One job of a run: its rule, the files it made and read, when it started and ended."""

    rule: str
    start: float
    end: float
    outputs: set[str] = field(default_factory=set)
    inputs: set[str] = field(default_factory=set)
    threads: int = 1

    @property
    def duration(self) -> float:
        """Its wall time; never negative (a record whose end precedes its start, which
        Snakemake writes for a job of no measurable time, counts as 0)."""
        return max(self.end - self.start, 0.0)


def _files(value) -> set[str]:
    """A record's file list (Snakemake keeps it as a list, or as the list's text)."""
    if isinstance(value, str):
        value = ast.literal_eval(value) if value.startswith("[") else [value]
    return {str(v) for v in value or ()}


def read_jobs(results: str, metadata: Path = METADATA) -> list[Job]:
    """The jobs whose outputs lie under ``results`` but not in the results folder of another
    configuration inside it (a folder holding a ``paper_b/datasets/`` of its own): the records of one job
    (same rule and end) joined into one, each job's start no earlier than the end of
    the jobs that made its inputs (Snakemake may keep an earlier start for a job rerun)."""
    jobs: dict[tuple, Job] = {}
    prefix = results.rstrip("/") + "/"
    records = {base64.urlsafe_b64decode(path.name.encode()).decode(): path
               for path in sorted(metadata.iterdir())}
    nested = {out[len(prefix):].split("/")[0] for out in records if out.startswith(prefix)
              and "/paper_b/datasets/" in out[len(prefix):]}
    for output, path in records.items():
        if not output.startswith(prefix) or output[len(prefix):].split("/")[0] in nested:
            continue
        record = json.loads(path.read_text())
        try:
            start, end = float(record["starttime"]), float(record["endtime"])
        except (KeyError, TypeError, ValueError):
            continue                               # a record without times (never ran here)
        key = (record["rule"], end)            # a job's records share its end, not its start
        job = jobs.setdefault(key, Job(record["rule"], start, end))
        job.start = min(job.start, start)
        job.outputs.add(output)
        job.inputs |= _files(record.get("input"))
    found = list(jobs.values())
    for i, before in dependencies(found).items():
        found[i].start = max([found[i].start] + [found[j].end for j in before])
    return found


def dependencies(jobs: list[Job]) -> dict[int, set[int]]:
    """For each job (by index), the jobs that made its inputs."""
    maker = {f: i for i, job in enumerate(jobs) for f in job.outputs}
    return {i: {maker[f] for f in job.inputs if f in maker and maker[f] != i}
            for i, job in enumerate(jobs)}


def users_of(needs: dict[int, set[int]]) -> dict[int, set[int]]:
    """For each job, the jobs that read what it made (the inverse of :func:`dependencies`)."""
    users: dict[int, set[int]] = {i: set() for i in needs}
    for i, before in needs.items():
        for j in before:
            users[j].add(i)
    return users


def tails(jobs: list[Job], needs: dict[int, set[int]]) -> list[float]:
    """For each job, the longest chain from its start to the end of the run (itself included),
    from the last job back (``ValueError`` for records that form a cycle)."""
    users = users_of(needs)
    waiting = {i: len(u) for i, u in users.items()}
    tail = [0.0] * len(jobs)
    done = [i for i, n in waiting.items() if n == 0]
    for i in done:                                 # grows while it is walked
        tail[i] = jobs[i].duration + max((tail[u] for u in users[i]), default=0.0)
        for j in needs[i]:
            waiting[j] -= 1
            if waiting[j] == 0:
                done.append(j)
    if len(done) != len(jobs):
        raise ValueError("the job records form a cycle")
    return tail


def critical_chain(jobs: list[Job]) -> tuple[float, list[Job]]:
    """The longest chain of jobs through their dependencies, and its length (s)."""
    needs = dependencies(jobs)
    tail, users = tails(jobs, needs), users_of(needs)
    i = max(range(len(jobs)), key=tail.__getitem__)
    chain = [jobs[i]]
    while users[i]:
        i = max(users[i], key=tail.__getitem__)
        chain.append(jobs[i])
    return max(tail, default=0.0), chain


def on_cores(jobs: list[Job], cores: int, batch: set[str], serial: float) -> list[Job]:
    """The jobs as the workflow runs them on ``cores`` cores: a batch job on
    ``max(1, cores // 2)`` threads, its time by Amdahl's law with serial share ``serial``
    (module docstring); ``Job.threads`` says how many cores each takes."""
    threads = max(1, cores // 2)
    scaled = []
    for job in jobs:
        t = threads if job.rule in batch else 1
        factor = serial + (1 - serial) / t
        scaled.append(Job(job.rule, job.start, job.start + job.duration * factor,
                          job.outputs, job.inputs, t))
    return scaled


def simulated_makespan(jobs: list[Job], cores: int) -> float:
    """List scheduling on ``cores`` cores: a job starts when its inputs are made and its
    ``threads`` cores are free, the ready jobs by longest remaining chain first (one that does
    not fit lets a smaller one start); each takes its cores for its duration."""
    needs = dependencies(jobs)
    tail, users = tails(jobs, needs), users_of(needs)
    waiting = {i: len(before) for i, before in needs.items()}
    ready = [(-tail[i], i) for i, n in waiting.items() if n == 0]
    running: list[tuple[float, int]] = []
    now, free = 0.0, cores
    while ready or running:
        ready.sort()
        for entry in list(ready):
            need = min(jobs[entry[1]].threads, cores)
            if need <= free:
                ready.remove(entry)
                free -= need
                heapq.heappush(running, (now + jobs[entry[1]].duration, entry[1]))
        now, i = heapq.heappop(running)
        free += min(jobs[i].threads, cores)
        for j in users[i]:
            waiting[j] -= 1
            if waiting[j] == 0:
                ready.append((-tail[j], j))
    return now


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="results", help="the run's results folder")
    parser.add_argument("--cores", type=int, nargs="+", default=[2, 4, 8, 16, 64])
    parser.add_argument("--serial", type=float, default=0.1,
                        help="serial share of a batch job (module docstring: how to measure)")
    args = parser.parse_args(argv)
    jobs = read_jobs(args.results)
    if not jobs:
        raise SystemExit(f"no job records under {args.results}/: run the workflow first")
    total = sum(job.duration for job in jobs)
    batch = set(batch_rules(Path.cwd()))
    length, chain = critical_chain(jobs)
    print(f"{len(jobs)} jobs under {args.results}/, total job time {total:.1f} s")
    print(f"critical chain, every job on one thread: {length:.1f} s = {length / total:.2f} of "
          "the total:")
    for job in chain:
        print(f"  {job.rule:<28} {job.duration:7.1f} s")
    print(f"batch jobs on half the cores (serial share {args.serial:g}): "
          + ", ".join(sorted({j.rule for j in jobs if j.rule in batch})))
    base = simulated_makespan(on_cores(jobs, args.cores[0], batch, args.serial), args.cores[0])
    print("cores  simulated makespan  of the first  critical chain  of the total")
    for cores in args.cores:
        scaled = on_cores(jobs, cores, batch, args.serial)
        span, (chain_length, _) = simulated_makespan(scaled, cores), critical_chain(scaled)
        print(f"{cores:5d}  {span:16.1f} s  {span / base:12.2f}  {chain_length:12.1f} s  "
              f"{chain_length / total:12.2f}")

if __name__ == "__main__":
    main()
