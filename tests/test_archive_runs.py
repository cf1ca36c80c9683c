"""What a user keeps from a reduced run (tests/workflow_runs.py): the archive, its RO-Crate
(rocrate-validator) and its restoration without recomputation, and the same archive from two
independent runs."""

import base64
import hashlib
import io
import json
import shlex
import tarfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import yaml

from ro_crate import validate_crate
from rotorvib.pipeline.archive import (
    MANIFEST,
    METADATA_DIR,
    RESTORE_STEPS,
    digest_file,
    sha256_file,
)
from rotorvib.pipeline.archive_restore import main as archive_main
from rotorvib.pipeline.archive_restore import restore_archive, verify_archive
from workflow_runs import (
    REDUCED,
    REDUCED_SHARDED,
    copy_repository,
    copy_run,
    job_records,
    planned_jobs,
    snakemake,
)

pytestmark = pytest.mark.workflow


def test_archive_restores_without_recomputation(run_dir, tmp_path, monkeypatch, capsys):
    """The archive holds the results, the report's words and pages, the run's configuration
    and commit and an RO-Crate that passes rocrate-validator. Its maker can make Snakemake run
    nothing: an altered job record is refused in one line, and an archive whose landing page
    and a caption carry Jinja payloads, restored into a fresh copy by the restore notes' steps,
    reruns nothing but the report's words and pages, rebuilt byte for byte (the archive packed
    again is the original), and the HTML report from it; no payload runs."""
    work = copy_run(run_dir, tmp_path / "work")
    snakemake(work, "-j2", "archive", *REDUCED)
    archive = work / "results/archive/rotorvib-results.tar.gz"
    members = verify_archive(archive)
    assert {"results/paper_c/datasets/ga.nc", "LICENSE", "CITATION.cff", "Snakefile",
            "results/run/config.yaml", "results/run/commit.txt",
            "config/test/config.yaml", "ro-crate-metadata.json"} <= set(members)
    for kind in ("png", "svg", "json"):  # every figure in both formats, with what it draws
        figures = {p.relative_to(work).as_posix()
                   for p in (work / "results").glob(f"paper_*/figures/*.{kind}")}
        assert figures and figures <= set(members), kind
    stored = [data for name, data in _members(archive, links=False).items()
              if name.startswith("results/")]   # the report's copies are links: bytes once
    assert len({hashlib.sha256(data).digest() for data in stored}) == len(stored)
    with tarfile.open(archive) as tar:
        links = {m.name for m in tar.getmembers() if m.islnk()}
    assert {p.relative_to(work).as_posix()
            for p in (work / "results/report").rglob("*.png")} <= links
    assert digest_file(archive).read_text().split()[0] == sha256_file(archive)
    fresh = copy_repository(tmp_path / "fresh")
    marker = tmp_path / "MARKER"
    conda = _altered(archive, tmp_path / "conda.tar.gz", {
        next(n for n in _members(archive) if n.startswith(METADATA_DIR)): lambda data: json.dumps(
            {**json.loads(data), "conda_env": base64.b64encode(
                f"!!python/object/apply:os.system ['touch {marker}']".encode()).decode()}).encode()})
    monkeypatch.chdir(fresh)
    assert archive_main(["restore", str(conda), "--sha256", sha256_file(conda)]) == 1
    assert len(capsys.readouterr().err.splitlines()) == 1 and not (fresh / "results").exists()
    jinja = f"{{{{ self.__init__.__globals__.__builtins__.__import__('os').system('touch {marker}') }}}}"
    texts = ("results/report/landing.rst",
             next(n for n in members if n.startswith("results/report/captions/")))
    hostile = _altered(archive, tmp_path / "hostile.tar.gz",
                       {name: lambda data: data + jinja.encode() for name in texts})
    restored = restore_archive(hostile, sha256_file(hostile), fresh)
    assert "Snakefile" not in restored and "results/paper_c/datasets/ga.nc" in restored
    assert not [name for name in restored if name.startswith("results/report/")]
    touch, rebuild = (shlex.split(step)[1:] for step in RESTORE_STEPS.split(" && "))
    snakemake(fresh, *touch, *REDUCED)
    assert planned_jobs(snakemake(fresh, *rebuild, *REDUCED)) == {
        "report_text", "report_results", "all"}
    with ThreadPoolExecutor(1) as pool:      # the validator works while Snakemake reports
        issues = pool.submit(validate_crate, fresh, tmp_path / "cache")
        assert planned_jobs(snakemake(fresh, "-n", *REDUCED)) == set()
        snakemake(fresh, "--report", "results/report.html", *REDUCED)   # rebuilt from it
        assert "Verdict totals" in (fresh / "results/report.html").read_text(errors="replace")
        rebuilt = snakemake(fresh, "-j1", "archive", *REDUCED)       # and the archive, again
        assert planned_jobs(rebuilt) == {"archive"}
        assert (fresh / archive.relative_to(work)).read_bytes() == archive.read_bytes()
    assert not marker.exists()
    assert [message for _, message, _ in issues.result()] == [
        "The Root Data Entity SHOULD have a `publisher` property (Organization or Person)"]


