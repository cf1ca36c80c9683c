"""End-to-end workflow tests on the reduced configuration (config/test/config.yaml): what the
runs built (every result, Table 2's forces, CF-compliant datasets), their determinism (two
independent runs, one of them sharded, agree byte for byte), how bad input stops, and the
workflow's lint and format, all through the Snakemake command line as a user would run it. The
runs are shared with test_reruns.py (what reruns after an edit), test_delivery.py,
test_archive_runs.py and test_cluster.py (tests/workflow_runs.py); this file's tests start
first.
"""

import csv
import re
import subprocess
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import yaml

import rotorvib.comparison.verdicts as comparison
from conftest import ROOT, cf_check
from rotorvib.comparison.paper_values import read_paper_values
from workflow_runs import (
    BIN,
    REDUCED,
    copy_run,
    digests,
    job_records,
    snakemake,
    summary_rows,
)

pytestmark = pytest.mark.workflow


def test_reduced_run_builds_every_paper_c_result(run_dir):
    for name in ("fig3", "fig4", "fig5", "fig6", "fig7", "ga_convergence", "linearisation"):
        assert (run_dir / f"results/paper_c/figures/{name}.png").stat().st_size > 10_000
    rows = (run_dir / "results/comparison.csv").read_text().splitlines()
    quantities = {row.split(",")[2] for row in rows[1:]}
    expected = {p["quantity"] for p in read_paper_values(ROOT / "data/paper_values.csv")}
    assert quantities == expected
    assert "FAIL" in (run_dir / "results/paper_c/tables/derivation_checks.csv").read_text()


def test_no_row_prints_a_missing_number_as_nan(run_dir):
    """A number that does not exist (a run that never balances, an undetermined margin) is
    said in words or left empty in the comparison, the discrepancy analysis and the report's
    captions, never printed as 'nan' (Fig 11's row said 'beta0.1 nan s') or as an infinity
    (a curve censored at its bottom rose by '-inf s')."""
    cells = [cell for name in ("comparison.csv", "discrepancies.csv")
             for row in csv.reader((run_dir / "results" / name).open(newline=""))
             for cell in row]
    assert len(cells) > 1000
    assert [cell for cell in cells if re.search(r"\bnan\b", cell, re.I)] == []
    # nor as an infinity ("IC1 -inf s") in a text, there or in the report's captions (a
    # margin column may hold inf: a number a program reads)
    texts = [row["explanation"] for row in csv.DictReader(
        (run_dir / "results/comparison.csv").open(newline=""))]
    captions = [p.read_text() for p in (run_dir / "results/report/captions").rglob("*.rst")]
    assert len(captions) > 20
    assert [c for c in texts + captions if re.search(r"[-+]?\binf\b", c, re.I)] == []


def test_every_decided_claim_names_its_choices_and_what_each_alternative_gave(run_dir):
    """Each decided claim row of the comparison lists the project's choices it rests on, each
    led by a configuration key that exists (or a constant of rotorvib.comparison.verdicts), and a
    DEPENDS row lists the alternatives it was evaluated under with what each gave."""
    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    rows = list(csv.DictReader((run_dir / "results/comparison.csv").open(newline="")))
    decided = [r for r in rows if r["paper_value"] == ""
               and r["verdict"] in ("SUPPORTED", "NOT SUPPORTED", "DEPENDS")]
    assert len(decided) > 40
    assert [r["quantity"] for r in decided if not r["choices"]] == []
    keys = {m.group(0) for r in rows for choice in r["choices"].split(" | ")
            for m in [re.match(r"(paper_[abc]|comparison)(\.\w+)+", choice)] if m}
    assert len(keys) > 30

    def exists(key):
        head, *path = key.split(".")
        if head == "comparison" and hasattr(comparison, path[0]):
            return True
        node = config[head]
        for part in path:
            if not isinstance(node, dict) or part not in node:
                return False
            node = node[part]
        return True

    assert sorted(k for k in keys if not exists(k)) == []
    for r in (r for r in decided if r["verdict"] == "DEPENDS"):
        outcomes = {part.rsplit(": ", 1)[1] for part in r["alternatives"].split("; ")}
        assert "holds" in outcomes and outcomes - {"holds"}, r["quantity"]
    zeta = next(r for r in rows if r["quantity"] == "zeta_reproduces_printed_times")
    assert zeta["alternatives"].count(": ") == 4          # two kinematics x two definitions


def test_table2_peak_forces_match_the_paper(run_dir):
    """With R = 0.1 m (inferred), IC1 and the printed kinematics, Table 2's maximum bearing
    forces are reproduced within 1 %."""
    rows = (run_dir / "results/paper_b/tables/table2.csv").read_text().splitlines()[1:]
    forces = [float(r.split(",")[3]) for r in rows]
    paper = {p["quantity"]: p["value"] for p in read_paper_values(ROOT / "data/paper_values.csv")}
    for i, force in enumerate(forces, start=1):
        assert force == pytest.approx(paper[f"table2_fmax_{i}"], rel=0.01)


