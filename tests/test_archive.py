import gzip
import hashlib
import io
import os
import tarfile
import time
from pathlib import Path

import pytest

from rotorvib.pipeline.archive import MANIFEST, README, make_archive, sha256_file
from rotorvib.pipeline.archive_restore import main as archive_main
from rotorvib.pipeline.archive_restore import restore_archive, verify_archive


def test_archive_round_trip_and_corruption(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "results").mkdir()
    (tmp_path / "results/a.csv").write_text("x,y\n1,2\n")
    (tmp_path / "results/b.txt").write_text("hello")
    out = make_archive(["results/b.txt", "results/a.csv"], "results/archive/r.tar.gz")
    assert verify_archive(out) == ["results/a.csv", "results/b.txt"]
    with tarfile.open(out) as tar:
        names = tar.getnames()
        manifest = tar.extractfile(MANIFEST).read().decode()
    assert README in names
    assert f"{sha256_file('results/a.csv')}  results/a.csv" in manifest
    # a tampered member is detected
    bad = tmp_path / "bad.tar.gz"
    with tarfile.open(out) as src, tarfile.open(bad, "w:gz") as dst:
        for member in src.getmembers():
            data = src.extractfile(member).read()
            if member.name == "results/a.csv":
                data = b"x,y\n1,3\n"
            member.size = len(data)
            dst.addfile(member, io.BytesIO(data))
    with pytest.raises(ValueError, match="does not match"):
        verify_archive(bad)


