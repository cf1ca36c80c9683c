"""What a person sees on the console: every line short enough to read, the reasons why a job
runs shown only when asked for (the profile's ``quiet: [reason]``; Snakemake's reason lists
every missing or updated file), no "Shell command: None" under each script job; each job's
progress, fewer lines than its log and named after the job (rotorvib.pipeline.console); and at
the run's end where the results are or which job failed and why (rotorvib.pipeline.run_summary,
the Snakefile's onsuccess and onerror)."""

import io
import logging
import subprocess
import sys
from pathlib import Path

from conftest import ROOT
from rotorvib.pipeline import console, run_summary
from rotorvib.pipeline.config import load_yaml

FRESH = ["-n", "--config", "results=results/console-check"]   # nothing made: every job planned


def _longest(run) -> int:
    return max(len(line) for line in (run.stdout + run.stderr).splitlines())


def test_a_whole_plan_prints_no_line_of_kilobytes(snakemake_here):
    """A dry run of every job into an empty results folder: each job is named by its message,
    no line reaches a thousand characters, and no job's reason is printed."""
    run = snakemake_here(*FRESH)
    assert run.returncode == 0, run.stderr
    assert "Job " in run.stdout and "Reason:" not in run.stdout + run.stderr
    assert "Shell command" not in run.stdout + run.stderr
    assert _longest(run) < 1000


def test_the_reasons_come_back_when_asked_for(snakemake_here):
    """``--quiet host`` (the user guide's advice) replaces the profile's list: each job's reason
    is printed again, file lists and all."""
    run = snakemake_here(*FRESH, "--quiet", "host")
    assert run.returncode == 0, run.stderr
    assert "Reason: Missing output files:" in run.stdout + run.stderr
    assert _longest(run) > 1000



def _logger(stream, clock, every=10.0):
    logger = logging.getLogger(f"test_console.{id(stream)}")
    logger.propagate = False
    logger.setLevel(logging.INFO)
    logger.addHandler(console.ConsoleProgress(stream, "b_balance\nbeta", every=every,
                                              clock=clock))
    return logger


def test_progress_lines_are_named_escaped_and_throttled():
    stream, now = io.StringIO(), [0.0]
    logger = _logger(stream, lambda: now[0])
    for t, message in [(0, "GA: 0 of 9"), (4, "GA: 1 of 9"), (10, "GA: 2 of\x1b 9"),
                       (15, "GA: 3 of 9"), (21, "GA: 4 of 9")]:
        now[0] = t
        logger.info(message)
    assert stream.getvalue().splitlines() == [
        "[b_balance\\nbeta] GA: 0 of 9", "[b_balance\\nbeta] GA: 2 of\x1b 9",
        "[b_balance\\nbeta] GA: 4 of 9"]


def test_a_job_is_named_after_its_log():
    assert console.job_name("results/logs/b_pareto_printed.log") == "b_pareto_printed"


def test_a_job_writes_its_progress_to_its_log_and_to_the_console(tmp_path):
    """A job process (rotorvib.pipeline.job): every progress line in its log, the first on the
    console (standard error before the job started), named after the job."""
    script = ("import sys\nfrom rotorvib.pipeline import job\njob.start(sys.argv[1])\n"
              "from rotorvib.io.progress import Progress\np = Progress('steps', 3, every=0)\n"
              "for k in range(4):\n    p(k)\n")
    log = tmp_path / "c_broadband.log"
    run = subprocess.run([sys.executable, "-c", script, str(log)], check=False, capture_output=True,
                         text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert run.stderr.splitlines()[0].startswith("[c_broadband] steps: 0 of 3")
    assert len(run.stderr.splitlines()) == 1
    assert log.read_text().count("steps: ") == 4


def test_the_end_of_a_run_says_where_its_results_are(tmp_path):
    for path in ["out/comparison.md", "out/paper_c/figures/fig3.png", "out/logs/c_ga.log"]:
        (tmp_path / path).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / path).write_text("")
    text = run_summary.success_text("out", ["c"], left_out=["a", "b"],
                                    configfiles=["config/config.yaml", "my file.yaml"],
                                    root=tmp_path)
    assert "out/comparison.md" in text and "out/paper_c/figures/" in text
    assert "out/logs/" in text and "discrepancies.md" not in text
    assert "Left out by this configuration (key 'papers'): paper A, paper B" in text
    assert ("snakemake --report out/report.html --configfile config/config.yaml "
            "'my file.yaml'") in text


