"""Hostile archives against the restore (rotorvib.pipeline.archive_restore): job records and
report texts that would run code under Snakemake, bombs against its bounds, and failures of
its move phase, which must leave the clone as it was. Each archive is crafted in tmp_path, its
digest published by its maker (as anyone sharing an archive does)."""

import base64
import errno
import gzip
import hashlib
import io
import json
import os
import tarfile
import tracemalloc
from pathlib import Path
from types import SimpleNamespace

import pytest
from snakemake.persistence.file import FilePersistence

from rotorvib.pipeline import archive_restore
from rotorvib.pipeline.archive import (
    MANIFEST,
    METADATA_DIR,
    RESTORE_NOTES,
    RESTORE_STEPS,
    job_records,
    make_archive,
    record_path,
    sha256_file,
)
from rotorvib.pipeline.archive_restore import main as archive_main
from rotorvib.pipeline.archive_restore import restore_archive, verify_archive

JINJA = "{{ self.__init__.__globals__.__builtins__.__import__('os').system('touch MARKER') }}"
CONDA = base64.b64encode(b"!!python/object/apply:os.system ['touch MARKER']").decode()
#: A job record as the archive stores one (run times set to 0).
RECORD = {"rule": "figures", "input": ["results/a.nc"], "log": ["results/logs/f.log"],
          "shellcmd": None, "params": ["'abc'"], "code": "  script: f.py\n",
          "record_format_version": 6, "conda_env": None, "container_img_url": None,
          "software_stack_hash": "d41d8cd98f00b204e9800998ecf8427e", "job_hash": 0,
          "starttime": 0, "endtime": 0, "incomplete": False, "external_jobid": None,
          "input_checksums": {"results/a.nc": "sha256:00"}}


def _crafted(path, members):
    """A gzip tar of ``members`` (TarInfo, bytes or None) with a manifest of their bytes (a
    hard link's are its target's) recomputed, as an attacker would."""
    digests = {}
    for info, data in members:
        if info.isfile():
            digests[info.name] = hashlib.sha256(data).hexdigest()
        elif info.islnk():
            digests[info.name] = digests[info.linkname]
    lines = "".join(f"{d}  {n}\n" for n, d in digests.items()).encode()
    with tarfile.open(path, "w:gz", format=tarfile.PAX_FORMAT) as tar:
        for info, data in members:
            tar.addfile(info, io.BytesIO(data) if data is not None else None)
        info = tarfile.TarInfo(MANIFEST)
        info.size = len(lines)
        tar.addfile(info, io.BytesIO(lines))
    return path


def _file(name, data=b"x"):
    info = tarfile.TarInfo(name)
    info.size = len(data)
    return info, data


def _link(name, target):
    info = tarfile.TarInfo(name)
    info.type, info.linkname = tarfile.LNKTYPE, target
    return info, None


def _record(output, **changes):
    data = json.dumps({**RECORD, **changes}).encode()
    return _file(record_path(output, 255), data)


def _tree(root: Path) -> dict[str, bytes | None]:
    """Every path under ``root``: a file's bytes, None for a folder or link."""
    return {p.relative_to(root).as_posix(): p.read_bytes() if p.is_file() and not p.is_symlink()
            else None for p in sorted(root.rglob("*"))}


def _refused(archive, root, capsys, *words):
    """Run the restore command in ``root``: it exits 1 with one line on stderr, with ``words``;
    return that line."""
    cwd = os.getcwd()
    os.chdir(root)
    try:
        status = archive_main(["restore", str(archive), "--sha256", sha256_file(archive)])
    finally:
        os.chdir(cwd)
    out, err = capsys.readouterr()
    assert status == 1 and out == "" and len(err.splitlines()) == 1, err
    assert err.startswith("refused: ") and all(w in err for w in words), err
    return err


RECORDS = {   # a job record as an attacker would write it -> what the refusal says
    "conda_env payload": ({"conda_env": CONDA}, "['conda_env']"),
    "shell command": ({"shellcmd": "touch MARKER"}, "['shellcmd']"),
    "container": ({"container_img_url": "docker://evil"}, "['container_img_url']"),
    "rule name markup": ({"rule": "<script>"}, "['rule']"),
    "incomplete": ({"incomplete": True}, "['incomplete']"),
    "extra key": ({"extra": 1}, "keys that differ: ['extra']"),
}


