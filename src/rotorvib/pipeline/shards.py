"""Sharded batch studies: one study's runs split over several jobs, gathered byte for byte.

A batch study calls a *runner* ``runs(inputs) -> metrics`` (one row of metrics per run, e.g.
:meth:`rotorvib.papers.b.setup.Setup.runs`) once or a few times while it builds its dataset.
Every run is independent and deterministic, so the rows do not depend on which job computes
them:

- a shard job ``k`` of ``n`` builds the study with :class:`ShardRuns`, which computes the runs
  ``k, k + n, k + 2n, ...`` of every call (interleaved, so that cheap and dear runs mix) and
  fills the others with zeros; it writes only its rows (:func:`shard_dataset`), as a checked
  dataset with its own provenance;
- the gathering job builds the study again with :class:`GatheredRuns`, which answers every call
  from the shards' rows, having checked that they cover each call's runs exactly once.

A study hands its runner the inputs as a sequence whose items are built when read
(:class:`rotorvib.papers.b.setup.LazyInputs`): a shard sets up only its own runs and the
gathering none.

The gathered dataset is byte-identical to the one a single job computes
(``tests/test_shards.py``); the number of shards is not part of its provenance.

A study made of independent *searches* (a genetic algorithm per problem and seed) cannot be
split that way: each generation's runs depend on the last one's metrics.  Its shard job ``k``
runs the searches ``k, k + n, ...`` whole and records every run they make (:class:`RecordedRuns`);
the gathering job runs all the searches again, every run answered from the records
(:class:`ReplayedRuns`), which the searches, deterministic and independent of each other, ask
for in the same order (:func:`run_search`).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import xarray as xr

from rotorvib.checks import integer

Runner = Callable[[list], np.ndarray]


def shard_rows(n_runs: int, shard: int, shards: int) -> np.ndarray:
    """The runs of shard ``shard`` of ``shards``: ``shard, shard + shards, ...``; each argument
    an integer, ``n_runs >= 0``, ``shards >= 1`` and ``0 <= shard < shards`` (``ValueError``
    naming the argument otherwise)."""
    n_runs, shards = integer("n_runs", n_runs, 0), integer("shards", shards, 1)
    shard = integer("shard", shard, 0, shards - 1)
    return np.arange(shard, n_runs, shards)


class ShardRuns:
    """A runner that computes one shard of every call (``width`` metrics per run) and records
    its rows."""

    def __init__(self, runs: Runner, shard: int, shards: int, width: int):
        shard_rows(0, shard, shards)              # checks the pair
        self.runs, self.shard, self.shards, self.width = runs, shard, shards, width
        self.calls: list[tuple[int, np.ndarray, np.ndarray]] = []   # (n_runs, rows, metrics)

    def __call__(self, inputs: list) -> np.ndarray:
        rows = shard_rows(len(inputs), self.shard, self.shards)
        mine = (self.runs([inputs[i] for i in rows]) if rows.size
                else np.zeros((0, self.width)))
        self.calls.append((len(inputs), rows, mine))
        out = np.zeros((len(inputs), self.width))
        out[rows] = mine
        return out


def shard_dataset(runner: ShardRuns, study: str) -> xr.Dataset:
    """The rows a :class:`ShardRuns` computed, one ``run`` dimension over all its calls."""
    one = {"units": "1"}
    calls = runner.calls
    return xr.Dataset(
        {"metrics": (("run", "metric"), np.concatenate([m for _, _, m in calls]),
                     {"long_name": "metrics of the shard's runs (rows of the engine's metric "
                                   "table)", **one}),
         "row": ("run", np.concatenate([r for _, r, _ in calls]).astype(np.int64),
                 {"long_name": "index of the run in its call", **one}),
         "call": ("run", np.concatenate([np.full(r.size, j, dtype=np.int32)
                                         for j, (_, r, _) in enumerate(calls)]),
                  {"long_name": "which of the study's batches the run belongs to", **one}),
         "n_runs": ("batch", np.array([n for n, _, _ in calls], dtype=np.int64),
                    {"long_name": "runs of each of the study's batches", **one})},
        attrs={"title": f"shard {runner.shard} of {runner.shards} of {study}",
               "summary": f"The runs {runner.shard}, {runner.shard} + {runner.shards}, ... of "
                          f"every batch of {study}, gathered by its rule",
               "references": f"{study}; rotorvib.pipeline.shards"})


class GatheredRuns:
    """A runner that answers each call of a study from its shards' datasets."""

    def __init__(self, shards: list[xr.Dataset]):
        self.shards = shards
        self.call = 0
        counts = {tuple(ds.n_runs.values) for ds in shards}
        if len(counts) != 1:
            raise ValueError(f"the shards come from different studies (batch sizes {counts})")

    def __call__(self, inputs: list) -> np.ndarray:
        j, self.call = self.call, self.call + 1
        n_runs = int(self.shards[0].n_runs.values[j])
        if n_runs != len(inputs):
            raise ValueError(f"batch {j}: the shards hold {n_runs} runs, the study asks for "
                             f"{len(inputs)}")
        parts = [(ds.row.values[ds.call.values == j], ds.metrics.values[ds.call.values == j])
                 for ds in self.shards]
        rows = np.concatenate([r for r, _ in parts])
        if not np.array_equal(np.sort(rows), np.arange(n_runs)):
            raise ValueError(f"batch {j}: the shards do not hold each of its {n_runs} runs "
                             "exactly once")
        out = np.empty((n_runs, parts[0][1].shape[1]))
        for r, m in parts:
            out[r] = m
        return out


