"""The cost estimate: its run counter, its refusal outside a counting pass, and its counts
against the runs the reduced workflow really made."""

import numpy as np
import pytest
import xarray as xr

from rotorvib.models.balancer.layout import N_METRICS
from rotorvib.pipeline import estimate
from workflow_runs import copy_run


def _batch(start, n):
    return np.arange(start, start + n, dtype=float)[:, None] * np.ones(3), np.zeros((n, 2))


def test_the_counter_counts_samples_and_runs_only_small_batches():
    """Every run-up counted; batches of at most ``computed`` go to the real batch API, larger
    ones get all-zero metrics; the sample is drawn from every batch, not the first only, and
    keeps each run's batch options (but the progress switch) to time it with."""
    real = []

    def run_batch(form, params, y0s, criterion, **options):
        real.append((len(params), options))
        return np.ones((len(params), N_METRICS))

    counter = estimate.RunCounter(run_batch, sample=50, computed=10, seed=1)
    small = counter(0, *_batch(0, 10), "criterion", rtol=1e-6, progress=True)
    large = counter(0, *_batch(10, 5000), "criterion", rtol=1e-6, progress=False)
    assert real == [(10, {"rtol": 1e-6, "progress": True})] and np.all(small == 1)
    assert large.shape == (5000, N_METRICS) and not large.any()
    assert (counter.runs, counter.counted, counter.batches) == (5010, 5000, 2)
    labels = sorted(int(p[0]) for _, p, _ in counter.kept)
    assert len(labels) == 50 and labels[-1] > 2500 and len(set(labels)) == 50
    assert {batch for batch, _, _ in counter.kept} == {(0, "criterion", (("rtol", 1e-6),))}


def test_counting_is_refused_outside_a_counting_pass(tmp_path):
    with pytest.raises(RuntimeError, match="not a counting pass's folder"):
        estimate.count_runs(tmp_path)


def test_the_counts_are_the_runs_the_workflow_makes(run_dir, tmp_path):
    """A counting pass of the reduced configuration, in a copy of its run: each grid study's
    count equals the runs in its dataset (the basin's: the half of its map on and above the
    diagonal, identical balls, and the ICs' own runs); every job's
    sampled run-ups time to a positive cost, and the report adds them up."""
    work = copy_run(run_dir, tmp_path / "repo")
    checked = ["balance_beta", "balance_mass", "table1", "basin", "ga", "uncertainty_table2",
               "pareto_printed"]
    folder = estimate.counting_pass(work, ["config/test/config.yaml"], 2, "results/estimate/t",
                                    checked)
    costs = {c.dataset: c for c in estimate.job_costs(folder)}
    data = work / "results/paper_b/datasets"

    def size(name, *variables):
        ds = xr.open_dataset(data / f"{name}.nc")
        return sum(ds[v].size for v in variables)

    assert costs["balance_beta"].runs == size("balance_beta", "balance_time")
    assert costs["balance_mass"].runs == size("balance_mass", "balance_time")
    assert costs["table1"].runs == size("table1", "balance_time")
    basin = xr.open_dataset(data / "basin.nc")                  # half the symmetric map
    n = basin.sizes["phi1"]
    assert costs["basin"].runs == (basin.balance_time.size // n**2 * n * (n + 1) // 2
                                     + basin.ic_balance_time.size)
    assert set(checked) <= set(costs)
    assert all(c.cpu_per_run > 0 and c.runs >= c.counted for c in costs.values())
    text = estimate.report(list(costs.values()), estimate.pass_cpu(folder), 2)
    assert f"run-ups: {sum(c.runs for c in costs.values())};" in text
    for cost in costs.values():    # real work never reads as 0.0: uncounted jobs ran for real
        line = next(row for row in text.splitlines() if row.startswith(cost.dataset + " "))
        if cost.counted:
            assert float(line.split()[-1]) > 0, line
        else:
            assert line.endswith("in the rest"), line