def test_the_same_files_give_a_byte_identical_archive(tmp_path, monkeypatch):
    """Touching a file, or building at another path, changes nothing; its bytes do."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    (tmp_path / "results").mkdir()
    (tmp_path / "results/a.csv").write_text("x,y\n1,2\n")
    first = make_archive(["results/a.csv"], "one/r.tar.gz").read_bytes()
    os.utime("results/a.csv", (1e9, 1e9))
    assert make_archive(["results/a.csv"], "two/other.tar.gz").read_bytes() == first
    (tmp_path / "results/a.csv").write_text("x,y\n1,3\n")
    assert make_archive(["results/a.csv"], "three/r.tar.gz").read_bytes() != first


def test_a_copy_is_stored_once_and_restored_as_a_file(tmp_path, monkeypatch):
    """A results file with the bytes of an earlier one (the report's copy of a figure) is a
    hard link in the archive: the archive grows by a header, not by the file; a restore
    writes a copy outside results/report/ as a file of its own, with the same bytes, and
    leaves the report's copy out (rebuilt, never restored)."""
    monkeypatch.chdir(tmp_path)
    figure = os.urandom(50_000)     # incompressible: a copy stored whole would double it
    names = ("results/paper_a/figures/f.png", "results/paper_b/figures/f.png",
             "results/report/shown/f.png")
    for name in names:
        Path(name).parent.mkdir(parents=True, exist_ok=True)
        Path(name).write_bytes(figure)
    once = make_archive(names[:1], "one.tar.gz").stat().st_size
    out = make_archive(names, "all.tar.gz")
    assert out.stat().st_size - once < 4_000
    with tarfile.open(out) as tar:
        for name in names[1:]:
            link = tar.getmember(name)
            assert link.islnk() and link.linkname == names[0]
    root = tmp_path / "clone"
    root.mkdir()
    assert restore_archive(out, sha256_file(out), root) == list(names[:2])
    copy = root / names[1]
    assert copy.read_bytes() == figure and copy.stat().st_nlink == 1
    assert not (root / "results/report").exists()


@pytest.mark.parametrize("damage", ["truncate", "garbage", "empty", "no_manifest"])
def test_a_damaged_archive_raises_value_error(tmp_path, monkeypatch, damage):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "results").mkdir()
    (tmp_path / "results/a.csv").write_text("x,y\n" + "1,2\n" * 5000)
    out = make_archive(["results/a.csv"], "r.tar.gz")
    data = out.read_bytes()
    if damage == "no_manifest":
        with tarfile.open(out, "w:gz") as tar:
            tar.add("results/a.csv")
    else:
        out.write_bytes({"truncate": data[: len(data) // 2], "garbage": b"not an archive",
                         "empty": b""}[damage])
    with pytest.raises(ValueError, match="not a complete rotorvib archive"):
        verify_archive(out)


def test_generated_members_are_in_the_manifest(tmp_path, monkeypatch):
    """A member written from text (the RO-Crate) is checked like a file."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "results").mkdir()
    (tmp_path / "results/a.csv").write_text("x\n")
    out = make_archive(["results/a.csv"], "r.tar.gz", generated={"ro-crate-metadata.json": "{}"})
    assert verify_archive(out) == ["results/a.csv", "ro-crate-metadata.json"]
    with tarfile.open(out) as tar:
        assert tar.extractfile("ro-crate-metadata.json").read() == b"{}"
        assert "2 files" in tar.extractfile(README).read().decode()


def _built(tmp_path, monkeypatch):
    """An archive of two results, the Snakefile and a job record, as the rule builds it."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "results").mkdir()
    (tmp_path / "results/a.csv").write_text("x,y\n1,2\n")
    (tmp_path / "Snakefile").write_text("rule all:\n    input: []\n")
    return make_archive(["results/a.csv", "Snakefile"], "out/r.tar.gz")


def _crafted(path, members, manifest=True):
    """A gzip tar of ``members`` (TarInfo, bytes or None), with a manifest of their bytes
    recomputed (as an attacker would) unless ``manifest`` is False."""
    lines = "".join(f"{hashlib.sha256(data or b'').hexdigest()}  {info.name}\n"
                    for info, data in members if info.isfile() and info.name != README)
    with tarfile.open(path, "w:gz", format=tarfile.PAX_FORMAT) as tar:
        for info, data in members:
            tar.addfile(info, io.BytesIO(data) if data is not None else None)
        if manifest:
            info = tarfile.TarInfo(MANIFEST)
            info.size = len(lines.encode())
            tar.addfile(info, io.BytesIO(lines.encode()))
    return path


def _file(name, data=b"x", mode=0o644):
    info = tarfile.TarInfo(name)
    info.size, info.mode = len(data), mode
    return info, data


def _special(name, kind, target=""):
    info = tarfile.TarInfo(name)
    info.type, info.linkname = kind, target
    return info, None


CRAFTED = {
    "parent traversal": [_file("results/../../escaped.txt")],
    "absolute path": [_file("/tmp/rotorvib-absolute.txt")],
    "dot component": [_file("results/./a.csv")],
    "symbolic link": [_special("results/link", tarfile.SYMTYPE, "/etc/passwd")],
    "hard link": [_special("results/hard", tarfile.LNKTYPE, "/etc/passwd")],
    "hard link to a later member": [_special("results/hard", tarfile.LNKTYPE, "results/z.csv"),
                                    _file("results/z.csv")],
    "hard link outside results": [_file("LICENSE"),
                                  _special("results/hard", tarfile.LNKTYPE, "LICENSE")],
    "character device": [_special("results/tty", tarfile.CHRTYPE)],
    "block device": [_special("results/disk", tarfile.BLKTYPE)],
    "fifo": [_special("results/fifo", tarfile.FIFOTYPE)],
    "directory": [_special("results/dir", tarfile.DIRTYPE)],
    "setuid bit": [_file("results/tool", b"#!/bin/sh\n", mode=0o4755)],
    "setgid bit": [_file("results/tool", b"#!/bin/sh\n", mode=0o2755)],
    "duplicate member": [_file("results/a.csv"), _file("results/a.csv", b"y")],
}


@pytest.mark.parametrize("kind", sorted(CRAFTED))
def test_a_crafted_member_is_refused_before_anything_is_written(tmp_path, monkeypatch, kind):
    monkeypatch.chdir(tmp_path)
    archive = _crafted(tmp_path / "bad.tar.gz", CRAFTED[kind])
    digest = sha256_file(archive)
    root = tmp_path / "clone"
    root.mkdir()
    with pytest.raises(ValueError, match="member"):
        verify_archive(archive, digest)
    with pytest.raises(ValueError, match="member"):
        restore_archive(archive, digest, root)
    assert list(root.iterdir()) == [] and not (tmp_path / "escaped.txt").exists()


def test_a_huge_member_is_refused_by_its_header_without_reading_it(tmp_path):
    """A header that announces 3 GiB: refused from the header in well under a second, without
    reading (or holding) the member."""
    info = tarfile.TarInfo("results/huge.nc")
    info.size = 3 << 30
    path = tmp_path / "huge.tar.gz"
    with gzip.open(path, "wb") as gz:
        gz.write(info.tobuf(tarfile.PAX_FORMAT) + b"\0" * 4096)
    start = time.perf_counter()
    with pytest.raises(ValueError, match="larger than"):
        verify_archive(path)
    assert time.perf_counter() - start < 5


def test_an_altered_snakefile_is_refused_and_never_restored(tmp_path, monkeypatch):
    """An archive whose Snakefile was altered and its manifest recomputed passes the manifest
    (it travels inside), but not the digest published beside the archive; and even the
    published archive's own Snakefile is never written by a restore."""
    out = _built(tmp_path, monkeypatch)
    published = (tmp_path / "out/r.tar.gz.sha256").read_text().split()[0]
    assert published == sha256_file(out)
    members = []
    with tarfile.open(out) as tar:
        for member in tar.getmembers():
            data = tar.extractfile(member).read()
            if member.name == "Snakefile":
                data = b"import os\nos.system('touch PWNED')\n"
            if member.name != MANIFEST:
                member.size = len(data)
                members.append((member, data))
    altered = _crafted(tmp_path / "altered.tar.gz", members)
    assert verify_archive(altered)                     # its own manifest agrees with it
    root = tmp_path / "clone"
    root.mkdir()
    with pytest.raises(ValueError, match="not the published archive"):
        restore_archive(altered, published, root)
    assert list(root.iterdir()) == []
    assert restore_archive(out, published, root) == ["results/a.csv"]
    assert not (root / "Snakefile").exists() and (root / "results/a.csv").read_text() == "x,y\n1,2\n"


def test_a_restore_writes_nothing_through_a_link_in_the_clone(tmp_path, monkeypatch):
    out = _built(tmp_path, monkeypatch)
    root, elsewhere = tmp_path / "clone", tmp_path / "elsewhere"
    root.mkdir()
    elsewhere.mkdir()
    (root / "results").symlink_to(elsewhere)
    with pytest.raises(ValueError, match="symbolic link"):
        restore_archive(out, sha256_file(out), root)
    assert list(elsewhere.iterdir()) == []


def test_the_restore_command_needs_the_published_digest(tmp_path, monkeypatch, capsys):
    out = _built(tmp_path, monkeypatch)
    with pytest.raises(SystemExit):
        archive_main(["restore", str(out)])
    assert "restore needs --sha256" in capsys.readouterr().err
    assert archive_main(["restore", str(out), "--sha256", "0" * 64]) == 1
    assert "refused: the archive's SHA-256" in capsys.readouterr().err
    assert archive_main(["restore", str(out), "--sha256", sha256_file(out)]) == 0
    assert "restored 1 files" in capsys.readouterr().out
