"""End-to-end workflow tests on the reduced configuration (config/test/config.yaml).

The repository is copied to two temporary directories and the whole workflow runs in both,
side by side; the tests then check the outputs, determinism (the two runs agree byte for byte),
rerun behaviour, the report, the archive and the SLURM profile, all through the Snakemake
command line as a user would run it.
"""

import csv
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from functools import partial
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import yaml

from conftest import ROOT, cf_check
from forked_snakemake import ForkedSnakemake
from ro_crate import validate_crate
from rotorvib.comparison import read_paper_values
from rotorvib.io.archive import verify_archive
from rotorvib.models.balancer import dop853, engine, settling
from rotorvib.models.balancer.parameters import Balancer, SpeedProfile, fixed_parameters, fixed_state
from rotorvib.models.balancer.simulate import BalanceCriterion, run_batch

pytestmark = pytest.mark.workflow
BIN = Path(sys.executable).parent
REDUCED = ["--configfile", "config/config.yaml", "config/test/config.yaml"]
RECORDER = ROOT / "tests/oracles/job_recorder"
RECORDS = "job_records"


def _copy_repository(dest: Path) -> Path:
    """The repository's files (as git lists them) and the package's caches in
    ``src/**/__pycache__`` (numba's, the sympy code generator's, the fingerprint memo), each
    valid only for its sources (rotorvib.methods.numba_cache, rotorvib.methods.codegen,
    rotorvib.io.fingerprint). The library's own tests build them in the working tree; copied,
    the workflow runs here do not compile them again."""
    for cache in (ROOT / "src").rglob("__pycache__"):
        shutil.copytree(cache, dest / cache.relative_to(ROOT), dirs_exist_ok=True)
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


def _environment(cwd: Path, env: dict | None = None) -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(cwd / "src"), str(RECORDER)]),
            "ROTORVIB_JOB_RECORDS": str(cwd / RECORDS), **(env or {})}


def snakemake(cwd: Path, *args, check=True, env=None, timeout=None) -> subprocess.CompletedProcess:
    """Run Snakemake in ``cwd`` with its own ``src`` first on the path (and ``env`` added); every
    script job records what it loaded into ``cwd/job_records`` (tests/oracles/job_recorder)."""
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=_environment(cwd, env), timeout=timeout)
    if check and run.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{run.stdout}\n{run.stderr}")
    return run


def job_counts(run: subprocess.CompletedProcess) -> dict[str, int]:
    """Jobs per rule in the 'Job stats' table of a run (empty when nothing is to be done)."""
    lines = (run.stdout + run.stderr).splitlines()
    if "Job stats:" not in lines:
        return {}
    jobs = {}
    for line in lines[lines.index("Job stats:") + 3:]:
        name, count = line.split() if line.strip() else ("total", 0)
        if name == "total":
            break
        jobs[name] = int(count)
    return jobs


def planned_jobs(run: subprocess.CompletedProcess) -> set[str]:
    """Rule names in the 'Job stats' table of a dry run (empty when nothing is to be done)."""
    return set(job_counts(run))


def planned_outputs(cwd: Path, *args, command=None) -> set[str]:
    """Output files that Snakemake plans to (re)create, from ``--summary`` (run by ``command``,
    a :class:`forked_snakemake.ForkedSnakemake` of ``cwd``, when given)."""
    run = (command or partial(snakemake, cwd))("--summary", *REDUCED, *args)
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    header = lines[0].split("\t")
    rows = [dict(zip(header, line.split("\t"))) for line in lines[1:] if "\t" in line]
    return {row["output_file"] for row in rows if row["plan"] != "no update"}


def job_records(cwd: Path) -> list[dict]:
    """What each job of the run loaded and read and wrote (tests/oracles/job_recorder)."""
    return [json.loads(p.read_text()) for p in sorted((cwd / RECORDS).glob("*.json"))]


def downstream_outputs(records: list[dict], selected) -> set[str]:
    """Outputs of the ``selected`` jobs and of every job that reads them, transitively."""
    chosen = [r for r in records if selected(r)]
    outputs = {f for r in chosen for f in r["output"]}
    grew = True
    while grew:
        more = [r for r in records if r not in chosen and outputs & set(r["input"])]
        chosen += more
        outputs |= {f for r in more for f in r["output"]}
        grew = bool(more)
    return outputs


def _digests(root: Path) -> dict[str, str]:
    return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted((root / "results").glob("paper_*/**/*"))
            if p.suffix in {".nc", ".csv", ".md", ".png"}}


def _copy_run(run_dir: Path, dest: Path) -> Path:
    shutil.copytree(run_dir, dest, symlinks=True)
    return dest


