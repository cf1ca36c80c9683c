"""The makespan benchmark (benchmarks/makespan.py) on job records written as Snakemake writes
them: jobs joined from their outputs' records, linked through their files, the critical chain
and list scheduling checked against schedules worked out by hand."""

import base64
import json
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT))                 # the benchmarks are modules of the repository
from benchmarks.makespan import critical_chain, read_jobs, simulated_makespan  # noqa: E402


def _record(metadata, output, rule, start, end, inputs=()):
    name = base64.urlsafe_b64encode(output.encode()).decode()
    (metadata / name).write_text(json.dumps({"rule": rule, "input": list(inputs),
                                             "starttime": start, "endtime": end}))


@pytest.fixture
def metadata(tmp_path):
    """a (4 s) -> c (2 s) -> d (1 s); b (3 s) -> d; e (5 s) alone; a job with two outputs; a
    rerun whose record kept an earlier start; another configuration's folder inside."""
    m = tmp_path / "metadata"
    m.mkdir()
    _record(m, "results/a.nc", "a", 0.0, 4.0)
    _record(m, "results/a.png", "a", 0.0001, 4.0)            # the same job, another output
    _record(m, "results/b.nc", "b", 0.0, 3.0)
    _record(m, "results/c.nc", "c", 4.0, 6.0, ["results/a.nc"])
    _record(m, "results/d.nc", "d", 1.0, 7.0, ["results/c.nc", "results/b.nc"])  # kept start
    _record(m, "results/e.nc", "e", 0.0, 5.0, ["data/x.csv"])
    _record(m, "results/reduced/paper_b/datasets/f.nc", "f", 0.0, 99.0)
    return m


def test_jobs_are_joined_linked_and_started_after_their_inputs(metadata):
    jobs = {job.rule: job for job in read_jobs("results", metadata)}
    assert sorted(jobs) == ["a", "b", "c", "d", "e"]             # the nested run left out
    assert jobs["a"].outputs == {"results/a.nc", "results/a.png"}
    assert jobs["d"].duration == pytest.approx(1.0)               # 6 -> 7, not 1 -> 7
    length, chain = critical_chain(list(jobs.values()))
    assert length == pytest.approx(7.0) and [j.rule for j in chain] == ["a", "c", "d"]


@pytest.mark.parametrize("cores, makespan", [(1, 15.0), (2, 8.0), (3, 7.0), (64, 7.0)])
def test_list_scheduling_starts_the_longest_chain_first(metadata, cores, makespan):
    """Two cores: a (chain 7) and e (chain 5) first, before b (4); at 4, b before c (its chain
    4 against 3); c at 5 when e ends; d at 7, done at 8. One core: the sum, 15."""
    assert simulated_makespan(read_jobs("results", metadata), cores) == pytest.approx(makespan)


def test_batch_jobs_take_half_the_cores_by_amdahls_law(metadata, declared):
    """A batch job (a rule that declares ``resources: batch=1``) on 8 cores runs on 4 threads:
    its recorded 4 s becomes 4 (0.1 + 0.9 / 4) = 1.3 s, and it takes 4 cores; other jobs keep
    theirs. Snakemake's rules name the batch rules, with the rules that use them."""
    from benchmarks.makespan import on_cores

    jobs = read_jobs("results", metadata)
    scaled = {j.rule: j for j in on_cores(jobs, 8, {"a"}, 0.1)}
    assert scaled["a"].duration == pytest.approx(1.3) and scaled["a"].threads == 4
    assert scaled["b"].duration == pytest.approx(3.0) and scaled["b"].threads == 1
    # a: 1.3, then c: 2 -> d at 3.3 + 1; b (3 s) and e (5 s) beside it on the other cores
    assert simulated_makespan(list(scaled.values()), 8) == pytest.approx(5.0)
    # on 2 cores a batch job takes one thread, as recorded
    assert [j.duration for j in on_cores(jobs, 2, {"a"}, 0.1)] == [j.duration for j in jobs]
    found = {name for name, rule in declared.items() if rule.batch}
    assert {"b_ga", "b_ga_shard", "b_table1_runs", "b_zeta_inversion"} <= found
    assert "comparison" not in found and "b_time_responses" not in found


def test_the_slurm_profile_sets_the_threads_of_every_batch_rule_and_no_other():
    """The SLURM profile's ``set-threads`` block is what rotorvib.pipeline.slurm_profile writes
    from Snakemake's rules: exactly the rules that declare ``resources: batch=1``, each with
    more than one thread (a cluster job's step evaluates a rule's threads with its own cores,
    and only a ``--set-threads`` crosses into it)."""
    import yaml

    from rotorvib.pipeline.slurm_profile import CLUSTER_THREADS, batch_rules, written

    path = ROOT / "profiles/slurm/config.yaml"
    rules = batch_rules(ROOT)
    assert written(path.read_text(), rules) == path.read_text()
    threads = yaml.safe_load(path.read_text())["set-threads"]
    assert sorted(threads) == rules and set(threads.values()) == {CLUSTER_THREADS} != {1}
