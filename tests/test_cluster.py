"""The shipped SLURM profile on a real one-node SLURM cluster, rebuilding part of a reduced run
(tests/workflow_runs.py)."""

import os
import re
import subprocess
from collections import Counter

import pytest
import yaml

from conftest import ROOT
from workflow_runs import REDUCED_SHARDED, copy_run, digests, job_counts, job_records, snakemake

CLUSTER = ROOT / "workflow/cluster/one-node-slurm"


@pytest.fixture(scope="module")
def slurm_cluster(tmp_path_factory):
    """A one-node SLURM cluster without accounting (workflow/cluster/one-node-slurm), stopped
    afterwards; the test skips, with the script's reason, only where SLURM cannot be set up."""
    where = tmp_path_factory.mktemp("slurm") / "cluster"     # start makes it itself
    start = subprocess.run([str(CLUSTER), "start", str(where)], capture_output=True, text=True,
                           timeout=600)
    if start.returncode == 77:
        pytest.skip(start.stderr.strip())
    assert start.returncode == 0, start.stderr
    try:
        yield {"SLURM_CONF": str(where / "slurm.conf")}
    finally:
        subprocess.run([str(CLUSTER), "stop", str(where)], timeout=120)


SLURM_PROFILE = ROOT / "profiles/slurm/config.yaml"
#: The sharded study the cluster test rebuilds, and its shards
SHARDED_STUDY = "paper_b/datasets/balance_beta.nc"
SHARDS = [f"paper_b/shards/balance_beta.{k}-of-3.nc" for k in range(3)]
#: Datasets of papers A and C the cluster test rebuilds too, where Snakemake runs
OTHER_RULES = ("a_stability", "c_mass_ratio")


def submitted_jobs(log: str) -> dict[str, str]:
    """SLURM job id -> rule, from the executor plugin's log."""
    return dict(re.findall(r"submitted with SLURM jobid (\d+) \(log: \S*/rule_(\w+?)/", log))


def slurm_record(job_id: str, env: dict) -> str:
    return subprocess.run(["scontrol", "show", "job", job_id], capture_output=True, text=True,
                          env={**os.environ, **env}).stdout


def test_the_shipped_slurm_profile_runs_on_a_real_cluster(runs, tmp_path, slurm_cluster):
    """A sharded study, datasets of papers A and C and the comparison are removed from the
    sharded reduced run (tests/workflow_runs.py) and rebuilt through profiles/slurm as
    the README says: the study's three shards as SLURM jobs (side by side where the node has
    room) with the threads the profile sets, and nothing else; the gathering job, the other
    datasets, their figures and values and the comparison where Snakemake runs. Every result
    comes back byte-identical (so the gathered study equals the unsharded run's,
    test_workflow.py). A hang fails the test (15 min bound)."""
    work = copy_run(runs[1], tmp_path / "work")
    before = digests(work)
    comparison = (work / "results/comparison.csv").read_bytes()
    made = {r["rule"]: min(r["output"])
            for r in sorted(job_records(work), key=lambda r: r["output"])
            if r["rule"] in OTHER_RULES}
    for path in [*made.values(), *(f"results/{name}" for name in [SHARDED_STUDY, *SHARDS]),
                 "results/comparison.csv"]:
        (work / path).unlink()
    run = snakemake(work, "--workflow-profile", "profiles/slurm", *REDUCED_SHARDED,
                    env=slurm_cluster, timeout=900)
    log = run.stdout + run.stderr
    submitted = submitted_jobs(log)
    planned = job_counts(run)
    assert Counter(submitted.values()) == {"b_balance_study_shard": 3}, log
    assert {*OTHER_RULES, "b_balance_study", "comparison"} <= set(planned), planned
    assert any(rule.startswith("figures_") for rule in planned), planned
    threads = yaml.safe_load(SLURM_PROFILE.read_text())["set-threads"]
    assert threads["b_balance_study_shard"] > 1
    spans = []
    for job_id in submitted:
        record = slurm_record(job_id, slurm_cluster)
        assert "JobState=COMPLETED" in record, record
        assert f"NumCPUs={threads['b_balance_study_shard']} " in record, record
        spans.append(re.search(r"StartTime=(\S+) EndTime=(\S+)", record).groups())
    node = subprocess.run(["scontrol", "show", "node"], capture_output=True, text=True,
                          env={**os.environ, **slurm_cluster}).stdout
    if int(re.search(r"CPUTot=(\d+)", node).group(1)) >= 2 * threads["b_balance_study_shard"]:
        assert any(a[0] < b[1] and b[0] < a[1] for a in spans for b in spans if a != b), spans
    assert digests(work) == before
    assert (work / "results/comparison.csv").read_bytes() == comparison

