"""Archive of the pipeline's results: one tarball, a SHA-256 manifest and restore notes.

The archive holds the files under their repository paths (``results/...``) plus
``results/ARCHIVE_MANIFEST.sha256`` (``sha256sum -c`` format) and ``results/ARCHIVE_README.md``.
It is reproducible: two builds of the same commit and configuration give the same bytes.
Members come in sorted order with a fixed mtime (``SOURCE_DATE_EPOCH``, else 0), owner and
mode, and a gzip header without a timestamp; Snakemake's job records are archived without
what differs between two runs (:data:`RUN_TIMES`: start and end times, the job's in-process
hash), which Snakemake uses for the report's runtimes only, never to decide a rerun.  The HTML
report, whose runtimes and timestamps differ between runs, is not archived: ``snakemake
--report`` rebuilds it from a restored archive.
"""

from __future__ import annotations

import base64
import gzip
import hashlib
import io
import json
import os
import tarfile
import zlib
from pathlib import Path

MANIFEST = "results/ARCHIVE_MANIFEST.sha256"
#: Snakemake's per-output records (params, code and input hashes), kept so that a restored
#: archive still reruns exactly the jobs a later config or code change affects.
METADATA_DIR = ".snakemake/metadata"
README = "results/ARCHIVE_README.md"

RESTORE_NOTES = """# rotorvib results archive

This archive holds every dataset (netCDF), table and figure of one run of the rotorvib
workflow, under their paths in the repository, with the run's whole configuration and commit
(`results/run/`), the Snakefile, the licence and the citation file. `ro-crate-metadata.json` describes it all as a Workflow Run RO-Crate (the
workflow, the run, each file's checksum, format and licence).

## Restore without recomputing

From the root of a clone of the repository at the commit recorded in the datasets
(attribute `provenance_git_commit`):

    tar -xzf rotorvib-results.tar.gz
    sha256sum -c results/ARCHIVE_MANIFEST.sha256    # every file must say OK
    snakemake -j1 --touch                            # mark the restored files up to date
    snakemake -n                                     # "Nothing to be done"
    snakemake --report results/report.html           # the HTML report, from the restored files

`--touch` only updates timestamps; no job runs. The archive also carries Snakemake's records
of the jobs (`.snakemake/metadata/`), so after restoring, changing a parameter in
`config/config.yaml` reruns exactly the jobs that depend on it, as after a fresh run. The
records carry no run times (two builds of one commit give the same archive), so the report's
runtime statistics read zero.

## Contents

{count} files; SHA-256 of each in `ARCHIVE_MANIFEST.sha256`.
"""


def sha256_file(path: str | Path) -> str:
    """SHA-256 of a file's bytes, read in 1 MiB blocks."""
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _mtime() -> int:
    return int(os.environ.get("SOURCE_DATE_EPOCH", 0))


def _add_text(tar: tarfile.TarFile, name: str, text: str) -> None:
    data = text.encode()
    info = tarfile.TarInfo(name)
    info.size = len(data)
    info.mode = 0o644
    info.mtime = _mtime()
    tar.addfile(info, io.BytesIO(data))


def job_records(files) -> list[str]:
    """Snakemake's metadata record of each file, where one exists (see METADATA_DIR)."""
    names = (f"{METADATA_DIR}/{base64.urlsafe_b64encode(f.encode()).decode()}" for f in files)
    return [n for n in names if Path(n).is_file()]


#: The fields of a Snakemake job record that differ between two runs of the same jobs.
RUN_TIMES = ("starttime", "endtime", "job_hash")


def without_run_times(path: str | Path) -> str:
    """A job record's JSON with :data:`RUN_TIMES` set to the archive's fixed time (0 for the
    hash)."""
    record = json.loads(Path(path).read_text(encoding="utf-8"))
    for key in RUN_TIMES:
        if key in record:
            record[key] = 0 if key == "job_hash" else _mtime()
    return json.dumps(record)


def make_archive(files: list[str | Path], output: str | Path,
                 generated: dict[str, str] | None = None) -> Path:
    """Pack ``files`` (paths relative to the repository root) with their Snakemake job
    records, the ``generated`` members (name -> text, e.g. the RO-Crate), a manifest of all of
    them and a README."""
    files = sorted({Path(f).as_posix() for f in files})
    records = {record: without_run_times(record) for record in job_records(files)}
    generated = dict(sorted({**records, **(generated or {})}.items()))
    manifest = "".join(f"{sha256_file(f)}  {f}\n" for f in files) + "".join(
        f"{hashlib.sha256(text.encode()).hexdigest()}  {name}\n"
        for name, text in generated.items())
    output = Path(output)
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "wb") as raw, \
            gzip.GzipFile(filename="", fileobj=raw, mode="wb", mtime=0) as gz, \
            tarfile.open(fileobj=gz, mode="w", format=tarfile.PAX_FORMAT) as tar:
        for f in files:
            tar.add(f, arcname=f, recursive=False, filter=_anonymise)
        for name, text in generated.items():
            _add_text(tar, name, text)
        _add_text(tar, MANIFEST, manifest)
        _add_text(tar, README, RESTORE_NOTES.format(count=len(files) + len(generated)))
    return output


def _anonymise(info: tarfile.TarInfo) -> tarfile.TarInfo:
    """No owner, a fixed mode and mtime: the member depends on the file's bytes only."""
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    info.mode = 0o644
    info.mtime = _mtime()
    info.pax_headers = {}
    return info


def verify_archive(path: str | Path) -> list[str]:
    """Check every member against the manifest; return the archived file paths.

    Raises ``ValueError`` on a missing, extra or corrupted member, and on a file that is not
    a complete gzip-compressed tar archive.
    """
    try:
        return _verify(path)
    except (EOFError, OSError, tarfile.TarError, zlib.error, KeyError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not a complete rotorvib archive ({type(e).__name__}: {e})") \
            from None


def _verify(path: str | Path) -> list[str]:
    with tarfile.open(path, "r:gz") as tar:
        members = {m.name: m for m in tar.getmembers() if m.isfile()}
        expected = {}
        for line in tar.extractfile(members.pop(MANIFEST)).read().decode().splitlines():
            digest, name = line.split("  ", 1)
            expected[name] = digest
        members.pop(README)
        if set(members) != set(expected):
            raise ValueError(f"archive members {sorted(set(members) ^ set(expected))} do not "
                             "match the manifest")
        for name, member in members.items():
            actual = hashlib.sha256(tar.extractfile(member).read()).hexdigest()
            if actual != expected[name]:
                raise ValueError(f"{name}: SHA-256 {actual} does not match the manifest")
    return sorted(expected)
