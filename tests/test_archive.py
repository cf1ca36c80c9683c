import io
import tarfile

import pytest

from rotorvib.io.archive import MANIFEST, README, make_archive, sha256_file, verify_archive


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
