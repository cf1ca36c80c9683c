"""What a run says when it ends (the Snakefile's ``onsuccess:`` and ``onerror:``).

After a run that succeeded, :func:`success_text`: where the comparison with the papers, the
analysis of the misses, the figures, tables, datasets and job logs are (those the run's folder
holds), the papers the configuration left out, and the command that builds the report for
this configuration. After a run that failed, :func:`failure_text`: each job that failed, read
from Snakemake's log of the run, with its log and the first lines of its error, each line
escaped as a log line is (:func:`rotorvib.io.progress.one_line`).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

from rotorvib.io.progress import one_line

#: Lines of a failed job's error shown (its log holds the rest).
ERROR_LINES = 8

_PAPER_FOLDERS = (("figures", "figures (PNG and SVG)"), ("tables", "tables"),
                  ("datasets", "datasets (netCDF)"))


def report_command(results: str, configfiles=(), config_args=(), elsewhere=None) -> str:
    """The command that builds the report of a run of ``results`` (folder) made with the
    ``--configfile`` files ``configfiles`` and the ``--config`` entries ``config_args``.

    ``elsewhere``, for a run whose working folder is not the workflow's own (a module's caller,
    ``--directory``): ``(working folder, the workflow's stylesheet)``. The command then names
    both: the folder, so that it runs where the results are, whichever folder the user is in,
    and the stylesheet and configuration files, by their absolute paths (Snakemake finds the
    default profile, and the stylesheet it names, from the folder the command starts in, not
    the working folder)."""
    words = ["snakemake", "--report", f"{results}/report.html"]
    if elsewhere is not None:
        folder, stylesheet = elsewhere
        words += ["--directory", str(folder)]
        if Path(stylesheet).is_file():
            words += ["--report-stylesheet", str(stylesheet)]
    if configfiles:
        named = _relative if elsewhere is None else (lambda path: str(Path(path).resolve()))
        words += ["--configfile", *map(named, configfiles)]
    if config_args:
        words += ["--config", *config_args]
    return shlex.join(words)


def left_out(papers, schema: dict) -> list[str]:
    """The papers whose sections (``paper_<p>``) the configuration's ``schema`` declares that
    ``papers`` (those of the run) leaves out."""
    declared = {key.removeprefix("paper_") for key in schema["properties"]
                if key.startswith("paper_")}
    return sorted(declared - set(papers))


def _relative(path) -> str:
    """``path`` relative to the working directory where it lies under it, else as given."""
    try:
        return str(Path(path).resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


def success_text(results: str, papers, left_out=(), configfiles=(), config_args=(),
                 root: str | Path = ".", elsewhere=None) -> str:
    """The closing lines of a run that succeeded: what the folder ``results`` (relative to
    ``root``, the working directory) holds of the papers ``papers`` ("a", "b", "c"), the
    papers the configuration ``left_out`` and how to build the report (:func:`report_command`,
    given ``elsewhere``)."""
    base = Path(root)
    lines = ["Where the results are:"]
    found = [(f"{results}/{name}", what) for name, what in (
        ("comparison.md", "the papers' values and claims beside ours, with verdicts"),
        ("discrepancies.md", "each number missed, analysed")) if (base / results / name).exists()]
    for folder, what in _PAPER_FOLDERS:
        held = [f"{results}/paper_{p}/{folder}/" for p in sorted(papers)
                if (base / results / f"paper_{p}" / folder).is_dir()]
        if held:
            found.append((", ".join(held), what))
    if (base / results / "logs").is_dir():
        found.append((f"{results}/logs/", "each job's log"))
    lines += [f"  {one_line(path)}  {what}" for path, what in found] or [
        f"  nothing yet under {one_line(results)}/"]
    if left_out:
        lines.append("Left out by this configuration (key 'papers'): "
                     + ", ".join(f"paper {p.upper()}" for p in sorted(left_out)))
    lines.append("Build the report, then open it in a browser:")
    lines.append("  " + one_line(report_command(results, configfiles, config_args, elsewhere)))
    return "\n".join(lines)


#: The CPU line a job's log ends with (rotorvib.pipeline.job.CPU_LINE), which is no error.
_CPU_LINE = re.compile(r"^job CPU: [0-9.]+ s$")
_ERROR = re.compile(r"^Error in rule (\S+?):\n((?:[ \t]+\S.*\n?)*)", re.MULTILINE)
_LOG = re.compile(r"^[ \t]+log: (.+?) \(check log file", re.MULTILINE)
_MESSAGE = re.compile(r"^[ \t]+message: (.+)$", re.MULTILINE)


def failed_jobs(snakemake_log: str) -> list[dict]:
    """The jobs that failed, as the text of Snakemake's log of a run names them: each as
    ``{"rule", "message", "logs"}``, in the order they failed, each job once."""
    jobs, seen = [], set()
    for rule, details in _ERROR.findall(snakemake_log):
        logs = _LOG.search(details)
        message = _MESSAGE.search(details)
        said = message.group(1) if message else ""
        job = {"rule": rule, "message": "" if said == "None" else said,
               "logs": logs.group(1).split(", ") if logs else []}
        if (key := (rule, tuple(job["logs"]))) not in seen:
            seen.add(key)
            jobs.append(job)
    return jobs


def error_lines(log_text: str, count: int = ERROR_LINES) -> list[str]:
    """The first ``count`` lines of the error a job's log ends with: from its traceback's
    first line (or, without one, the first line that names an error), its last line (the
    exception) after them where they stop short of it; the log's last lines if neither."""
    lines = [line for line in log_text.splitlines()
             if line.strip() and not _CPU_LINE.match(line)]
    start = next((i for i, line in enumerate(lines) if line.startswith("Traceback")), None)
    if start is None:
        start = next((i for i, line in enumerate(lines)
                      if re.search(r"error|exception", line, re.IGNORECASE)), None)
    if start is None:
        return [one_line(line) for line in lines[-count:]]
    shown = lines[start:start + count]
    if start + count < len(lines):
        shown += ["...", lines[-1]]
    return [one_line(line) for line in shown]


def failure_text(snakemake_logs, root: str | Path = ".") -> str:
    """The closing lines of a run that failed: each failed job (:func:`failed_jobs`) of
    Snakemake's log of the run ``snakemake_logs`` (a path, or the list of paths Snakemake
    hands ``onerror``), its log (relative to ``root``, the working directory) and the first
    lines of its error (:func:`error_lines`)."""
    paths = [Path(snakemake_logs)] if isinstance(snakemake_logs, (str, Path)) else [
        Path(p) for p in snakemake_logs]
    text = "".join(p.read_text(encoding="utf-8", errors="replace") for p in paths if p.is_file())
    where = ", ".join(one_line(str(p)) for p in paths) or "Snakemake's output above"
    jobs = failed_jobs(text)
    if not jobs:
        return f"The run failed before or between jobs: see {where}"
    lines = []
    for job in jobs:
        what = f" ({one_line(job['message'])})" if job["message"] else ""
        lines.append(f"Job failed: rule {one_line(job['rule'])}{what}")
        for log in job["logs"]:
            lines.append(f"  log: {one_line(log)}")
            log_path = Path(root) / log
            if log_path.is_file():
                error = error_lines(log_path.read_text(encoding="utf-8", errors="replace"))
                lines += [f"    {line}" for line in error] or ["    (the log is empty)"]
            else:
                lines.append("    (no log was written)")
    lines.append(f"Snakemake's log of the run: {where}")
    return "\n".join(lines)
