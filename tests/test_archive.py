import io
import os
import tarfile

import pytest

from rotorvib.pipeline.archive import MANIFEST, README, make_archive, sha256_file, verify_archive


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
