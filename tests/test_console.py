"""What a person sees on the console: every line short enough to read, the reasons why a job
runs shown only when asked for (the profile's ``quiet: [reason]``; Snakemake's reason lists
every missing or updated file)."""

FRESH = ["-n", "--config", "results=results/console-check"]   # nothing made: every job planned


def _longest(run) -> int:
    return max(len(line) for line in (run.stdout + run.stderr).splitlines())


def test_a_whole_plan_prints_no_line_of_kilobytes(snakemake_here):
    """A dry run of every job into an empty results folder: each job is named by its message,
    no line reaches a thousand characters, and no job's reason is printed."""
    run = snakemake_here(*FRESH)
    assert run.returncode == 0, run.stderr
    assert "Job " in run.stdout and "Reason:" not in run.stdout + run.stderr
    assert _longest(run) < 1000


def test_the_reasons_come_back_when_asked_for(snakemake_here):
    """``--quiet host`` (the user guide's advice) replaces the profile's list: each job's reason
    is printed again, file lists and all."""
    run = snakemake_here(*FRESH, "--quiet", "host")
    assert run.returncode == 0, run.stderr
    assert "Reason: Missing output files:" in run.stdout + run.stderr
    assert _longest(run) > 1000
