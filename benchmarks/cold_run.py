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
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path


def cpu_model() -> str:
    """The processor's model name (Linux), else what the platform says."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def children_cpu() -> float:
    """User + system seconds of every child process waited for so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def cold_run(repository: Path, cores: int, revision: str = "HEAD") -> dict:
    """Clone ``repository`` at ``revision`` into a scratch folder, run ``snakemake -j<cores>``
    there and return the record: commit, date, cores, machine, wall and CPU seconds."""
    commit = subprocess.run(["git", "rev-parse", "--verify", f"{revision}^{{commit}}"],
                            cwd=repository, check=True, capture_output=True,
                            text=True).stdout.strip()
    with tempfile.TemporaryDirectory(prefix="rotorvib-cold-") as scratch:
        clone = Path(scratch) / "clone"
        subprocess.run(["git", "clone", "--quiet", "--no-checkout", str(repository), str(clone)],
                       check=True)
        subprocess.run(["git", "checkout", "--quiet", commit], cwd=clone, check=True)
        env = {**os.environ, "PYTHONPATH": os.pathsep.join(
            filter(None, [str(clone / "src"), os.environ.get("PYTHONPATH")]))}
        cpu, start = children_cpu(), time.perf_counter()
        subprocess.run([str(Path(sys.executable).parent / "snakemake"), f"-j{cores}",
                        "--quiet", "rules"], cwd=clone, env=env, check=True,
                       stdout=subprocess.DEVNULL)
        wall, cpu = time.perf_counter() - start, children_cpu() - cpu
    return {"commit": commit, "date": datetime.now(timezone.utc).date().isoformat(),
            "cores": cores, "machine": {"cpus": os.cpu_count(), "cpu": cpu_model(),
                                        "python": platform.python_version()},
            "wall_s": round(wall, 1), "cpu_s": round(cpu, 1)}


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
        records = side_by_side(lambda rev: cold_run(Path.cwd(), args.cores, rev),
                               ("HEAD", args.against), args.rounds)
        for r in records:
            print(f"round {r['round']}, {r['revision']} ({r['commit'][:7]}): {r['wall_s']} s "
                  f"wall, {r['cpu_s']} s CPU")
        for key, name in (("cpu_s", "CPU"), ("wall_s", "wall")):
            per_round, total = ratios(records, key)
            print(f"HEAD / {args.against}, {name}: {total:.3f} (rounds: "
                  f"{', '.join(f'{x:.3f}' for x in per_round)})")
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