def test_a_run_outside_the_workflows_folder_gets_a_report_command_that_says_where(tmp_path):
    """From a module's caller or with ``--directory``, the report's command names the working
    folder, the stylesheet (where the workflow's folder has it: a workflow fetched from a URL
    may not) and the configuration files by their absolute paths, so that it works from
    whichever folder the user is in."""
    css = tmp_path / "rotorvib/profiles/report.css"
    css.parent.mkdir(parents=True)
    css.write_text("")
    folder = tmp_path / "analysis"
    command = run_summary.report_command("results", ["config/my.yaml"],
                                         elsewhere=(folder, css))
    assert command == (f"snakemake --report results/report.html --directory {folder} "
                       f"--report-stylesheet {css} --configfile "
                       f"{(Path.cwd() / 'config/my.yaml').resolve()}")
    missing = run_summary.report_command("results", elsewhere=(folder, tmp_path / "none.css"))
    assert missing == f"snakemake --report results/report.html --directory {folder}"


def test_the_papers_left_out_come_from_the_schema():
    schema = load_yaml(ROOT / "config/schema.yaml")
    papers = sorted(key.removeprefix("paper_") for key in schema["properties"]
                    if key.startswith("paper_"))
    assert len(papers) >= 2
    assert run_summary.left_out(papers[-1:], schema) == papers[:-1]
    assert run_summary.left_out(papers, schema) == []


SNAKEMAKE_LOG = """\
[Sat Nov 28 19:00:00 2026]
Error in rule c_ga:
    message: Paper C: genetic-algorithm tuning
    jobid: 3
    output: out/paper_c/datasets/ga.nc
    log: out/logs/c_ga.log (check log file(s) for error details)
Logfile out/logs/c_ga.log:
================================================================================
Shutting down, this might take some time.
Error in rule c_ga:
    message: None
    jobid: 3
    log: out/logs/c_ga.log (check log file(s) for error details)
"""


def test_a_failed_run_names_the_job_its_log_and_its_error(tmp_path):
    (tmp_path / "out/logs").mkdir(parents=True)
    trace = ["Traceback (most recent call last):"] + [f'  File "x.py", line {k}' for k in
                                                       range(20)] + ["ValueError: bad\x1b[31m"]
    (tmp_path / "out/logs/c_ga.log").write_text("19:00:00 GA: 1 of 8\n" + "\n".join(trace)
                                                + "\njob CPU: 0.370 s\n")
    (tmp_path / "run.log").write_text(SNAKEMAKE_LOG)
    text = run_summary.failure_text([tmp_path / "run.log"], root=tmp_path)
    lines = text.splitlines()
    assert lines[0] == "Job failed: rule c_ga (Paper C: genetic-algorithm tuning)"
    assert lines[1] == "  log: out/logs/c_ga.log"
    assert lines[2] == "    Traceback (most recent call last):"
    assert lines[-3:-1] == ["    ...", "    ValueError: bad\\x1b[31m"]
    assert text.count("Job failed") == 1 and lines[-1].startswith("Snakemake's log of the run")


def test_error_lines_without_a_traceback():
    assert run_summary.error_lines("progress\nsomething went wrong: Error 3\nmore\n") == [
        "something went wrong: Error 3", "more"]
    assert run_summary.error_lines("a\nb\nc", count=2) == ["b", "c"]


def test_a_run_that_failed_outside_a_job_points_to_the_log(tmp_path):
    (tmp_path / "run.log").write_text("Building DAG of jobs...\n")
    assert run_summary.failure_text(tmp_path / "run.log").startswith(
        "The run failed before or between jobs: see ")
