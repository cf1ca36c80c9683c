"""The shipped SLURM profile on a real one-node SLURM cluster, rebuilding part of a reduced run
(tests/workflow_runs.py)."""

import filecmp
import os
import re
import subprocess
from collections import Counter

import pytest
import yaml

from conftest import ROOT
from workflow_runs import REDUCED, copy_run, digests, job_counts, job_records, snakemake

pytestmark = pytest.mark.workflow


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


# One dataset job of each paper to rerun on the cluster; the profile gives b_balance_study
# more than one thread.
CLUSTER_RULES = ("a_stability", "b_balance_study", "c_mass_ratio")
SLURM_PROFILE = ROOT / "workflow/profiles/slurm/config.yaml"


def workflow_rules() -> set[str]:
    """Every rule name of the workflow (``rule X:`` and ``use rule ... as X with:``)."""
    text = "\n".join(p.read_text() for p in (ROOT / "workflow/rules").glob("*.smk"))
    return {a or b for a, b in re.findall(r"^(?:rule (\w+):|use rule \w+ as (\w+) with:)",
                                          text, re.M)}


def submitted_jobs(log: str) -> dict[str, str]:
    """SLURM job id -> rule, from the executor plugin's log."""
    return dict(re.findall(r"submitted with SLURM jobid (\d+) \(log: \S*/rule_(\w+?)/", log))


def slurm_record(job_id: str, env: dict) -> str:
    return subprocess.run(["scontrol", "show", "job", job_id], capture_output=True, text=True,
                          env={**os.environ, **env}).stdout


def test_the_shipped_slurm_profile_runs_on_a_real_cluster(run_dir, tmp_path, slurm_cluster):
    """Three datasets and the comparison are removed from a finished reduced run and rebuilt
    through workflow/profiles/slurm as the README says: the datasets as SLURM jobs (with the
    threads the profile sets), their figures, values and the comparison as local rules; every
    result comes back byte-identical. A hang fails the test (15 min bound)."""
    work = copy_run(run_dir, tmp_path / "work")
    before = digests(work)
    comparison = (work / "results/comparison.csv").read_bytes()
    made = {r["rule"]: min(r["output"]) for r in sorted(job_records(work), key=lambda r: r["output"])
            if r["rule"] in CLUSTER_RULES}
    for path in [*made.values(), "results/comparison.csv"]:
        (work / path).unlink()
    run = snakemake(work, "--workflow-profile", "workflow/profiles/slurm", *REDUCED,
                    env=slurm_cluster, timeout=900)
    log = run.stdout + run.stderr
    submitted = submitted_jobs(log)
    per_rule = Counter(submitted.values())
    planned = job_counts(run)
    assert set(CLUSTER_RULES) <= set(per_rule), log
    assert all(per_rule[rule] == planned[rule] for rule in per_rule), (per_rule, planned)
    figures = {rule for rule in planned if rule.startswith("figures_")}
    assert figures and planned["comparison"] == 1      # ran, but locally:
    assert not figures & set(per_rule) and "comparison" not in per_rule
    threads = yaml.safe_load(SLURM_PROFILE.read_text())["set-threads"]
    assert threads["b_balance_study"] > 1 and set(threads) <= workflow_rules()
    for job_id, rule in submitted.items():
        record = slurm_record(job_id, slurm_cluster)
        assert "JobState=COMPLETED" in record, record
        if rule in threads:
            assert f"NumCPUs={threads[rule]} " in record, record
    assert digests(work) == before
    assert (work / "results/comparison.csv").read_bytes() == comparison


def test_a_study_sharded_over_slurm_jobs_gathers_the_local_bytes(run_dir, tmp_path,
                                                                 slurm_cluster):
    """Paper B's beta study split into three shards (paper_b.shards = 3) through the shipped
    profile: each shard a SLURM job of its own, completed, with the profile's threads; the
    gathered dataset byte-identical to the reduced run's unsharded one."""
    work = copy_run(run_dir, tmp_path / "work")
    (work / "sharded.yaml").write_text("results: results/sharded\npaper_b:\n  shards: 3\n")
    name = "paper_b/datasets/balance_beta.nc"
    run = snakemake(work, "--workflow-profile", "workflow/profiles/slurm", *REDUCED,
                    "sharded.yaml", "--", f"results/sharded/{name}", env=slurm_cluster,
                    timeout=900)
    log = run.stdout + run.stderr
    submitted = submitted_jobs(log)
    shards = [job for job, rule in submitted.items() if rule == "b_balance_study_shard"]
    assert len(shards) == 3 and list(submitted.values()).count("b_balance_study") == 1, log
    threads = yaml.safe_load(SLURM_PROFILE.read_text())["set-threads"]["b_balance_study_shard"]
    spans = []
    for job in shards:
        record = slurm_record(job, slurm_cluster)
        assert "JobState=COMPLETED" in record and f"NumCPUs={threads} " in record, record
        spans.append(re.search(r"StartTime=(\S+) EndTime=(\S+)", record).groups())
    node = subprocess.run(["scontrol", "show", "node"], capture_output=True, text=True,
                          env={**os.environ, **slurm_cluster}).stdout
    if int(re.search(r"CPUTot=(\d+)", node).group(1)) >= 2 * threads:   # room for two at once
        assert any(a[0] < b[1] and b[0] < a[1] for a in spans for b in spans if a != b), spans
    assert filecmp.cmp(work / "results" / name, work / "results/sharded" / name, shallow=False)