def _compile_the_engine() -> None:
    """A short stopped batch with each integrator, in this process: it compiles the engine into
    numba's cache in the working tree (under the package's compile lock) before the repository
    is copied, so that the copies carry it and the library tests beside (pytest-xdist) load it:
    one compilation instead of three side by side."""
    b = Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=0.01, eps_bar=0.012, zeta=0.01,
                              beta=1.0)
    p = fixed_parameters(b, SpeedProfile(200.0, "runup"))[None]
    y0 = fixed_state(2, r0=1e-3, theta0=0.0, phi0=[0.5, -0.5])[None]
    for method in dop853.METHODS:
        run_batch(engine.FIXED, p, y0, BalanceCriterion(1e-4, 1.0, 0.05, 1e-3), method=method,
                  stop=settling.StopRule(margin=0.5, check_dt=0.02, neutral=1e-9),
                  progress=False)


@pytest.fixture(scope="module")
def runs(tmp_path_factory) -> list[Path]:
    """Two independent reduced runs, each in its own copy of the repository, side by side (two
    runs share the two cores better than one run followed by another)."""
    _compile_the_engine()
    works = [_copy_repository(tmp_path_factory.mktemp(name)) for name in ("repo", "twin")]
    with ThreadPoolExecutor(len(works)) as pool:
        list(pool.map(lambda work: snakemake(work, "-j2", *REDUCED), works))
    return works


@pytest.fixture(scope="module")
def run_dir(runs) -> Path:
    return runs[0]


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
    first, second = (_digests(work) for work in runs)
    assert first and first == second


def test_config_change_reruns_exactly_the_dependent_jobs(run_dir, tmp_path):
    assert planned_outputs(run_dir) == set()
    records = job_records(run_dir)
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  den_hartog:\n    d: 0.09\n")
    expected = downstream_outputs(records, lambda r: r["rule"] == "c_time_response")
    assert "results/paper_c/figures/fig4.png" in expected
    assert planned_outputs(run_dir, str(change)) == expected
    # the same override on the command line: its nested value is read as YAML, a number
    assert planned_outputs(run_dir, "--config", 'paper_c={den_hartog: {d: 0.09}}') == expected
    change.write_text("paper_b:\n  balance_studies:\n    eps_bar:\n      fixed: {beta: 0.5, "
                      "mass: 0.01}\n")
    assert planned_outputs(run_dir, str(change)) == {
        "results/paper_b/datasets/balance_eps_bar.nc",
        "results/paper_b/figures/balance_eps_bar.png"}


def _edit_in_turn(work: Path, files: list[str], edit) -> dict[str, set[str]]:
    """Planned outputs after editing each file alone (restored afterwards), each dry run a
    ``snakemake`` command forked from one that has done its imports (tests/forked_snakemake.py)."""
    planned = {}
    with ForkedSnakemake(work, _environment(work)) as command:
        for name in files:
            path = work / name
            original, stat = path.read_bytes(), path.stat()
            try:
                edit(path)
                planned[name] = planned_outputs(work, command=command)
            finally:
                path.write_bytes(original)
                os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
    return planned


def _behaviour_edit(path: Path):
    if path.suffix == ".py":
        path.write_text(path.read_text() + "\n_EDITED = True\n")
    else:  # a data file: new content (Snakemake ignores a newer file with an unchanged checksum)
        path.write_text(path.read_text() + "\n")


def test_every_module_and_data_file_reruns_exactly_the_jobs_that_load_it(run_dir, tmp_path):
    """Edit each module under src/rotorvib and each file under data/ in turn: the dry run plans
    exactly the jobs that loaded that module (recorded from sys.modules while they ran) or read
    that file, and everything downstream of them, neither more nor fewer."""
    records = [r for r in job_records(run_dir) if r["rule"] != "archive"]
    modules = sorted(p.relative_to(run_dir).as_posix()
                     for p in (run_dir / "src/rotorvib").rglob("*.py"))
    data = sorted(p.relative_to(run_dir).as_posix() for p in (run_dir / "data").iterdir())
    files = modules + data

    def name_of(path):
        parts = Path(path).relative_to("src").with_suffix("").parts
        return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)

    def expected(path):
        if path.startswith("data/"):
            return downstream_outputs(records, lambda r: path in r["input"])
        return downstream_outputs(records, lambda r: name_of(path) in r["modules"])

    copies = [run_dir, _copy_run(run_dir, tmp_path / "second")]
    with ThreadPoolExecutor(len(copies)) as pool:
        halves = pool.map(lambda k: _edit_in_turn(copies[k], files[k::2], _behaviour_edit),
                          range(len(copies)))
    planned = {name: plan for half in halves for name, plan in half.items()}
    wrong = {name: {"missing": sorted(expected(name) - plan), "extra": sorted(plan - expected(name))}
             for name, plan in planned.items() if plan != expected(name)}
    assert not wrong, json.dumps(wrong, indent=1)
    assert planned["src/rotorvib/__init__.py"] >= {f for r in records for f in r["output"]}


