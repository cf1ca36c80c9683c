"""How many run-ups a configuration asks for, and what they will cost, before they run.

``python -m rotorvib.pipeline.estimate [--cores N] [CONFIG ...]`` (the files as for
``--configfile``, merged in order over ``config/config.yaml``) answers in three steps:

1. **Count.** The workflow itself builds paper B's datasets (rule ``b_datasets``; not the
   discrepancy analysis's, which needs the stated values measured on real runs and does not
   grow with the studies) in a scratch folder
   (``results/estimate/...``), with every batch of runs of the balancer model's batch API
   (:func:`rotorvib.models.balancer.simulate.run_batch`) of more than ``COMPUTED`` run-ups
   answered by a counter instead of the engine: all-zero metrics (every run censored), the
   number of run-ups recorded with a random sample of them (:func:`count_runs`, installed in
   every job process by a ``sitecustomize`` hook on the counting pass's path, before anything
   imports the model; nothing in the workflow or its jobs' code knows of it).
   Smaller batches (Table 2's calibration, say) run for real, so that what depends on them
   builds. The counts are those of the workflow's own code: nothing here mirrors it.
2. **Time.** Each job's sample of run-ups is integrated for real on one thread: the CPU
   seconds of one run-up of that study, on this machine.
3. **Report.** Per job (named by the dataset it writes): run-ups, CPU per run-up, their
   product; the CPU the counting pass spent on everything else (its jobs' logs:
   stability maps, boundaries, the few single runs, the batches it ran);
   the total in CPU-hours, and the wall time on ``--cores`` cores if the work shared them
   perfectly.

Papers A and C have no run-ups; the configurations that enlarge paper B's studies
(``config/large``) leave them as they are, at the cost the paper configuration measures.
"""

from __future__ import annotations

import argparse
import atexit
import os
import pickle
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotorvib.pipeline.job_logs import jobs_cpu

COUNT_ENV = "ROTORVIB_COUNT_RUNS"
MARKER = "counting-pass"
#: batches of at most this many run-ups run for real in the counting pass
COMPUTED = 1000
#: run-ups of each job integrated for real to time it
SAMPLE = 64


class RunCounter:
    """Stands in for :func:`~rotorvib.models.balancer.simulate.run_batch` in a counting pass:
    counts every run-up of the job, keeps a uniform random sample of ``sample`` of them
    (reservoir sampling) with the batch's form, criterion and options, computes batches of at
    most ``computed`` run-ups with ``real`` and answers larger ones with all-zero metrics. A
    sampled run is timed to its end: its batch's ``balance_bounds`` (the GA's) are not kept,
    and the zero metrics give the GA no finite bound anyway."""

    def __init__(self, real, sample: int = SAMPLE, computed: int = COMPUTED, seed: int = 0):
        self.real, self.sample, self.computed = real, sample, computed
        self.rng = np.random.default_rng(seed)
        self.runs, self.counted, self.batches = 0, 0, 0
        self.kept: list[tuple[tuple, np.ndarray, np.ndarray]] = []

    def __call__(self, form, params, y0s, criterion, **options) -> np.ndarray:
        from rotorvib.models.balancer.layout import N_METRICS

        batch = (form, criterion, tuple(sorted(
            (k, v) for k, v in options.items() if k not in ("progress", "balance_bounds"))))
        for row, y0 in zip(params, y0s):
            self.runs += 1
            if len(self.kept) < self.sample:
                self.kept.append((batch, row, y0))
            elif (j := self.rng.integers(self.runs)) < self.sample:
                self.kept[j] = (batch, row, y0)
        self.batches += 1
        if len(params) <= self.computed:
            return self.real(form, params, y0s, criterion, **options)
        self.counted += len(params)
        return np.zeros((len(params), N_METRICS))

    def write(self, path: Path) -> None:
        with open(path, "wb") as f:
            pickle.dump({"runs": self.runs, "counted": self.counted, "batches": self.batches,
                         "sample": self.kept}, f)


def count_runs(folder: Path) -> None:
    """Install a :class:`RunCounter` as the balancer model's batch API for this process (a job
    of a counting pass: the ``sitecustomize`` hook :func:`counting_pass` puts on the path runs
    this at start-up, before any module binds the name); when the process ends, its counts go
    to ``folder/counts/<dataset>.<pid>.pkl``, the dataset being the job's first output.
    Refused unless ``folder`` is a counting pass's scratch folder: zero metrics must never
    reach real results."""
    if not (folder / MARKER).is_file():
        raise RuntimeError(f"{COUNT_ENV}={folder} is not a counting pass's folder (no "
                           f"{MARKER} file): refusing to answer runs with zeros")
    from rotorvib.models.balancer import simulate

    counter = RunCounter(simulate.run_batch)
    simulate.run_batch = counter

    def write():
        job = getattr(sys.modules.get("__main__"), "snakemake", None)
        if counter.runs and job is not None:
            (folder / "counts").mkdir(exist_ok=True)
            counter.write(folder / "counts" / f"{Path(job.output[0]).name.split('.')[0]}."
                                              f"{os.getpid()}.pkl")

    atexit.register(write)


#: the counting pass's ``sitecustomize``: every Python process of its jobs counts its runs
HOOK = ("import os\nfrom pathlib import Path\n"
        "from rotorvib.pipeline.estimate import COUNT_ENV, count_runs\n"
        "count_runs(Path(os.environ[COUNT_ENV]))\n")


