"""End-to-end workflow tests on the reduced configuration (config/test/config.yaml).

The repository is copied to a temporary directory and the whole workflow runs there once;
the tests then check the outputs, determinism, rerun behaviour, the report, the archive and
the SLURM profile, all through the Snakemake command line as a user would run it.
"""

import hashlib
import os
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

import pytest

from conftest import ROOT, cf_check
from rotorvib.archive import verify_archive
from rotorvib.comparison import read_paper_values

pytestmark = pytest.mark.workflow
BIN = Path(sys.executable).parent
REDUCED = ["--configfile", "config/config.yaml", "config/test/config.yaml"]


def _copy_repository(dest: Path) -> Path:
    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                            cwd=ROOT, capture_output=True, text=True)
    if listed.returncode == 0:
        for name in listed.stdout.splitlines():
            if (ROOT / name).is_file():
                (dest / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(ROOT / name, dest / name)
    else:
        shutil.copytree(ROOT, dest, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("results", ".snakemake", ".git", ".venv"))
    return dest


def snakemake(cwd: Path, *args, check=True) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(cwd / "src")}
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=env)
    if check and run.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{run.stdout}\n{run.stderr}")
    return run


def planned_jobs(run: subprocess.CompletedProcess) -> set[str]:
    """Rule names in the 'Job stats' table of a dry run (empty when nothing is to be done)."""
    lines = (run.stdout + run.stderr).splitlines()
    if "Job stats:" not in lines:
        return set()
    jobs = set()
    for line in lines[lines.index("Job stats:") + 3:]:
        name = line.split()[0] if line.strip() else "total"
        if name == "total":
            break
        jobs.add(name)
    return jobs


def _digests(root: Path) -> dict[str, str]:
    return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted((root / "results").glob("paper_*/**/*"))
            if p.suffix in {".nc", ".csv", ".md", ".png"}}


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    work = _copy_repository(tmp_path_factory.mktemp("repo"))
    snakemake(work, "-j2", *REDUCED)
    return work


C_DOWNSTREAM_OF_TIME = {"c_time_response", "c_fig3", "c_fig4", "c_fig7", "c_linearisation",
                        "c_reproduced_values", "comparison", "all"}


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
    assert len(datasets) == 4 + 4 + 9
    for path in datasets:
        passed, report = cf_check(path)
        assert passed, report


def test_rerun_gives_byte_identical_results(run_dir):
    before = _digests(run_dir)
    snakemake(run_dir, "-j2", "--forceall", *REDUCED)
    assert _digests(run_dir) == before


def test_config_change_reruns_exactly_the_dependent_jobs(run_dir, tmp_path):
    assert planned_jobs(snakemake(run_dir, "-n", *REDUCED)) == set()
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  den_hartog:\n    d: 0.09\n")
    assert planned_jobs(snakemake(run_dir, "-n", *REDUCED, str(change))) == C_DOWNSTREAM_OF_TIME
    change.write_text("paper_c:\n  mass_ratio_family:\n    mu: [0.2, 0.6, 0.85, 1.0, 1.2]\n")
    assert planned_jobs(snakemake(run_dir, "-n", *REDUCED, str(change))) == {
        "c_mass_ratio", "c_fig6", "c_reproduced_values", "comparison", "all"}


def test_source_change_reruns_exactly_the_jobs_using_it(run_dir):
    figures = run_dir / "src/rotorvib/dva/figures.py"
    original = figures.read_text()
    try:
        figures.write_text(original + "\n# an edit\n")
        assert planned_jobs(snakemake(run_dir, "-n", *REDUCED)) == {
            "c_fig3", "c_fig4", "c_fig5", "c_fig6", "c_fig7", "c_ga_convergence",
            "c_linearisation", "all"}
    finally:
        figures.write_text(original)
    assert planned_jobs(snakemake(run_dir, "-n", *REDUCED)) == set()


def test_malformed_config_stops_before_any_job(run_dir, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("paper_c:\n  rotor:\n    M: -5.0\n  ga:\n    popsize: 10\n")
    run = snakemake(run_dir, "-j1", *REDUCED, str(bad), check=False)
    text = run.stdout + run.stderr
    assert run.returncode != 0
    assert "config key 'paper_c.rotor.M': -5.0 is not allowed; must be a number > 0" in text
    assert "unknown key(s) 'popsize'" in text
    assert "rule c_" not in text


def test_report_contains_every_figure(run_dir):
    snakemake(run_dir, "--report", "results/report.html", *REDUCED)
    html = (run_dir / "results/report.html").read_text(errors="replace")
    for name in ("fig3.png", "fig5.png", "comparison.csv", "table2.csv"):
        assert name in html


def test_archive_restores_without_recomputation(run_dir, tmp_path):
    snakemake(run_dir, "-j2", "archive", *REDUCED)
    archive = run_dir / "results/archive/rotorvib-results.tar.gz"
    members = verify_archive(archive)
    assert "results/paper_c/datasets/ga.nc" in members
    fresh = _copy_repository(tmp_path / "fresh")
    with tarfile.open(archive) as tar:
        tar.extractall(fresh, filter="data")
    snakemake(fresh, "-j1", "--touch", *REDUCED)
    assert planned_jobs(snakemake(fresh, "-n", *REDUCED)) == set()


def test_slurm_profile_parses(run_dir):
    run = snakemake(run_dir, "-n", "-F", "--workflow-profile", "workflow/profiles/slurm", *REDUCED)
    assert "c_ga" in planned_jobs(run)


def test_lint_and_format_are_clean():
    lint = subprocess.run([str(BIN / "snakemake"), "--lint"], cwd=ROOT, capture_output=True,
                          text=True)
    assert lint.returncode == 0, lint.stdout + lint.stderr
    fmt = subprocess.run([str(BIN / "snakefmt"), "--check", "."], cwd=ROOT, capture_output=True,
                         text=True)
    assert fmt.returncode == 0, fmt.stdout + fmt.stderr
