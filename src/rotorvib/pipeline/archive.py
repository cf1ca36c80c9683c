"""Archive of the pipeline's results: one tarball, a SHA-256 manifest and restore notes, and a
restore that verifies before it trusts (:func:`restore_archive`).

The archive holds the files under their repository paths (``results/...``) plus
``results/ARCHIVE_MANIFEST.sha256`` (``sha256sum -c`` format) and ``results/ARCHIVE_README.md``.
It is reproducible: two builds of the same commit and configuration give the same bytes.
Members come in sorted order with a fixed mtime (``SOURCE_DATE_EPOCH``, else 0), owner and
mode, and a gzip header without a timestamp; a results file with the bytes of an earlier one
(the report's copies of the figures and table pages) is stored once, the copy as a hard link
(:data:`LINKED`); Snakemake's job records are archived without
what differs between two runs (:data:`RUN_TIMES`: start and end times, the job's in-process
hash), which Snakemake uses for the report's runtimes only, never to decide a rerun.  The HTML
report, whose runtimes and timestamps differ between runs, is not archived: ``snakemake
--report`` rebuilds it from a restored archive. The check and the restore, which trust nothing
in an archive, are rotorvib.pipeline.archive_restore (``python -m rotorvib.pipeline.archive``).
"""

from __future__ import annotations

import base64
import gzip
import hashlib
import io
import json
import os
import tarfile
from pathlib import Path

MANIFEST = "results/ARCHIVE_MANIFEST.sha256"
#: Where a file with the bytes of an earlier one (the copies of the figures and table pages
#: that the report shows, ``results/report/``) is stored once: as a hard link to the first
#: (in sorted order), which a restore writes as a copy (outside ``results/report/``, which it
#: leaves out) and ``tar -x`` as a link.
LINKED = "results/"
#: Snakemake's per-output records (params, code and input hashes), kept so that a restored
#: archive still reruns exactly the jobs a later config or code change affects.
METADATA_DIR = ".snakemake/metadata"
README = "results/ARCHIVE_README.md"
#: The RO-Crate's metadata file, at the archive's root (rotorvib.pipeline.crate).
CRATE = "ro-crate-metadata.json"
#: What to run after a restore (rotorvib.pipeline.archive_restore): mark the restored files up
#: to date but the report's words and pages, which the restore leaves out, then rebuild those
#: (rules report_text and report_results, a few seconds).
RESTORE_STEPS = "snakemake -j1 --touch --omit-from report_text && snakemake -j1"

RESTORE_NOTES = """# rotorvib results archive

This archive holds every dataset (netCDF), table and figure of one run of the rotorvib
workflow, under their paths in the repository, with the run's whole configuration and commit
(`results/run/`), the Snakefile, the licence and the citation file. `ro-crate-metadata.json`
describes it all as an RO-Crate 1.3 (the workflow, the run, each file's checksum, format and
licence).

## Restore without recomputing

From the root of a clone of the repository at the commit recorded in the datasets
(attribute `provenance_git_commit`), with the SHA-256 published beside the archive (its
`.sha256` file; never a digest read from the archive itself):

    python -m rotorvib.pipeline.archive restore rotorvib-results.tar.gz --sha256 DIGEST
    snakemake -j1 --touch --omit-from report_text    # mark the restored files up to date
    snakemake -j1                                    # the report's words and pages, rebuilt
    snakemake -n                                     # "Nothing to be done"
    snakemake --report results/report.html           # the HTML report, from the restored files

The restore checks the archive against the digest before it reads further, then every file
against `results/ARCHIVE_MANIFEST.sha256` and within its bounds, before it writes anything; it
takes regular files only and writes only `results/`, Snakemake's job records
(`.snakemake/metadata/`, each checked field by field: no shell command, conda environment or
container) and the crate, all or none. Nothing Snakemake evaluates comes from an archive: the
Snakefile and the configuration files are your clone's, and the report's words, pages and the
copies it shows (`results/report/`, whose landing page and captions Snakemake renders as
templates) are left out and rebuilt from the restored comparison by two short jobs, the second
command. `--touch` only updates timestamps; no job runs. With the job records, changing a
parameter in `config/config.yaml` reruns exactly the jobs that depend on it, as after a fresh
run. The records carry no run times (two builds of one commit give the same archive), so the
report's runtime statistics read zero.

## Contents

{count} files; SHA-256 of each in `ARCHIVE_MANIFEST.sha256`. A file with the bytes of an
earlier one (the report's copies of the figures and table pages, `results/report/shown/`) is
stored once, as a hard link to it, which `tar -x` writes as a link (the restore leaves
`results/report/` out, and its steps copy it again).
"""