def test_datasets_pass_cf_1_11(run_dir):
    datasets = sorted(run_dir.glob("results/paper_*/datasets/*.nc"))
    written = {f for r in job_records(run_dir) for f in r["output"] if f.endswith(".nc")}
    assert {p.relative_to(run_dir).as_posix() for p in datasets} == written
    passed, report = cf_check(*datasets)
    assert passed, report


def test_two_runs_give_byte_identical_results(runs):
    """Every dataset, table and figure of two independent runs is the same byte for byte, the
    second with paper B's batch studies in three shards each (tests/workflow_runs.py): a run is
    deterministic, and sharding changes no result. The second has its shards besides."""
    first, second = (digests(work) for work in runs)
    shards = {name for name in second if name.startswith("results/paper_b/shards/")}
    assert first and shards and first == {k: v for k, v in second.items() if k not in shards}


def test_jobs_load_the_heavy_libraries_only_where_their_work_needs_them(run_dir):
    """pint (ROSS's) only in the job that runs ROSS, xarray's probe for it answered without it
    (rotorvib.pipeline.pint_probe); SALib only where a Sobol study samples and analyses; pymoo
    only where a genetic algorithm or NSGA-II runs: not in the jobs that read datasets, draw
    them or state their claims."""
    loaded = {package: {r["rule"] for r in job_records(run_dir) if package in r["packages"]}
              for package in ("pint", "SALib", "pymoo")}
    assert loaded == {"pint": {"b_ross"}, "SALib": {"b_uncertainty", "c_uncertainty"},
                      "pymoo": {"b_ga", "b_pareto", "c_ga", "c_broadband", "c_discrepancies"}}