def _altered(archive: Path, path: Path, changes) -> Path:
    """``archive`` with the bytes of the members named in ``changes`` (name -> function of the
    bytes) changed and its manifest recomputed, as its maker would, who publishes its digest."""
    with tarfile.open(archive) as tar:
        members = [(m, tar.extractfile(m).read() if m.isfile() else None)
                   for m in tar.getmembers()]
    members = [(m, changes[m.name](data) if m.name in changes else data) for m, data in members]
    data_of = {m.name: data for m, data in members}
    data_of[MANIFEST] = "".join(
        f"{hashlib.sha256(data_of[name]).hexdigest() if name in changes else digest}  {name}\n"
        for digest, name in (line.split("  ", 1)
                             for line in data_of[MANIFEST].decode().splitlines())).encode()
    with tarfile.open(path, "w:gz", format=tarfile.PAX_FORMAT) as tar:
        for member, data in members:
            data = data_of[member.name]
            if data is not None:
                member.size = len(data)
            tar.addfile(member, io.BytesIO(data) if data is not None else None)
    return path


def _members(archive: Path, links: bool = True) -> dict[str, bytes]:
    """Each member's bytes; a hard link's are its target's (``links``), else it is left out."""
    with tarfile.open(archive) as tar:
        return {m.name: tar.extractfile(m).read() for m in tar.getmembers()
                if m.isfile() or (links and m.islnk())}


def test_two_runs_pack_the_same_archive_but_for_the_split(runs, tmp_path):
    """The session's two independent runs (same commit, jobs run at different times, the
    second with paper B's batch studies in three shards) each pack their archive. Every member
    is the same byte for byte, job records included (their run times left out), but those that
    say how the second was split: its configuration (paper_b.shards, and the file that sets
    it), the records of the studies gathered from shards (their inputs), of the run's
    configuration files (their parameters), and the crate, manifest and README that list
    them. The first, packed again later, is the same file byte for byte."""
    archives = []
    for i, (run, config) in enumerate(zip(runs, (REDUCED, REDUCED_SHARDED))):
        work = copy_run(run, tmp_path / f"build{i}")
        snakemake(work, "-j2", "archive", *config)
        archives.append(_members(work / "results/archive/rotorvib-results.tar.gz"))
    packed = tmp_path / "build0/results/archive/rotorvib-results.tar.gz"
    first = packed.read_bytes()
    again = snakemake(tmp_path / "build0", "-j1", "-f", "archive", *REDUCED)
    assert planned_jobs(again) == {"archive"} and packed.read_bytes() == first
    one, split = archives
    assert set(split) - set(one) == {REDUCED_SHARDED[-1]} and set(one) <= set(split)
    records = {name for name in one if name.startswith(METADATA_DIR)}
    assert len(records) > 100
    differ = {name for name in one if one[name] != split[name]}
    assert differ - records == {"results/run/config.yaml", "ro-crate-metadata.json",
                                "results/ARCHIVE_MANIFEST.sha256", "results/ARCHIVE_README.md"}
    configs = [yaml.safe_load(members["results/run/config.yaml"]) for members in archives]
    assert [c["paper_b"].pop("shards") for c in configs] == [1, 3] and configs[0] == configs[1]
    changed = {}
    for name in differ & records:
        fields = [json.loads(members[name]) for members in archives]
        path = base64.urlsafe_b64decode(name.rsplit("/", 1)[1]).decode()
        changed[path] = {key for key in fields[0] if fields[0][key] != fields[1].get(key)}
    gathered = {r["output"][0] for r in job_records(runs[1])
                if any("/shards/" in f for f in r["input"])}
    assert len(gathered) == 10
    assert changed == {**{path: {"input", "input_checksums"} for path in gathered},
                       "results/run/commit.txt": {"params"},
                       "results/run/config.yaml": {"params"}}