def _study_job(snakemake, runs: Runner, build: Callable[[Runner], xr.Dataset],
               shard_job: Callable[[int, int], xr.Dataset],
               gathered: Callable[[list[xr.Dataset]], Runner], seed: int | None) -> None:
    """The job of a sharded study's script, whichever of its three kinds it is: a shard (the
    wildcards ``shard`` and ``shards``) writes ``shard_job(shard, shards)``; the gathering
    (named input ``shards``) builds the dataset with the runner ``gathered(shard datasets)``;
    the whole study builds it with ``runs``.  ``seed`` goes into the provenance."""
    from rotorvib.io.datasets import Provenance, read_dataset, write_dataset
    from rotorvib.pipeline.job import job_config

    provenance = Provenance(snakemake.rule, job_config(snakemake.params), seed)
    wildcards = dict(snakemake.wildcards.items())
    if "shard" in wildcards:
        write_dataset(shard_job(int(wildcards["shard"]), int(wildcards["shards"])),
                      snakemake.output[0], provenance)
        return
    paths = list(getattr(snakemake.input, "shards", []))
    if paths:
        producers = snakemake.params.input_producers
        runs = gathered([read_dataset(path, producers) for path in paths])
    write_dataset(build(runs), snakemake.output[0], provenance)


def run_study(snakemake, runs: Runner, build: Callable[[Runner], xr.Dataset], *, width: int,
              study: str, seed: int | None = None) -> None:
    """The job of a batch study's script (:func:`_study_job`): a shard computes its rows of
    every batch (:class:`ShardRuns`), the gathering answers every batch from them
    (:class:`GatheredRuns`).  ``build(runner)`` builds the study's dataset from a runner;
    ``seed`` goes into the provenance."""
    def shard_job(shard, shards):
        runner = ShardRuns(runs, shard, shards, width)
        build(runner)
        return shard_dataset(runner, study)

    _study_job(snakemake, runs, build, shard_job, GatheredRuns, seed)


def run_keys(inputs: list) -> list[bytes]:
    """Each run's identity: the bytes of its inputs (a parameter row and an initial state, or a
    number), as float64."""
    return [b"".join(np.ascontiguousarray(part, dtype=float).tobytes()
                     for part in (item if isinstance(item, tuple) else (item,)))
            for item in inputs]


class RecordedRuns:
    """A runner that computes every call with ``runs`` and records each run's inputs (their
    :func:`run_keys`) and metrics: one shard of a search."""

    def __init__(self, runs: Runner):
        self.runs = runs
        self.keys: list[bytes] = []
        self.metrics: list[np.ndarray] = []

    def __call__(self, inputs: list) -> np.ndarray:
        metrics = self.runs(inputs)
        self.keys += run_keys(inputs)
        self.metrics.append(metrics)
        return metrics


def record_dataset(runner: RecordedRuns, study: str, shard: int, shards: int,
                   width: int) -> xr.Dataset:
    """The runs a :class:`RecordedRuns` computed (``width`` metrics each): their keys as bytes
    and their metrics."""
    keys = (np.stack([np.frombuffer(k, dtype=np.uint8) for k in runner.keys]) if runner.keys
            else np.zeros((0, 0), dtype=np.uint8))
    metrics = np.concatenate(runner.metrics) if runner.metrics else np.zeros((0, width))
    return xr.Dataset(
        {"metrics": (("run", "metric"), metrics,
                     {"long_name": "metrics of the shard's runs (rows of the engine's metric "
                                   "table)", "units": "1"}),
         "key": (("run", "byte"), keys,
                 {"long_name": "the run's inputs as the bytes of float64 values",
                  "units": "1"})},
        attrs={"title": f"shard {shard} of {shards} of {study}",
               "summary": f"Every run of the searches {shard}, {shard} + {shards}, ... of "
                          f"{study}, replayed by its rule",
               "references": f"{study}; rotorvib.pipeline.shards"})


class ReplayedRuns:
    """A runner that answers each run of a search from its shards' records
    (:func:`record_dataset`); a run no shard computed is an error, never computed here."""

    def __init__(self, shards: list[xr.Dataset]):
        self.table: dict[bytes, np.ndarray] = {}
        for ds in shards:
            for key, row in zip(ds.key.values, ds.metrics.values):
                known = self.table.setdefault(key.tobytes(), row)
                if not np.array_equal(known, row, equal_nan=True):
                    raise ValueError("two shards disagree on the metrics of one run")

    def __call__(self, inputs: list) -> np.ndarray:
        try:
            return np.array([self.table[k] for k in run_keys(inputs)])
        except KeyError:
            raise ValueError("a run of the search is in no shard's records: the shards come "
                             "from another search") from None


def run_search(snakemake, runs: Runner, build: Callable[[Runner], xr.Dataset],
               part: Callable[[Runner, int, int], None], *, width: int, study: str,
               seed: int | None = None) -> None:
    """The job of a study made of independent searches (a GA per problem and seed)
    (:func:`_study_job`): a shard runs searches k, k + n, ... whole (``part(runner, k, n)``)
    and writes every run they made (:class:`RecordedRuns`); the gathering replays all the
    searches (``build``) from those records (:class:`ReplayedRuns`).  A search's next runs
    depend on the last, so a shard cannot compute a share of each batch (:func:`run_study`);
    the searches are independent and deterministic, so the replay is the whole study byte for
    byte."""
    def shard_job(shard, shards):
        shard_rows(0, shard, shards)                      # checks the pair
        runner = RecordedRuns(runs)
        part(runner, shard, shards)
        return record_dataset(runner, study, shard, shards, width)

    _study_job(snakemake, runs, build, shard_job, ReplayedRuns, seed)
