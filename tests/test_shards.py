"""Sharded batch studies (rotorvib.pipeline.shards): a study split over jobs gives the dataset
of one job byte for byte, and the pieces are checked before they are gathered."""

from collections import Counter

import numpy as np
import pytest
import xarray as xr

from rotorvib.methods.ga import minimise_many
from rotorvib.models.balancer.layout import N_METRICS
from rotorvib.papers.b.setup import LazyInputs, Setup
from rotorvib.papers.b.studies import balance_study_dataset, basin_dataset
from rotorvib.papers.b.uncertainty import INPUTS, run_case
from rotorvib.pipeline.shards import (
    GatheredRuns,
    ShardRuns,
    gathered_searches,
    searches_dataset,
    shard_dataset,
    shard_rows,
)
from workflow_runs import REDUCED_SHARDED, copy_run, job_counts, job_records, snakemake

#: Every sharded study of paper B (the rules whose script calls run_balancer_study or run_search).
SHARDED = ["balance_beta", "balance_mass", "balance_eps_bar", "table1", "forces", "basin", "ga",
           "uncertainty_table2", "uncertainty_fig7", "uncertainty_table1"]


def fake_runs(inputs):
    """A deterministic runner: each run's metrics depend on its input alone."""
    return np.array([[x, x**2, np.sin(x)] for x in inputs])


def study(runs):
    """A study of two batches of different sizes, as the basin map has."""
    return runs(list(np.linspace(0.0, 1.0, 11))), runs(list(np.arange(3.0)))


@pytest.mark.parametrize("shards", [1, 2, 4, 13])
def test_gathered_shards_are_the_whole_study(shards):
    whole = study(fake_runs)
    pieces = []
    for k in range(shards):
        runner = ShardRuns(fake_runs, k, shards, width=3)
        study(runner)
        pieces.append(shard_dataset(runner, "a test study"))
    gathered = study(GatheredRuns(pieces))
    for a, b in zip(whole, gathered):
        assert np.array_equal(a, b)
    assert sum(p.sizes["run"] for p in pieces) == 14          # each run computed once


def test_shards_that_do_not_cover_the_study_are_refused():
    pieces = []
    for k in range(3):
        runner = ShardRuns(fake_runs, k, 3, width=3)
        study(runner)
        pieces.append(shard_dataset(runner, "a test study"))
    with pytest.raises(ValueError, match="exactly once"):
        study(GatheredRuns(pieces[:2]))                        # a shard missing
    with pytest.raises(ValueError, match="exactly once"):
        study(GatheredRuns([*pieces, pieces[0]]))              # one twice
    with pytest.raises(ValueError, match="hold 11 runs, the study asks for 12"):
        GatheredRuns(pieces)(list(range(12)))
    other = ShardRuns(fake_runs, 0, 1, width=3)
    other([1.0, 2.0])
    with pytest.raises(ValueError, match="different studies"):
        GatheredRuns([pieces[0], shard_dataset(other, "another study")])
    with pytest.raises(ValueError, match=r"shard = 3: must be an integer >= 0 and <= 2"):
        shard_rows(10, 3, 3)


def test_lazy_inputs_build_a_run_when_it_is_asked_for():
    built = []
    inputs = LazyInputs(5, lambda i: built.append(i) or (i, -i))
    assert len(inputs) == 5 and built == []
    assert inputs[3] == (3, -3) and inputs[-1] == (4, -4) and inputs[np.int64(0)] == (0, 0)
    assert inputs[1:4:2] == [(1, -1), (3, -3)] and list(inputs)[2] == (2, -2)
    assert built == [3, 4, 0, 1, 3, 0, 1, 2, 3, 4]
    for bad in (5, -6):
        with pytest.raises(IndexError, match=f"run {bad} of 5"):
            inputs[bad]


def grid_studies(setup: Setup, runs):
    """Paper B's kinds of batch study, small: a balance study, the basin map (half of it run)
    and an uncertainty case (its runs over ICs)."""
    ics = {"IC1": [0.0, 90.0], "IC2": [45.0, 180.0]}
    rows = np.zeros((4, len(INPUTS)))                 # no tolerances; R and r(0) given
    rows[:, INPUTS.index("R")], rows[:, INPUTS.index("r0")] = np.linspace(0.009, 0.011, 4), 1e-4
    return [balance_study_dataset(setup, kinematics=["printed", "consistent"], ics=ics,
                                  axis="beta", values=[0.2, 0.5, 1.0], fixed={"mass": 0.01,
                                  "eps_bar": 0.012}, where="a test", runs=runs).balance_time,
            basin_dataset(setup, kinematics=["printed"], cases=[[1.0, 0.01]], n=4,
                          eps_bar=0.012, ics=ics, runs=runs).balance_time,
            run_case(setup, rows, {"beta": 1.0, "mass": 0.01, "eps_bar": 0.012, "speed": None,
                                   "ics": list(ics.values())}, kinematics="printed",
                     runs=runs)["force_max"]]


