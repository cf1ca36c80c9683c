"""End-to-end workflow tests on the reduced configuration (config/test/config.yaml): what the
runs built (every result, Table 2's forces, CF-compliant datasets), their determinism (two
independent runs agree byte for byte), how bad input stops, and the workflow's lint and format,
all through the Snakemake command line as a user would run it. The runs (tests/workflow_runs.py)
are built by the first test here, which starts first, and shared with the other files that read
them (reruns, the report and archive, the cluster).
"""

import re
import subprocess
from pathlib import Path

import netCDF4
import numpy as np
import pytest

from conftest import ROOT, cf_check
from rotorvib.comparison import read_paper_values
from workflow_runs import BIN, REDUCED, copy_run, digests, job_records, snakemake

pytestmark = pytest.mark.workflow


def test_reduced_run_builds_every_paper_c_result(run_dir):
    for name in ("fig3", "fig4", "fig5", "fig6", "fig7", "ga_convergence", "linearisation"):
        assert (run_dir / f"results/paper_c/figures/{name}.png").stat().st_size > 10_000
    rows = (run_dir / "results/comparison.csv").read_text().splitlines()
    quantities = {row.split(",")[2] for row in rows[1:]}
    expected = {p["quantity"] for p in read_paper_values(ROOT / "data/paper_values.csv")}
    assert quantities == expected
    assert "FAIL" in (run_dir / "results/paper_c/tables/derivation_checks.csv").read_text()


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
    """Every dataset, table and figure of two independent runs is the same byte for byte."""
    first, second = (digests(work) for work in runs)
    assert first and first == second


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
    """Force the job drawing paper C's Fig 6 (from the mass-ratio dataset) alone; return its log
    (it must fail)."""
    run = snakemake(work, "-j1", "-f", "results/paper_c/figures/fig6.png", *REDUCED, *args,
                    check=False)
    assert run.returncode != 0, run.stdout
    return (work / "results/logs/figures_c_mass_ratio.log").read_text()


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


def test_a_dataset_made_under_another_configuration_is_refused(run_dir, tmp_path):
    """With Snakemake told to ignore changed parameters (``--rerun-triggers mtime``), a dataset
    made under the old configuration is still refused by the job that reads it."""
    work = copy_run(run_dir, tmp_path / "work")
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  mass_ratio_family:\n    mu: [0.5, 1.0]\n")
    log = _figure_job_error(work, str(change), "--rerun-triggers", "mtime")
    assert ("results/paper_c/datasets/mass_ratio.nc was made by rule 'c_mass_ratio' under "
            "another configuration") in log
    assert not (work / "results/paper_c/figures/fig6.png").exists()


# The one lint declined on purpose: there is no conda environment (README, "Running on a SLURM
# cluster"): environment.txt installs the project itself, which a Snakemake-built conda
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
