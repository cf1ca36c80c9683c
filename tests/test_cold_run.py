"""The side-by-side comparison of two revisions' cold runs (benchmarks/cold_run.py --against):
its alternating order cancels a machine that drifts during the comparison, its ratios are
those of the sums, and its hook records each job's CPU as the operating system accounts it."""

import json
import resource
import subprocess
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT))                 # the benchmarks are modules of the repository
import benchmarks.cold_run as cold_run_module  # noqa: E402
from benchmarks.cold_run import (  # noqa: E402
    JOB_HOOK,
    common_jobs_ratio,
    figures_left_out,
    job_seconds,
    main,
    ratios,
    rule_group,
    side_by_side,
)


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


def test_both_sides_stay_the_commits_they_were_at_the_start(tmp_path, monkeypatch, capsys):
    """A commit made while the comparison runs (its rounds take an hour) changes neither side:
    every round of HEAD runs the commit HEAD was when it began."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=tmp_path, check=True, capture_output=True,
                              text=True, env={"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t",
                                              "GIT_COMMITTER_NAME": "t",
                                              "GIT_COMMITTER_EMAIL": "t@t", "HOME": str(tmp_path)}
                              ).stdout.strip()

    git("init", "-q")
    for message in ("old", "head"):
        git("commit", "-q", "--allow-empty", "-m", message)
    start = {"HEAD": git("rev-parse", "HEAD"), "HEAD~1": git("rev-parse", "HEAD~1")}
    ran = []

    def fake_cold_run(repository, cores, revision):
        ran.append(revision)
        git("commit", "-q", "--allow-empty", "-m", "made meanwhile")
        return {"commit": revision, "cpu_s": 1.0, "wall_s": 1.0, "jobs": 0, "jobs_cpu_s": {}}

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(cold_run_module, "cold_run", fake_cold_run)
    main(["--against", "HEAD~1", "--rounds", "2"])
    assert ran == [start["HEAD"], start["HEAD~1"], start["HEAD~1"], start["HEAD"]]
    assert f"round 2, HEAD ({start['HEAD'][:7]})" in capsys.readouterr().out


def test_the_hook_records_a_jobs_rule_and_cpu_as_it_exits(tmp_path):
    hook, records = tmp_path / "hook", tmp_path / "jobs"
    hook.mkdir()
    records.mkdir()
    (hook / "sitecustomize.py").write_text(JOB_HOOK)
    job = ("from types import SimpleNamespace\nimport time\n"
           "snakemake = SimpleNamespace(rule='figures_b_fig8', output=["
           "'results/paper_b/figures/fig9.png', 'results/paper_b/figures/fig9.svg', "
           "'results/paper_b/figures/fig8.png'])\n"
           "end = time.process_time() + 0.3\nwhile time.process_time() < end: pass\n")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", job], check=True,
                   env={"PYTHONPATH": str(hook), "ROTORVIB_JOB_CPU": str(records)})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    accounted = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    [record] = [json.loads(p.read_text()) for p in records.glob("*.json")]
    assert record["rule"] == "figures_b_fig8"
    assert record["figures"] == ["paper_b/fig8", "paper_b/fig9"]
    assert 0.3 <= record["cpu"] and abs(record["cpu"] - accounted) < 0.05, (record, accounted)
    # a process that runs no job records nothing
    subprocess.run([sys.executable, "-c", "pass"], check=True,
                   env={"PYTHONPATH": str(hook), "ROTORVIB_JOB_CPU": str(records)})
    assert len(list(records.glob("*.json"))) == 1


def test_jobs_are_compared_over_the_rules_and_figures_both_revisions_have():
    """The rules both revisions recorded in every round, and the figure jobs that draw only
    figures both draw (however each groups them into jobs); a new study's rule and the figure
    job of its figure are left out alike."""
    assert [rule_group(r) for r in ("b_ga_shard", "b_ga", "comparison")] == [
        "b_ga", "b_ga", "comparison"]
    head_figures = [{"figures": ["paper_b/fig8", "paper_b/fig9"], "cpu_s": 20.0},
                    {"figures": ["paper_b/new"], "cpu_s": 4.0}]
    old_figures = [{"figures": ["paper_b/fig8"], "cpu_s": 14.0},
                   {"figures": ["paper_b/fig9"], "cpu_s": 12.0}]
    records = [{"round": 1, "revision": "HEAD", "figure_jobs": head_figures,
                "jobs_cpu_s": {"b_ga": 60.0, "b_new_study": 5.0}},
               {"round": 1, "revision": "old", "figure_jobs": old_figures,
                "jobs_cpu_s": {"b_ga": 55.0}},
               {"round": 2, "revision": "old", "figure_jobs": old_figures,
                "jobs_cpu_s": {"b_ga": 57.0}},
               {"round": 2, "revision": "HEAD", "figure_jobs": head_figures,
                "jobs_cpu_s": {"b_ga": 62.0, "b_new_study": 5.0}}]
    ratio, common = common_jobs_ratio(records)
    assert common == ["b_ga", "figures"]                 # the new study is left out
    assert ratio == pytest.approx((60 + 20 + 62 + 20) / (55 + 26 + 57 + 26))
    assert figures_left_out(records, "HEAD") == (["paper_b/new"], 8.0)
    assert figures_left_out(records, "old") == ([], 0.0)
    assert job_seconds(records[0]) == 60 + 5 + 20 + 4