def sha256_file(path: str | Path) -> str:
    """SHA-256 of a file's bytes, read in 1 MiB blocks."""
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _mtime() -> int:
    return int(os.environ.get("SOURCE_DATE_EPOCH", "0"))


def _add_text(tar: tarfile.TarFile, name: str, text: str) -> None:
    data = text.encode()
    info = tarfile.TarInfo(name)
    info.size = len(data)
    info.mode = 0o644
    info.mtime = _mtime()
    tar.addfile(info, io.BytesIO(data))


def record_path(output: str, name_max: int) -> str:
    """Where Snakemake keeps the job record of ``output``: the URL-safe base64 of its path
    under :data:`METADATA_DIR`, cut into folder names of ``name_max - 1`` characters at most,
    each but the last prefixed by ``@`` (so a long path fits the file system's name length
    limit, ``name_max``; snakemake.persistence.file)."""
    encoded = base64.urlsafe_b64encode(output.encode()).decode()
    parts = [encoded[i:i + name_max - 1] for i in range(0, len(encoded), name_max - 1)]
    return "/".join([METADATA_DIR, *(f"@{p}" for p in parts[:-1]), parts[-1]])


def job_records(files) -> list[str]:
    """Snakemake's metadata record of each file, where one exists (see METADATA_DIR)."""
    name_max = os.pathconf(METADATA_DIR if Path(METADATA_DIR).is_dir() else ".", "PC_NAME_MAX")
    names = (record_path(f, name_max) for f in files)
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
    them and a README; write the archive's SHA-256 beside it (:func:`digest_file`)."""
    files = sorted({Path(f).as_posix() for f in files})
    digests = {f: sha256_file(f) for f in files}
    records = {record: without_run_times(record) for record in job_records(files)}
    generated = dict(sorted({**records, **(generated or {})}.items()))
    manifest = "".join(f"{digests[f]}  {f}\n" for f in files) + "".join(
        f"{hashlib.sha256(text.encode()).hexdigest()}  {name}\n"
        for name, text in generated.items())
    output = Path(output)
    output.parent.mkdir(parents=True, exist_ok=True)
    with open(output, "wb") as raw, \
            gzip.GzipFile(filename="", fileobj=raw, mode="wb", mtime=0) as gz, \
            tarfile.open(fileobj=gz, mode="w", format=tarfile.PAX_FORMAT) as tar:
        first = {}      # a results file's digest -> the first results file with those bytes
        for f in files:
            if f.startswith(LINKED) and digests[f] in first:
                tar.addfile(_anonymise(_hard_link(f, first[digests[f]])))
                continue
            tar.add(f, arcname=f, recursive=False, filter=_anonymise)
            if f.startswith(LINKED):
                first.setdefault(digests[f], f)
        for name, text in generated.items():
            _add_text(tar, name, text)
        _add_text(tar, MANIFEST, manifest)
        _add_text(tar, README, RESTORE_NOTES.format(count=len(files) + len(generated)))
    digest_file(output).write_text(f"{sha256_file(output)}  {output.name}\n", encoding="utf-8")
    return output


def _hard_link(name: str, target: str) -> tarfile.TarInfo:
    """A member that holds no bytes: ``name`` is a copy of the earlier member ``target``."""
    info = tarfile.TarInfo(name)
    info.type, info.linkname = tarfile.LNKTYPE, target
    return info


def digest_file(archive: str | Path) -> Path:
    """The file beside an archive that holds its SHA-256 (``sha256sum`` format): the digest a
    restore checks the archive against, published with it."""
    return Path(f"{archive}.sha256")


def _anonymise(info: tarfile.TarInfo) -> tarfile.TarInfo:
    """No owner, a fixed mode and mtime: the member depends on the file's bytes only."""
    info.uid = info.gid = 0
    info.uname = info.gname = ""
    info.mode = 0o644
    info.mtime = _mtime()
    info.pax_headers = {}
    return info


if __name__ == "__main__":
    from rotorvib.pipeline.archive_restore import main

    raise SystemExit(main())