@pytest.mark.parametrize("kind", sorted(RECORDS))
def test_a_job_record_not_as_snakemake_writes_it_is_refused(tmp_path, capsys, kind):
    """A record with a conda environment (which Snakemake's report loads with an unsafe YAML
    loader), a shell command, a container or any field or key the workflow never writes is
    refused in one line naming the member and the field, and nothing is written."""
    changes, words = RECORDS[kind]
    archive = _crafted(tmp_path / "r.tar.gz", [_file("results/a.nc"),
                                               _record("results/a.nc", **changes)])
    root = tmp_path / "clone"
    root.mkdir()
    line = _refused(archive, root, capsys, "the job record of results/a.nc", words)
    assert METADATA_DIR in line
    assert _tree(root) == {} and not (root / "MARKER").exists()


@pytest.mark.parametrize("name", [f"{METADATA_DIR}/not base64", f"{METADATA_DIR}/TElDRU5TRQ==",
                                  f"{METADATA_DIR}/@cmVzdWx0cy9hLm5j"])
def test_a_job_record_of_no_results_file_is_refused(tmp_path, name):
    """A member under the records' folder must be named as Snakemake names the record of a
    file of results/ (here: not base64, the record of LICENSE, a folder without its last part)."""
    archive = _crafted(tmp_path / "r.tar.gz", [_file(name, json.dumps(RECORD).encode())])
    with pytest.raises(ValueError, match="is not named as the job record of a file of results/"):
        verify_archive(archive, sha256_file(archive))


def test_the_report_texts_are_never_restored(tmp_path, monkeypatch, capsys):
    """The landing page and captions (which Snakemake renders as Jinja templates) and the rest
    of results/report/, with their job records, are left out; the restore says so and what to
    run, which rebuilds them. The results and their records are restored."""
    texts = ["results/report/landing.rst", "results/report/captions/figures/a_fig2.rst",
             "results/report/pages/summary.html"]
    members = [_file("results/a.nc"), _record("results/a.nc")] + [
        _file(name, JINJA.encode()) for name in texts] + [_record(name) for name in texts]
    archive = _crafted(tmp_path / "r.tar.gz", members)
    root = tmp_path / "clone"
    root.mkdir()
    monkeypatch.chdir(root)
    assert archive_main(["restore", str(archive), "--sha256", sha256_file(archive)]) == 0
    out = capsys.readouterr().out
    assert out == (f"restored 2 files (results/report/ left out: its texts are rebuilt, not "
                   f"restored); now run: {RESTORE_STEPS}\n")
    assert set(_tree(root)) == {"results", "results/a.nc", ".snakemake", METADATA_DIR,
                                record_path("results/a.nc", 255)}


def test_a_link_to_a_report_file_left_out_is_restored(tmp_path):
    """A results file stored as a link to a file of results/report/ (which the restore leaves
    out) is still restored, with its bytes."""
    archive = _crafted(tmp_path / "r.tar.gz", [
        _file("results/report/pages/a.html", b"<p>a</p>"),
        _link("results/paper_a/a.html", "results/report/pages/a.html")])
    root = tmp_path / "clone"
    root.mkdir()
    assert restore_archive(archive, sha256_file(archive), root) == ["results/paper_a/a.html"]
    assert (root / "results/paper_a/a.html").read_bytes() == b"<p>a</p>"


def test_the_restore_notes_give_the_steps_the_restore_prints():
    for step in RESTORE_STEPS.split(" && "):
        assert f"\n    {step} " in RESTORE_NOTES


def test_a_hard_link_counts_its_targets_bytes(tmp_path, monkeypatch):
    """1000 hard links to a 64 KiB file: a 10 kB archive that would write 65.6 MB. Each link
    counts its target's bytes, so a bound of 1 MiB refuses it at the 16th link, and nothing
    is written to the clone."""
    monkeypatch.setattr(archive_restore, "MAX_TOTAL_BYTES", 1 << 20)
    members = [_file("results/a.bin", b"\0" * (64 << 10))] + [
        _link(f"results/l{i:04d}", "results/a.bin") for i in range(1000)]
    archive = _crafted(tmp_path / "bomb.tar.gz", members)
    assert archive.stat().st_size < 12_000
    root = tmp_path / "clone"
    root.mkdir()
    with pytest.raises(ValueError, match=r"member 'results/l0015': more than 100000 members or "
                                         r"1048576 bytes \(hard links count their target's\)"):
        restore_archive(archive, sha256_file(archive), root)
    assert _tree(root) == {}