def test_a_shard_builds_its_own_runs_inputs_and_the_gathering_none(config, monkeypatch):
    """Each job of a sharded study sets up only the runs it computes (the inputs cost a job its
    share, not the whole study): a shard its own, the gathering none; the gathered studies are
    the whole ones."""
    setup = Setup.from_paper_b(config["paper_b"])
    built = []
    run_inputs = Setup.run_inputs
    monkeypatch.setattr(Setup, "run_inputs",
                        lambda self, **kw: built.append(1) or run_inputs(self, **kw))

    def runs(inputs):               # metrics that depend on each run's inputs alone
        return np.array([[p.sum(), *y, *p][:N_METRICS] for p, y in inputs])

    whole = grid_studies(setup, runs)
    n_runs = len(built)
    assert n_runs == 2 * 2 * 3 + (4 * 5 // 2 + 2) + 4 * 2
    pieces = []
    for k in range(3):
        built.clear()
        runner = ShardRuns(runs, k, 3, width=N_METRICS)
        grid_studies(setup, runner)
        assert len(built) == sum(rows.size for _, rows, _ in runner.calls)
        pieces.append(shard_dataset(runner, "a test study"))
    built.clear()
    gathered = grid_studies(setup, GatheredRuns(pieces))
    assert built == [] and sum(p.sizes["run"] for p in pieces) == n_runs
    for a, b in zip(whole, gathered):
        assert np.array_equal(a, b, equal_nan=True)


SEEDS = [1, 2, 3, 4, 5]


def searches(runs, seeds=SEEDS):
    """Independent GA searches (one per seed) of (m_0 - 0.3)^2 + x_1^2 over [-1, 1]^2, m_0 the
    first metric of a run whose input is the design's first coordinate; every generation of
    all of them one call of ``runs``."""
    def objectives(xs, worst):
        metrics = runs([float(v) for x in xs for v in x[:, 0]])
        f = (metrics[:, 0] - 0.3) ** 2 + np.concatenate([x[:, 1] for x in xs]) ** 2
        return np.split(f, np.cumsum([len(x) for x in xs])[:-1])

    return minimise_many(objectives, len(seeds), [-1.0, -1.0], [1.0, 1.0], pop_size=6,
                         n_gen=4, seed=seeds)


def shard_of_searches(k, shards):
    """Shard ``k`` of ``shards`` of the searches of :func:`searches`, as its job writes it (and
    reads it back)."""
    mine = shard_rows(len(SEEDS), k, shards).tolist()
    results = searches(fake_runs, [SEEDS[i] for i in mine]) if mine else []
    return searches_dataset(results, mine, "a test search", k, shards)


@pytest.mark.parametrize("shards", [1, 2, 3, 7])
def test_searches_gathered_from_their_shards_are_the_whole_study(shards, tmp_path):
    """Each shard runs its searches whole and writes their results; gathered (from the files)
    they are the optima and histories of one job, every array equal bit for bit (a shard with
    no search, 7 > 5, writes none)."""
    whole = searches(fake_runs)
    pieces = []
    for k in range(shards):
        path = tmp_path / f"{k}.nc"
        shard_of_searches(k, shards).to_netcdf(path)
        pieces.append(xr.load_dataset(path))
    gathered = gathered_searches(pieces, len(SEEDS))
    assert len(gathered) == len(whole)
    for a, b in zip(whole, gathered):
        assert np.array_equal(a.x, b.x) and a.f == b.f and a.history.keys() == b.history.keys()
        for name in a.history:
            assert np.array_equal(a.history[name], b.history[name])
            assert b.history[name].dtype == np.asarray(a.history[name]).dtype


def test_shards_that_do_not_hold_each_search_once_are_refused():
    pieces = [shard_of_searches(k, 2) for k in range(2)]
    for wrong in (pieces[:1], [*pieces, pieces[1]]):          # a shard missing, one twice
        with pytest.raises(ValueError, match="each of the study's 5 searches exactly once"):
            gathered_searches(wrong, len(SEEDS))
    with pytest.raises(ValueError, match="exactly once"):
        gathered_searches(pieces, 6)                          # another study's shards


def test_the_sharded_run_made_each_study_in_shards(runs, tmp_path):
    """The reduced run with every study in three shards (tests/workflow_runs.py; its results
    equal the unsharded run's byte for byte, test_workflow.py): each study three shard jobs and
    one gathering job; a dry run afterwards has nothing to do, and a changed study reruns its
    own three shards and gathering job only."""
    counts = Counter(record["rule"] for record in job_records(runs[1]))
    assert counts["b_balance_study_shard"] == 9 and counts["b_balance_study"] == 3
    assert counts["b_basin_shard"] == counts["b_table1_runs_shard"] == counts["b_ga_shard"] == 3
    assert counts["b_uncertainty_shard"] == 9 and counts["b_uncertainty"] == 3
    assert counts["b_forces_shard"] == 3
    work = copy_run(runs[1], tmp_path / "work")
    targets = [f"results/paper_b/datasets/{name}.nc" for name in SHARDED]
    assert job_counts(snakemake(work, "-n", *REDUCED_SHARDED, "--", *targets)) == {}
    (work / "denser.yaml").write_text(
        "paper_b:\n  balance_studies:\n    mass:\n      range: {min: 0.006, max: 0.02, n: 4}\n")
    again = job_counts(snakemake(work, "-n", *REDUCED_SHARDED, "denser.yaml", "--", *targets))
    assert again == {"b_balance_study_shard": 3, "b_balance_study": 1}
