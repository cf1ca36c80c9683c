"""The side-by-side comparison of two revisions' cold runs (benchmarks/cold_run.py --against):
its alternating order cancels a machine that drifts during the comparison, and its ratios are
those of the sums."""

import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT))                 # the benchmarks are modules of the repository
from benchmarks.cold_run import main, ratios, side_by_side  # noqa: E402


def drifting_machine(cost: dict[str, float], drift: float):
    """A runner whose every run takes ``drift`` seconds longer than the one before it."""
    calls = []

    def run(revision):
        calls.append(revision)
        seconds = cost[revision] + drift * (len(calls) - 1)
        return {"commit": revision * 7, "cpu_s": seconds, "wall_s": seconds / 2}

    return run, calls


def test_alternating_rounds_cancel_a_steady_drift():
    run, calls = drifting_machine({"HEAD": 100.0, "old": 100.0}, drift=10.0)
    records = side_by_side(run, ("HEAD", "old"), rounds=2)
    assert calls == ["HEAD", "old", "old", "HEAD"]
    assert [(r["round"], r["revision"]) for r in records] == [
        (1, "HEAD"), (1, "old"), (2, "old"), (2, "HEAD")]
    per_round, total = ratios(records, "cpu_s")
    assert per_round == pytest.approx([100 / 110, 130 / 120])
    assert total == pytest.approx(1.0)            # 230 / 230: the drift weighs on both alike
    # the same drift without alternation would have said HEAD is 8 % faster: 220 / 240
    assert ratios(records, "wall_s")[1] == pytest.approx(1.0)


def test_a_real_difference_survives_the_drift():
    run, _ = drifting_machine({"HEAD": 120.0, "old": 100.0}, drift=5.0)
    records = side_by_side(run, ("HEAD", "old"), rounds=4)
    # runs 0, 3, 4, 7 are HEAD's and 1, 2, 5, 6 the old one's: 70 s of drift land on each
    assert sum(r["cpu_s"] for r in records if r["revision"] == "HEAD") == 4 * 120 + 70
    assert sum(r["cpu_s"] for r in records if r["revision"] == "old") == 4 * 100 + 70
    assert ratios(records, "cpu_s")[1] == pytest.approx(550 / 470)


def test_no_rounds_is_refused_before_any_run(capsys):
    with pytest.raises(SystemExit):
        main(["--against", "HEAD~1", "--rounds", "0"])
    assert "--rounds: at least 1, not 0" in capsys.readouterr().err