@pytest.mark.parametrize("kind", [tarfile.XHDTYPE, tarfile.XGLTYPE, tarfile.GNUTYPE_LONGNAME,
                                  tarfile.GNUTYPE_LONGLINK])
def test_an_extended_header_is_bounded_before_it_is_read(tmp_path, kind):
    """A pax header or GNU long name announcing 16 MiB (tarfile reads it whole: a 1 MB archive
    of one took 1.07 GB) is refused from its header: the check allocates under 1 MiB."""
    info = tarfile.TarInfo("././@LongLink")
    info.type, info.size = kind, 16 << 20
    path = tmp_path / "long.tar.gz"
    with gzip.open(path, "wb") as gz:
        gz.write(info.tobuf(tarfile.USTAR_FORMAT) + b"\0" * (16 << 20))
    tracemalloc.start()
    try:
        with pytest.raises(ValueError, match="an extended header of 16777216 bytes, over the "
                                             "bound of 65536"):
            verify_archive(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1 << 20


def test_extended_headers_in_a_row_and_sparse_files_are_refused(tmp_path):
    """Four pax headers in a row (tarfile reads a chain by recursion) and a GNU sparse member
    (whose map tarfile reads unbounded) are refused from their headers."""
    pax = tarfile.TarInfo("././@PaxHeader")
    pax.type = tarfile.XHDTYPE
    record = b"11 path=ab\n"
    pax.size = len(record)
    chain = (pax.tobuf(tarfile.USTAR_FORMAT) + record + b"\0" * (512 - len(record))) * 4
    sparse = tarfile.TarInfo("results/s")
    sparse.type = tarfile.GNUTYPE_SPARSE
    for name, data, words in [("chain", chain, "more than 3 extended headers in a row"),
                              ("sparse", sparse.tobuf(tarfile.GNU_FORMAT), "is a sparse file")]:
        path = tmp_path / f"{name}.tar.gz"
        path.write_bytes(gzip.compress(data + b"\0" * 1024))
        with pytest.raises(ValueError, match=words):
            verify_archive(path)


def test_the_digest_is_checked_before_anything_is_staged(tmp_path, monkeypatch):
    """An archive that is not the published one is refused before its first member is read:
    nothing is staged (20 MiB were, before)."""
    archive = _crafted(tmp_path / "r.tar.gz", [_file(f"results/f{i}.bin", os.urandom(1 << 20))
                                               for i in range(20)])
    monkeypatch.setattr(archive_restore, "CheckedTarStream", None)   # any read of a member fails
    root = tmp_path / "clone"
    root.mkdir()
    with pytest.raises(ValueError, match="not the published archive"):
        restore_archive(archive, "0" * 64, root)
    assert _tree(root) == {}


def test_only_the_crates_exact_name_is_restored_at_the_root(tmp_path):
    archive = _crafted(tmp_path / "r.tar.gz", [
        _file("results/a"), _file("ro-crate-metadata.json", b"{}"),
        _file("ro-crate-metadata.json.evil"), _file("ro-crate-metadata.jsonx/y")])
    root = tmp_path / "clone"
    root.mkdir()
    assert restore_archive(archive, sha256_file(archive), root) == [
        "results/a", "ro-crate-metadata.json"]
    assert sorted(_tree(root)) == ["results", "results/a", "ro-crate-metadata.json"]


def _six_hundred(tmp_path):
    """An archive of 600 results files, and a clone holding an older copy of one of them."""
    archive = _crafted(tmp_path / "m.tar.gz", [_file(f"results/d{i:03d}/f.txt", b"new")
                                               for i in range(600)])
    root = tmp_path / "clone"
    (root / "results/d100").mkdir(parents=True)
    (root / "results/d100/f.txt").write_bytes(b"old")
    return archive, root


def _obstacle(tmp_path, obstacle: str):
    """The six-hundred-file archive and its clone, with ``obstacle`` at ``results/d300``: a
    folder where a file goes, or a symbolic link on the way or in a file's place, to a folder
    ``elsewhere``; ``(archive, root, elsewhere)``."""
    archive, root = _six_hundred(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    if obstacle == "folder":
        (root / "results/d300/f.txt").mkdir(parents=True)
    elif obstacle == "link on the way":
        (root / "results/d300").symlink_to(elsewhere)
    else:
        (root / "results/d300").mkdir()
        (root / "results/d300/f.txt").symlink_to(elsewhere / "f.txt")
    return archive, root, elsewhere


@pytest.mark.parametrize("obstacle", ["folder", "link on the way", "link in place"])
def test_an_obstacle_in_the_clone_is_found_before_the_first_move(tmp_path, capsys, obstacle):
    """A folder where a file goes, or a symbolic link on the way or in a file's place (the
    audit: 503-543 files left, tracebacks): refused in one line naming it; nothing moves."""
    archive, root, elsewhere = _obstacle(tmp_path, obstacle)
    before = _tree(root)
    _refused(archive, root, capsys, str(root / "results/d300"))
    assert _tree(root) == before and _tree(elsewhere) == {}


@pytest.mark.parametrize("raced", ["link on the way", "link in place"])
def test_a_link_raced_in_after_the_checks_is_never_followed(tmp_path, capsys, monkeypatch,
                                                            raced):
    """A link put on the way, or in a file's place, between the checks and the moves (the
    checks are skipped here, as a racer would win): the moves open each folder without
    following a link, so the link is refused or replaced, never written through; undone."""
    archive, root, elsewhere = _obstacle(tmp_path, raced)
    monkeypatch.setattr(archive_restore, "_destination_problem", lambda root, relative: None)
    before = _tree(root)
    _refused(archive, root, capsys, str(root / "results/d300"), "the clone is as it was")
    assert _tree(root) == before and _tree(elsewhere) == {}


@pytest.mark.parametrize("failure", [errno.ENOSPC, errno.EXDEV])
def test_a_failed_move_is_undone(tmp_path, capsys, monkeypatch, failure):
    """The 300th move fails (a full disk, another file system raced in): the 299 files moved
    are removed with the folders made for them, the file replaced comes back, and the refusal
    is one line."""
    archive, root = _six_hundred(tmp_path)
    before = _tree(root)
    replace, moves = os.replace, []

    def failing(source, target, **folders):
        if ".restore-" in str(source) and ".replaced" not in str(source):
            moves.append(target)
            if len(moves) == 300:
                raise OSError(failure, os.strerror(failure))
        return replace(source, target, **folders)

    monkeypatch.setattr(os, "replace", failing)
    _refused(archive, root, capsys, "results/d299/f.txt: ", os.strerror(failure),
             "the clone is as it was")
    assert _tree(root) == before


def test_a_restore_that_would_fill_the_disk_is_refused_before_staging(tmp_path, monkeypatch):
    archive, root = _six_hundred(tmp_path)
    before = _tree(root)
    monkeypatch.setattr(archive_restore.shutil, "disk_usage",
                        lambda path: SimpleNamespace(free=10 << 20))
    with pytest.raises(ValueError, match="member 'results/d000/f.txt': 3 bytes would leave "
                                         "less than 67108864 bytes free"):
        restore_archive(archive, sha256_file(archive), root)
    assert _tree(root) == before


def test_a_long_results_path_is_archived_and_restored_where_snakemake_reads_it(
        tmp_path, monkeypatch):
    """A results file whose path takes more than 255 characters in base64 (a results folder of
    170 characters): its job record is where Snakemake keeps it (a folder per 254 characters),
    archived (it crashed the archive job, ENAMETOOLONG) and restored there."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    output = f"results/{'d' * 170}/paper_c/datasets/ga.nc"
    snakemakes = FilePersistence._record_path(SimpleNamespace(_fetch_max_len=lambda _: 255),
                                              METADATA_DIR, output)
    assert snakemakes == record_path(output, 255) and snakemakes.count("/@") == 1
    Path(output).parent.mkdir(parents=True)
    Path(output).write_text("x\n")
    Path(snakemakes).parent.mkdir(parents=True)
    Path(snakemakes).write_text(json.dumps(RECORD))
    assert job_records([output]) == [snakemakes]
    archive = make_archive([output], "r.tar.gz")
    root = tmp_path / "clone"
    root.mkdir()
    assert restore_archive(archive, sha256_file(archive), root) == [snakemakes, output]
    assert json.loads((root / snakemakes).read_text()) == RECORD