@dataclass(frozen=True)
class JobCost:
    """One job's run-ups, those the counter answered (the others ran in the counting pass and
    are in its measured CPU) and the CPU seconds of one by its timed sample; ``dataset``
    names the job by the dataset it writes."""

    dataset: str
    runs: int
    counted: int
    cpu_per_run: float

    @property
    def cpu(self) -> float:
        """CPU seconds of the counted run-ups."""
        return self.counted * self.cpu_per_run


def time_sample(sample: list) -> float:
    """CPU seconds per run-up of a job's sample (one thread; the engine's compiled code loaded
    before the clock starts)."""
    from rotorvib.models.balancer.simulate import run_batch, use_threads

    use_threads(1)
    cpu = 0.0
    by_batch: dict[int, list] = {}
    for batch, params, y0 in sample:
        by_batch.setdefault(id(batch), []).append((batch, params, y0))
    for group in by_batch.values():
        (form, criterion, options) = group[0][0]
        params, y0s = np.stack([p for _, p, _ in group]), np.stack([y for _, _, y in group])
        args = dict(options, progress=False)
        run_batch(form, params[:1], y0s[:1], criterion, **args)          # load, not timed
        start = time.process_time()
        run_batch(form, params, y0s, criterion, **args)
        cpu += time.process_time() - start
    return cpu / len(sample)


def job_costs(folder: Path) -> list[JobCost]:
    """The run-ups of every job of a counting pass (by the dataset it writes) and their CPU by
    its timed sample."""
    costs = []
    for path in sorted((folder / "counts").glob("*.pkl")):
        with open(path, "rb") as f:
            counts = pickle.load(f)
        costs.append(JobCost(path.name.split(".")[0], counts["runs"], counts["counted"],
                             time_sample(counts["sample"])))
    return costs


def pass_cpu(folder: Path) -> float:
    """CPU seconds the jobs of a counting pass spent, as each job's log states
    (:mod:`rotorvib.pipeline.job_logs`)."""
    return jobs_cpu(sorted((folder / "logs").glob("*.log")))


def counting_pass(root: Path, configfiles: list[str], cores: int, results: str,
                  datasets: list[str] | None = None) -> Path:
    """Build the paper B datasets of the workflow in ``root`` (or those named ``datasets``)
    into ``results`` (relative to it), every job with a run counter; return that scratch
    folder."""
    folder = root / results
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    (folder / MARKER).write_text("paper B's runs answered by a counter: not results\n")
    # shards change no count: each study in one job (fewer jobs to start)
    (folder / "one_shard.yaml").write_text("paper_b:\n  shards: 1\n  ga_shards: 1\n")
    # every dataset of paper B but the discrepancy analysis's (it needs the stated values
    # measured on real runs)
    command = [sys.executable, "-m", "snakemake", f"--cores={cores}", "--nolock", "--quiet",
               "--configfile", "config/config.yaml", *configfiles,
               f"{results}/one_shard.yaml", "--config",
               f"results={results}", "--omit-from", "b_reproduced_values", "--",
               *([f"{results}/paper_b/datasets/{name}.nc" for name in datasets] if datasets
                 else ["b_datasets"])]
    hook = folder / "hook"
    hook.mkdir()
    (hook / "sitecustomize.py").write_text(HOOK)
    path = os.pathsep.join(filter(None, [str(hook), os.environ.get("PYTHONPATH")]))
    done = subprocess.run(command, cwd=root, capture_output=True, text=True,
                          env={**os.environ, COUNT_ENV: str(folder), "PYTHONPATH": path})
    if done.returncode:
        raise RuntimeError("the counting pass failed:\n" + done.stdout[-3000:]
                           + done.stderr[-3000:])
    return folder


def report(costs: list[JobCost], rest: float, cores: int) -> str:
    """The estimate as text: a line per job, the totals. A job whose batches all ran for real
    in the counting pass (none counted) shows no CPU of its own: it is in the rest, which the
    pass measured, not 0."""
    width = max([len(c.dataset) for c in costs] + [7])
    lines = [f"{'dataset':<{width}}  {'run-ups':>10}  {'counted':>10}  {'CPU-s/run-up':>12}  "
             f"{'CPU-s':>11}"]
    lines += [f"{c.dataset:<{width}}  {c.runs:>10d}  {c.counted:>10d}  {c.cpu_per_run:>12.2e}  "
              + (f"{c.cpu:>11.3g}" if c.counted else f"{'in the rest':>11}") for c in costs]
    runs, cpu = sum(c.runs for c in costs), sum(c.cpu for c in costs)
    total = cpu + rest
    lines += [f"run-ups: {runs}; the counted ones {cpu:.1f} CPU-s; the rest of paper B "
              f"(measured in the counting pass, the uncounted run-ups included): "
              f"{rest:.1f} CPU-s",
              f"estimate: {total:.0f} CPU-s = {total / 3600:.2f} CPU-hours, about "
              f"{total / cores / 60:.1f} min on {cores} cores if the work shares them "
              "perfectly"]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    """The command line: count, time and report (module docstring); the scratch folder is
    removed unless ``--keep``."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("configfiles", nargs="*", help="merged over config/config.yaml")
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder")
    args = parser.parse_args(argv)
    results = f"results/estimate/pass{os.getpid()}"
    print(f"counting paper B's run-ups: its jobs run on {args.cores} cores with every batch of "
          f"more than {COMPUTED} run-ups counted, not integrated (what this pass costs is the "
          f"'rest' below), then {SAMPLE} run-ups of each job are timed", flush=True)
    try:
        folder = counting_pass(Path.cwd(), args.configfiles, args.cores, results)
        print(report(job_costs(folder), pass_cpu(folder), args.cores))
    finally:
        if not args.keep:
            shutil.rmtree(Path.cwd() / results, ignore_errors=True)


if __name__ == "__main__":
    main()
