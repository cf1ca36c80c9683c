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
runs the searches ``k, k + n, ...`` whole and writes their results (:func:`searches_dataset`);
the gathering job puts the results of all the searches back in their order
(:func:`gathered_searches`) and builds the study from them, as one job builds it from the
results of all its searches, which are independent and deterministic (:func:`run_search`).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import xarray as xr

from rotorvib.checks import integer
from rotorvib.methods.optima import GAResult
from rotorvib.models.balancer.layout import N_METRICS
from rotorvib.models.balancer.simulate import use_threads

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


def _study_job(snakemake, whole: Callable[[], xr.Dataset],
               shard_job: Callable[[int, int], xr.Dataset],
               gather: Callable[[list[xr.Dataset]], xr.Dataset], seed: int | None) -> None:
    """The job of a sharded study's script, whichever of its three kinds it is: a shard (the
    wildcards ``shard`` and ``shards``) writes ``shard_job(shard, shards)``; the gathering
    (named input ``shards``) writes ``gather(shard datasets)``; the whole study ``whole()``.
    ``seed`` goes into the provenance."""
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
        study = gather([read_dataset(path, producers) for path in paths])
    else:
        study = whole()
    write_dataset(study, snakemake.output[0], provenance)


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

    _study_job(snakemake, lambda: build(runs), shard_job,
               lambda pieces: build(GatheredRuns(pieces)), seed)



def run_balancer_study(snakemake, setup, build: Callable[[Runner], xr.Dataset], *, study: str,
                       seed: int | None = None) -> None:
    """:func:`run_study` of a study of the balancer's runs: ``setup.runs`` (e.g.
    :meth:`rotorvib.papers.b.setup.Setup.runs`), each a row of the balancer's metrics, the
    batches shared out to the job's threads."""
    use_threads(snakemake.threads)
    run_study(snakemake, setup.runs, build, width=N_METRICS, study=study, seed=seed)


def searches_dataset(results: list[GAResult], searches, study: str, shard: int,
                     shards: int) -> xr.Dataset:
    """The ``results`` of the searches numbered ``searches`` (their indices in the study): each
    optimum ``x`` and ``f`` and every array of its history (``history_<name>``, one row per
    generation)."""
    one = {"units": "1"}
    data = {"search": ("search", np.asarray(searches, dtype=np.int64),
                       {"long_name": "index of the search in the study", **one})}
    if results:
        data["x"] = (("search", "variable"), np.array([r.x for r in results]),
                     {"long_name": "optimum of the search", **one})
        data["f"] = ("search", np.array([r.f for r in results], dtype=float),
                     {"long_name": "objective at the optimum", **one})
        for name in results[0].history:
            values = np.array([r.history[name] for r in results])
            dims = ("search", "generation", "variable")[:values.ndim]
            data[f"history_{name}"] = (dims, values, {"long_name": f"{name} of each generation",
                                                      **one})
    return xr.Dataset(
        data, attrs={"title": f"shard {shard} of {shards} of {study}",
                     "summary": f"The results of the searches {shard}, {shard} + {shards}, ... "
                                f"of {study}, gathered by its rule",
                     "references": f"{study}; rotorvib.pipeline.shards"})


def gathered_searches(shards: list[xr.Dataset], n_searches: int) -> list[GAResult]:
    """The results of the ``n_searches`` searches of a study, in their order, from its shards'
    :func:`searches_dataset`; ``ValueError`` unless they hold each search exactly once."""
    found = np.concatenate([ds.search.values for ds in shards])
    if not np.array_equal(np.sort(found), np.arange(n_searches)):
        raise ValueError(f"the shards do not hold each of the study's {n_searches} searches "
                         f"exactly once (they hold {sorted(found.tolist())})")
    results: list[GAResult | None] = [None] * n_searches
    for ds in shards:
        names = [name for name in ds.data_vars if name.startswith("history_")]
        for j, index in enumerate(ds.search.values):
            results[index] = GAResult(
                x=ds.x.values[j], f=float(ds.f.values[j]),
                history={name.removeprefix("history_"): ds[name].values[j] for name in names})
    return results


def run_search(snakemake, n_searches: int, solve: Callable[[list[int]], list[GAResult]],
               build: Callable[[list[GAResult]], xr.Dataset], *, study: str,
               seed: int | None = None) -> None:
    """The job of a study made of ``n_searches`` independent searches (a GA per problem and
    seed) (:func:`_study_job`): ``solve(indices)`` runs the searches of those indices and
    returns their results, ``build(results)`` builds the study from the results of all of them
    in order.  A shard runs the searches k, k + n, ... whole and writes their results
    (:func:`searches_dataset`); the gathering builds the study from all the shards' results
    (:func:`gathered_searches`).  A search's next runs depend on the last, so a shard cannot
    compute a share of each batch (:func:`run_study`); the searches are independent and
    deterministic, so the gathered study is the whole one byte for byte."""
    def shard_job(shard, shards):
        mine = shard_rows(n_searches, shard, shards).tolist()
        return searches_dataset(solve(mine) if mine else [], mine, study, shard, shards)

    _study_job(snakemake, lambda: build(solve(list(range(n_searches)))), shard_job,
               lambda pieces: build(gathered_searches(pieces, n_searches)), seed)
