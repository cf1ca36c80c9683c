"""Every way a configuration arrives goes through one guarded entry (rotorvib.pipeline.strict_yaml):
files the checker or the workflow reads, and ``--config`` overrides as Snakemake hands them
over. Each hostile input below is refused with one line naming the file (with line and column)
or the key, within 10 s and 1 GB, with no traceback, hang or signal."""

import os
import resource
import subprocess
import sys
import textwrap

import pytest
import yaml

from conftest import ROOT
from rotorvib.pipeline.config_sources import typed_overrides
from rotorvib.pipeline.strict_yaml import MAX_DEPTH, ConfigError, check_value

LIMIT_BYTES = 1 << 30


def _bounded():
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT_BYTES, LIMIT_BYTES))


def check(*paths) -> subprocess.CompletedProcess:
    """``python -m rotorvib.pipeline.config PATH...`` within 10 s and 1 GB of address space."""
    return subprocess.run([sys.executable, "-m", "rotorvib.pipeline.config", *map(str, paths)],
                          capture_output=True, text=True, timeout=10, cwd=ROOT,
                          preexec_fn=_bounded)


def _files(tmp_path) -> dict:
    made = {}

    def text(name, content):
        made[name] = tmp_path / f"{name}.yaml"
        made[name].write_text(content)

    text("deep", "a: " + "[" * 5000 + "]" * 5000 + "\n")
    text("deeper", "a: " + "[" * 100_000 + "]" * 100_000 + "\n")
    text("deep_blocks", "".join(" " * i + f"k{i}:\n" for i in range(MAX_DEPTH + 2)) + "\n")
    text("self_alias", "a: &a [*a]\n")
    text("self_alias_map", "a: &a {b: *a}\n")
    text("alias_bomb", "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"b{i}: &b{i} [{', '.join([f'*{prev}'] * 9)}]\n"
        for i, prev in enumerate(["a"] + [f"b{i}" for i in range(8)])))
    text("octal", "paper_b:\n  shards: 0777\n")
    text("duplicate", "paper_b:\n  shards: 2\n  shards: 3\n")
    text("template", "__use_yte__: true\n")
    made["directory"] = tmp_path / "folder"
    made["directory"].mkdir()
    made["fifo"] = tmp_path / "fifo"
    os.mkfifo(made["fifo"])
    made["loop"] = tmp_path / "loop"
    made["loop"].symlink_to(made["loop"])
    made["device"] = "/dev/zero"
    made["missing"] = tmp_path / "missing.yaml"
    return made


REFUSALS = {
    "deep": f"deep.yaml:1:{MAX_DEPTH + 3}: nested more than {MAX_DEPTH} levels deep",
    "deeper": f"deeper.yaml:1:{MAX_DEPTH + 3}: nested more than {MAX_DEPTH} levels deep",
    "deep_blocks": f"nested more than {MAX_DEPTH} levels deep",
    "self_alias": "self_alias.yaml:1:8: alias *a inside the value it names",
    "self_alias_map": "self_alias_map.yaml:1:11: alias *a inside the value it names",
    "alias_bomb": "its aliases expand to more than 1e+05 values",
    "octal": "octal.yaml:2:11: '0777' reads differently in YAML 1.1 and 1.2",
    "duplicate": "duplicate.yaml:3:3: duplicate key 'shards'",
    "template": "asks for Snakemake's YTE templates",
    "directory": "folder: not a regular file",
    "fifo": "fifo: not a regular file",
    "loop": "loop: cannot be read (Too many levels of symbolic links)",
    "device": "/dev/zero: not a regular file",
    "missing": "missing.yaml: cannot be read (No such file or directory)",
}


@pytest.mark.parametrize("case", sorted(REFUSALS))
def test_the_checker_refuses_a_hostile_file_in_one_line(tmp_path, case):
    run = check(_files(tmp_path)[case])
    assert run.returncode == 1, run.stderr[-2000:]
    assert REFUSALS[case] in run.stdout and "Traceback" not in run.stdout + run.stderr
    assert len(run.stdout.strip().splitlines()) <= 2


def _as_snakemake_reads(text: str):
    """A ``--config`` value as Snakemake's command line parses it (snakemake.cli.parse_config:
    YAML's base loader, the text itself where that fails)."""
    try:
        return yaml.load(text, Loader=yaml.loader.BaseLoader)
    except Exception:
        return text


@pytest.mark.parametrize("value, refusal", [
    ("{shards: 0777}", "--config paper_b.shards:1:1: '0777' reads differently"),
    ("{shards: yes}", "--config paper_b.shards:1:1: 'yes' reads differently"),
    ("{machine: {zeta: '&a [*a]'}}", "--config paper_b.machine.zeta:1:5: alias *a inside"),
    ("{machine: {zeta: '" + "[" * 200 + "]" * 200 + "'}}",
     f"--config paper_b.machine.zeta:1:{MAX_DEPTH + 1}: nested more than"),
    (textwrap.dedent("""\
        {a: &a [x, x, x, x, x, x, x, x, x], b: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a],
         c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b], d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c],
         e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d], f: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e],
         g: [*f, *f, *f, *f, *f, *f, *f, *f, *f]}"""),
     "e+06 values with its repetitions; at most 1e+05"),   # 9^7 leaves, measured unexpanded
])
def test_a_hostile_command_line_value_is_refused_naming_its_key(value, refusal):
    with pytest.raises(ConfigError) as error:
        typed_overrides({"paper_b": _as_snakemake_reads(value)})
    assert refusal in str(error.value)


def test_a_value_inside_itself_or_too_deep_is_refused_as_built():
    """A module's ``config:`` or Snakemake's reading of ``--config`` is a value already built."""
    looped: list = []
    looped.append(looped)
    with pytest.raises(ConfigError, match="module config: a value inside itself"):
        check_value({"a": looped}, "module config")
    deep: list = []
    for _ in range(MAX_DEPTH + 1):
        deep = [deep]
    with pytest.raises(ConfigError, match=f"nested more than {MAX_DEPTH} levels deep"):
        check_value(deep, "module config")
    shared = ["x"] * 100
    check_value({"a": [shared] * 100}, "fine")       # 10 100 values, each counted


@pytest.mark.parametrize("entries, refusal", [
    (["paper_b.shards=2"], "'paper_b.shards' is not a top-level key; write a nested key as YAML"),
    (["paper_b={shards: 2}", "results/paper_c/figures/fig5.png"],
     "--config 'results/paper_c/figures/fig5.png': not KEY=VALUE; a target written after"),
    (["paper_b={shards: 2, shards: 3}"], "--config paper_b:1:13: duplicate key 'shards'"),
    (["paper_b={shards: 0777}"], "--config paper_b.shards:1:1: '0777' reads differently"),
    (["paper_b={shards: -2}"], "config key 'paper_b.shards': -2 is not allowed"),
])
def test_the_checker_reads_command_line_entries_as_the_workflow_would(entries, refusal):
    """Snakemake stops on a dotted key or a target after ``--config`` with a traceback of its
    own, and keeps a duplicate key's last value; the checker names each."""
    run = subprocess.run([sys.executable, "-m", "rotorvib.pipeline.config", "config/config.yaml",
                          "--config", *entries], capture_output=True, text=True, timeout=10,
                         cwd=ROOT, preexec_fn=_bounded)
    assert run.returncode == 1 and refusal in run.stdout, run.stdout + run.stderr[-2000:]
    assert "Traceback" not in run.stderr