def test_malformed_config_stops_before_any_job(run_dir, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("paper_c:\n  rotor:\n    M: -5.0\n  ga:\n    popsize: 10\n")
    work = copy_run(run_dir, tmp_path / "work")
    run = snakemake(work, "-j1", *REDUCED, str(bad), check=False)
    text = run.stdout + run.stderr
    assert run.returncode != 0
    assert "config key 'paper_c.rotor.M': -5.0 is not allowed; must be a number > 0" in text
    assert "unknown key(s) 'popsize'" in text
    assert "rule c_" not in text


def _figure_job_error(work: Path, *args) -> str:
    """Force the job drawing paper C's Fig 6 (from the mass-ratio dataset; the job of paper C's
    figures that wait for no batch study, named for Fig 3) alone; return its log (it must
    fail), which the console shows too (the default profile's show-failed-logs)."""
    run = snakemake(work, "-j1", "-f", "results/paper_c/figures/fig6.png", *REDUCED, *args,
                    check=False)
    assert run.returncode != 0, run.stdout
    log = (work / "results/logs/figures_c_fig3.log").read_text()
    error = next(line for line in log.splitlines() if "DatasetError" in line)
    assert error in run.stdout + run.stderr
    return log


def test_an_offset_beyond_paper_a_expansion_stops_its_job_naming_the_key(run_dir, tmp_path):
    """Found by the fuzzer (tests/schema_fuzz.py): a case so slow that the configured offset is
    beyond the two-term expansion passes every check before the jobs (its limit has no closed
    form) and stops paper A's responses job, which names the config key and what to change."""
    work = copy_run(run_dir, tmp_path / "work")
    run = snakemake(work, "-j1", "results/paper_a/datasets/responses.nc", *REDUCED, "--config",
                    "paper_a={case: {omega: 0.002}}", check=False)
    assert run.returncode != 0, run.stdout
    log = (work / "results/logs/a_responses.log").read_text()
    assert ("config key 'paper_a.initial_offset': two-term initial conditions did not "
            "converge") in log
    assert "a smaller offset" in log and "a smaller offset" in run.stdout + run.stderr


def test_a_nan_poisoned_dataset_stops_the_downstream_rule(run_dir, tmp_path):
    """A valid netCDF whose values were overwritten with NaN after its rule wrote it never reaches
    a figure: the reading job stops, naming the file, the variable and the rule to rerun."""
    work = copy_run(run_dir, tmp_path / "work")
    path = work / "results/paper_c/datasets/mass_ratio.nc"
    with netCDF4.Dataset(path, "a") as nc:
        nc["D"][0, 0, :] = np.nan
    log = _figure_job_error(work)
    assert ("results/paper_c/datasets/mass_ratio.nc: variable 'D' is not what rule "
            "'c_mass_ratio' wrote") in log
    assert "snakemake --forcerun c_mass_ratio" in log
    assert not (work / "results/paper_c/figures/fig6.png").exists()


def test_a_copied_in_dataset_names_the_rule_that_makes_its_path(run_dir, tmp_path):
    """A valid dataset of another rule copied over the mass-ratio dataset (and so newer than
    its inputs) is refused, naming the rule that makes that path."""
    work = copy_run(run_dir, tmp_path / "work")
    datasets = work / "results/paper_c/datasets"
    (datasets / "mass_ratio.nc").write_bytes((datasets / "distance.nc").read_bytes())
    log = _figure_job_error(work)
    assert ("results/paper_c/datasets/mass_ratio.nc was made by rule 'c_distance', but rule "
            "'c_mass_ratio' makes this file (copied in?); rebuild it: snakemake --forcerun "
            "c_mass_ratio") in log


def test_a_dataset_made_under_another_configuration_is_refused(run_dir, tmp_path):
    """With Snakemake told to ignore changed parameters (``--rerun-triggers mtime``), a dataset
    made under the old configuration is still refused by the job that reads it."""
    work = copy_run(run_dir, tmp_path / "work")
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  mass_ratio_family:\n    mu: [0.2, 0.6, 0.85, 1.0, 1.2]\n")
    log = _figure_job_error(work, str(change), "--rerun-triggers", "mtime")
    assert ("results/paper_c/datasets/mass_ratio.nc was made by rule 'c_mass_ratio' under "
            "another configuration") in log
    assert not (work / "results/paper_c/figures/fig6.png").exists()


# The one lint declined on purpose: there is no conda environment (README, "Running on a SLURM
# cluster"): the set-up installs the project itself, which a Snakemake-built conda
# environment cannot do.
DECLINED_LINTS = {"Specify a conda environment or container for each rule."}


def test_lint_and_format_are_clean():
    lint = subprocess.run([str(BIN / "snakemake"), "--lint"], cwd=ROOT, capture_output=True,
                          text=True)
    text = lint.stdout + lint.stderr
    lints = set(re.findall(r"^    \* (.+?):$", text, flags=re.MULTILINE))
    assert lints <= DECLINED_LINTS, text
    assert lint.returncode == 0 or lints, text
    fmt = subprocess.run([str(BIN / "snakefmt"), "--check", "."], cwd=ROOT, capture_output=True,
                         text=True)
    assert fmt.returncode == 0, fmt.stdout + fmt.stderr


def test_the_reduced_configuration_writes_to_its_own_folder():
    """config/test/config.yaml as the README gives it never touches the paper configuration's
    results: every output it plans lies under results/reduced/."""
    run = subprocess.run([str(BIN / "snakemake"), "--summary", "--configfile",
                          "config/config.yaml", "config/test/config.yaml"], cwd=ROOT,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    outputs = [row["output_file"] for row in summary_rows(run.stdout)]
    assert len(outputs) > 100
    assert all(path.startswith("results/reduced/") for path in outputs), [
        p for p in outputs if not p.startswith("results/reduced/")][:5]


@pytest.mark.parametrize("log", ["b_pareto_printed.log", "c_broadband.log"])
def test_the_searches_logs_show_their_generations_advancing(run_dir, log):
    """The Pareto study's and the broadband absorber's searches log their generations too
    (each of the broadband's seeds its own): timed lines from the first generation to the last
    of the total, in order."""
    text = (run_dir / "results/logs" / log).read_text()
    found = re.findall(r"^\d\d:\d\d:\d\d (.*generations): (\d+) of (\d+), [\d.]+ s elapsed, "
                       r"about \S+ s left$", text, re.M)
    searches = {what for what, _, _ in found}
    assert len(searches) == (5 if log == "c_broadband.log" else 1), text
    for search in searches:
        done = [int(d) for what, d, _ in found if what == search]
        total = {int(t) for what, _, t in found if what == search}
        assert done[0] == 1 and total == {done[-1]} and done == sorted(done), text


def test_the_gas_log_shows_its_generations_advancing(run_dir):
    """Paper B's GA, the longest job, writes its progress to its log while it runs: each line
    timed, with the generation of the total, the time elapsed and an estimate of what is left."""
    log = (run_dir / "results/logs/b_ga.log").read_text()
    generations = [int(g) for g in re.findall(r"^\d\d:\d\d:\d\d GA generations \(\d+ searches "
                                              r"in lockstep\): (\d+) of (?:\d+), ", log, re.M)]
    total = int(re.search(r"GA generations \(\d+ searches in lockstep\): \d+ of (\d+)",
                          log).group(1))
    assert generations[0] == 1 and generations[-1] == total
    assert generations == sorted(generations) and "about" in log