def test_comments_and_docstrings_rerun_nothing(run_dir):
    modules = sorted((run_dir / "src/rotorvib").rglob("*.py"))
    originals = {p: p.read_bytes() for p in modules}
    try:
        for path in modules:
            text = path.read_text()
            if text.startswith('"""'):
                text = '"""Edited: ' + text[3:]
            path.write_text(text + "\n# a comment\n")
        assert planned_outputs(run_dir) == set()
    finally:
        for path, original in originals.items():
            path.write_bytes(original)


def test_malformed_config_stops_before_any_job(run_dir, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("paper_c:\n  rotor:\n    M: -5.0\n  ga:\n    popsize: 10\n")
    run = snakemake(run_dir, "-j1", *REDUCED, str(bad), check=False)
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
    work = _copy_run(run_dir, tmp_path / "work")
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
    work = _copy_run(run_dir, tmp_path / "work")
    change = tmp_path / "change.yaml"
    change.write_text("paper_c:\n  mass_ratio_family:\n    mu: [0.5, 1.0]\n")
    log = _figure_job_error(work, str(change), "--rerun-triggers", "mtime")
    assert ("results/paper_c/datasets/mass_ratio.nc was made by rule 'c_mass_ratio' under "
            "another configuration") in log
    assert not (work / "results/paper_c/figures/fig6.png").exists()


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def browser():
    """Headless Chromium (Debian's package, installed by .ci/run) driven by Playwright."""
    if CHROMIUM is None:
        if os.environ.get("CI"):
            pytest.fail("Chromium is missing: .ci/run installs Debian's chromium package")
        pytest.skip("no Chromium on this machine (Debian package chromium)")
    from playwright.sync_api import sync_playwright
    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(
            executable_path=CHROMIUM,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"])
        yield chromium
        chromium.close()


def _shown_entries(page, report: Path, category: str, subcategory: str) -> list[list[str]]:
    """The rows (label cells) the report lists for one subcategory, in its order, as shown
    after opening the report afresh and choosing that subcategory."""
    page.goto(report.as_uri())
    page.wait_for_selector("h1")
    page.evaluate(f"app.setView({{navbarMode: 'subcategory', category: '{category}', "
                  f"subcategory: '{subcategory}'}})")
    page.wait_for_selector("nav table tbody tr")
    return page.eval_on_selector_all(
        "nav table tbody tr",
        "rows => rows.map(r => [...r.querySelectorAll('td')].map(td => td.innerText.trim()))")


def test_the_report_reads_in_a_browser(run_dir, browser):
    """`snakemake --report` opened in headless Chromium: no console error, no docutils system
    message, the verdict totals on the landing page, every paper's figures in paper order,
    each with its own caption that states every comparison row about it."""
    snakemake(run_dir, "--report", "results/report.html", *REDUCED)
    page = browser.new_page()
    errors = []
    page.on("console", lambda message: errors.append(message.text)
            if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(str(error)))
    report = run_dir / "results/report.html"
    page.goto(report.as_uri())
    page.wait_for_selector("h1")
    landing = page.inner_text("body")
    table = read_comparison(run_dir / "results/comparison.csv")
    assert "Findings" in landing and f"{len(table)} stated values and claims" in landing
    majors = sum(r["verdict"] == "MAJOR" for r in table)
    assert re.search(rf"\ball\s+\d+\s+\d+\s+{majors}\s", landing)  # totals row: MAJOR column
    captions = page.evaluate("Object.fromEntries(Object.entries(results)"
                             ".map(([path, r]) => [path, r.caption]))")
    assert not [path for path, text in captions.items() if "system-message" in text]
    assert not page.query_selector_all(".system-message")
    for paper in "abc":
        drawn = {p.stem for p in (run_dir / f"results/paper_{paper}/figures").glob("*.png")}
        rows = _shown_entries(page, report, f"Paper {paper.upper()}", "Figures")
        names = [figure for _, figure in (row[:2] for row in rows)]
        numbered = [int(m.group(1)) for n in names if (m := re.match(r"Figs? (\d+)", n))]
        assert numbered == sorted(numbered)  # the paper's order, Fig 2 before Fig 10
        assert names[:len(numbered)] == [n for n in names if re.match(r"Figs? \d", n)]
        assert len(names) == len(drawn)
        for name in drawn:
            text = next(t for path, t in captions.items()
                        if path.endswith(f"paper_{paper}/figures/{name}.png"))
            assert f"Paper {paper.upper()}, " in text and (
                "What the paper states" in text or "states no value" in text)
        assert len({captions[p] for p in captions if f"paper_{paper}/figures/" in p}) == len(drawn)
    for row in table:  # every row about a numbered figure is in that figure's caption
        match = re.fullmatch(r"Figs? (\d+)(?:-(\d+))?", row["item"])
        if not match:
            continue
        first, last = int(match.group(1)), int(match.group(2) or match.group(1))
        for path, text in captions.items():
            name = re.search(rf"paper_{row['paper'].lower()}/figures/fig([\d_]+)\.png$", path)
            if name and {int(n) for n in name.group(1).split("_")} & set(range(first, last + 1)):
                assert f"<strong>{row['verdict']}</strong> ({row['item']})" in text, path
    assert errors == []


def read_comparison(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_archive_restores_without_recomputation(run_dir, tmp_path):
    """The archive holds the results, the report, the run's configuration and commit and an
    RO-Crate that passes rocrate-validator; restored into a fresh copy, nothing reruns."""
    snakemake(run_dir, "-j2", "archive", *REDUCED)
    archive = run_dir / "results/archive/rotorvib-results.tar.gz"
    members = verify_archive(archive)
    assert {"results/paper_c/datasets/ga.nc", "LICENSE", "CITATION.cff", "Snakefile",
            "results/report.html", "results/run/config.yaml", "results/run/commit.txt",
            "config/test/config.yaml", "ro-crate-metadata.json"} <= set(members)
    fresh = _copy_repository(tmp_path / "fresh")
    with tarfile.open(archive) as tar:
        tar.extractall(fresh, filter="data")
    assert "Findings" in (fresh / "results/report.html").read_text(errors="replace")
    with ThreadPoolExecutor(1) as pool:      # the validator works while Snakemake restores
        issues = pool.submit(validate_crate, fresh, tmp_path / "cache")
        snakemake(fresh, "-j1", "--touch", *REDUCED)
        assert planned_jobs(snakemake(fresh, "-n", *REDUCED)) == set()
    assert [message for _, message, _ in issues.result()] == [
        "The Root Data Entity SHOULD have a `publisher` property (Organization or Person)"]


CLUSTER = ROOT / "workflow/cluster/one-node-slurm"


@pytest.fixture(scope="module")
def slurm_cluster(tmp_path_factory):
    """A one-node SLURM cluster without accounting (workflow/cluster/one-node-slurm), stopped
    afterwards; the test skips, with the script's reason, only where SLURM cannot be set up."""
    where = tmp_path_factory.mktemp("slurm")
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


def test_the_shipped_slurm_profile_runs_on_a_real_cluster(run_dir, tmp_path, slurm_cluster):
    """Three datasets and the comparison are removed from a finished reduced run and rebuilt
    through workflow/profiles/slurm as the README says: the datasets as SLURM jobs (with the
    threads the profile sets), their figures, values and the comparison as local rules; every
    result comes back byte-identical. A hang fails the test (15 min bound)."""
    work = _copy_run(run_dir, tmp_path / "work")
    before = _digests(work)
    comparison = (work / "results/comparison.csv").read_bytes()
    made = {r["rule"]: min(r["output"]) for r in sorted(job_records(work), key=lambda r: r["output"])
            if r["rule"] in CLUSTER_RULES}
    for path in [*made.values(), "results/comparison.csv"]:
        (work / path).unlink()
    run = snakemake(work, "--workflow-profile", "workflow/profiles/slurm", *REDUCED,
                    env=slurm_cluster, timeout=900)
    log = run.stdout + run.stderr
    submitted = dict(re.findall(r"submitted with SLURM jobid (\d+) \(log: \S*/rule_(\w+?)/", log))
    per_rule = Counter(submitted.values())
    planned = job_counts(run)
    assert set(CLUSTER_RULES) <= set(per_rule), log
    assert all(per_rule[rule] == planned[rule] for rule in per_rule), (per_rule, planned)
    figures = {rule for rule in planned if rule.startswith("figures_")}
    assert figures and planned["comparison"] == 1      # ran, but locally:
    assert not figures & set(per_rule) and "comparison" not in per_rule
    threads = yaml.safe_load(SLURM_PROFILE.read_text())["set-threads"]
    assert threads["b_balance_study"] > 1 and set(threads) <= {r["rule"] for r in job_records(work)}
    for job_id, rule in submitted.items():
        record = subprocess.run(["scontrol", "show", "job", job_id], capture_output=True,
                                text=True, env={**os.environ, **slurm_cluster}).stdout
        assert "JobState=COMPLETED" in record, record
        if rule in threads:
            assert f"NumCPUs={threads[rule]} " in record, record
    assert _digests(work) == before
    assert (work / "results/comparison.csv").read_bytes() == comparison


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
