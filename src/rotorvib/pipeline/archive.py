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
--report`` rebuilds it from a restored archive.
"""

from __future__ import annotations

import base64
import gzip
import hashlib
import io
import json
import os
import shutil
import sys
import tarfile
import tempfile
import zlib
from pathlib import Path

MANIFEST = "results/ARCHIVE_MANIFEST.sha256"
#: Where a file with the bytes of an earlier one (the copies of the figures and table pages
#: that the report shows, ``results/report/``) is stored once: as a hard link to the first
#: (in sorted order), which a restore writes as a copy and ``tar -x`` as a link.
LINKED = "results/"
#: Snakemake's per-output records (params, code and input hashes), kept so that a restored
#: archive still reruns exactly the jobs a later config or code change affects.
METADATA_DIR = ".snakemake/metadata"
README = "results/ARCHIVE_README.md"

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
    snakemake -j1 --touch                            # mark the restored files up to date
    snakemake -n                                     # "Nothing to be done"
    snakemake --report results/report.html           # the HTML report, from the restored files

The restore checks the archive against the digest and every file against
`results/ARCHIVE_MANIFEST.sha256` before it writes anything, takes regular files only, and
writes only `results/`, Snakemake's job records (`.snakemake/metadata/`) and the crate: the
Snakefile and the configuration files come from your clone, never from an archive (Snakemake
runs the one and evaluates templates in the other). `--touch` only updates timestamps; no job
runs. With the job records, changing a parameter in `config/config.yaml` reruns exactly the
jobs that depend on it, as after a fresh run. The records carry no run times (two builds of
one commit give the same archive), so the report's runtime statistics read zero.

## Contents

{count} files; SHA-256 of each in `ARCHIVE_MANIFEST.sha256`. A file with the bytes of an
earlier one (the report's copies of the figures and table pages, `results/report/shown/`) is
stored once, as a hard link to it: the restore writes it as a file, `tar -x` as a link.
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


#: What a restore takes from an archive: the results, Snakemake's job records and the crate
#: that describes them. The rest (the Snakefile, the configuration files, the licence and the
#: citation) is checked against the manifest but never written: the workflow's code and
#: configuration come from the clone, not from an archive.
RESTORED = ("results/", f"{METADATA_DIR}/", "ro-crate-metadata.json")
#: Bounds on what a verify or a restore reads: members, bytes of one member and of all, and
#: of the manifest (the paper configuration's archive: about 700 members, 60 MB).
MAX_MEMBERS = 100_000
MAX_MEMBER_BYTES = 1 << 30
MAX_TOTAL_BYTES = 16 << 30
MAX_MANIFEST_BYTES = 32 << 20
_BLOCK = 1 << 20


class _HashingReader:
    """A binary file read through while its SHA-256 is computed: the digest covers exactly the
    bytes the tar reader saw (no second read that could see other bytes)."""

    def __init__(self, fh):
        self.fh, self.digest = fh, hashlib.sha256()

    def read(self, size=-1):
        data = self.fh.read(size)
        self.digest.update(data)
        return data

    def rest(self) -> str:
        """The digest of the whole file, after reading what the tar reader left."""
        for block in iter(lambda: self.read(_BLOCK), b""):
            pass
        return self.digest.hexdigest()


def _member_problem(member: tarfile.TarInfo, earlier: dict[str, str]) -> str | None:
    """Why a member is refused, or None: only regular files, and hard links to an earlier
    regular file of the archive (``earlier``: name -> digest; see :data:`LINKED`), with a
    relative, normalised name inside the archive, no special mode bits, within the size
    bound."""
    name = member.name
    if member.islnk():
        if member.linkname not in earlier or not member.linkname.startswith(LINKED):
            return f"is a link to {member.linkname!r}, not to an earlier file of {LINKED}"
    elif not member.isfile():
        return "is not a regular file (a symbolic link, directory or device)"
    if name.startswith("/") or "\\" in name or any(p in ("", ".", "..")
                                                     for p in name.split("/")):
        return "has a name that is not a plain relative path"
    if member.mode & 0o7000:
        return "has a setuid, setgid or sticky bit"
    if member.size > MAX_MEMBER_BYTES:
        return f"is larger than {MAX_MEMBER_BYTES} bytes"
    return None


def _manifest(data: bytes) -> dict[str, str]:
    """The manifest's lines, ``<64 hex digits>  <name>``, as name -> digest."""
    expected = {}
    for line in data.decode("utf-8").splitlines():
        digest, sep, name = line.partition("  ")
        if not sep or len(digest) != 64 or set(digest) - set("0123456789abcdef") or name in expected:
            raise ValueError(f"manifest line {line[:80]!r} is not '<sha256>  <name>'")
        expected[name] = digest
    return expected


def _copy(source, target: Path | None) -> str:
    """The SHA-256 of ``source`` read in blocks, written to ``target`` (a new file, created
    exclusively, never through a link) when given."""
    digest = hashlib.sha256()
    sink = None
    if target is not None:
        target.parent.mkdir(parents=True, exist_ok=True)
        sink = os.fdopen(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW,
                                 0o644), "wb")
    try:
        for block in iter(lambda: source.read(_BLOCK), b""):
            digest.update(block)
            if sink is not None:
                sink.write(block)
    finally:
        if sink is not None:
            sink.close()
    return digest.hexdigest()


def _scan(path: str | Path, sha256: str | None, stage: Path | None) -> list[str]:
    """Read the archive once, as a stream: check each member (:func:`_member_problem` and the
    bounds above), hash it, and write it under ``stage`` when a restore takes it (:data:`RESTORED`);
    then check the whole file's SHA-256 against ``sha256`` (when given) and every member
    against the manifest. Returns the archived file paths; ``ValueError`` otherwise."""
    digests, manifest, total = {}, None, 0
    with open(path, "rb") as raw:
        reader = _HashingReader(raw)
        with tarfile.open(fileobj=reader, mode="r|gz") as tar:
            for member in tar:
                if problem := _member_problem(member, digests):
                    raise ValueError(f"member {member.name!r} {problem}")
                if member.name in digests or (member.name == MANIFEST and manifest is not None):
                    raise ValueError(f"member {member.name!r} appears twice")
                total += member.size
                if len(digests) >= MAX_MEMBERS or total > MAX_TOTAL_BYTES:
                    raise ValueError(f"more than {MAX_MEMBERS} members or {MAX_TOTAL_BYTES} bytes")
                restored = stage is not None and member.name.startswith(RESTORED)
                target = stage / member.name if restored else None
                if member.islnk():      # a copy of an earlier member, staged when restored
                    digests[member.name] = digests[member.linkname]
                    if restored:
                        with open(stage / member.linkname, "rb") as copied:
                            _copy(copied, target)
                    continue
                source = tar.extractfile(member)
                if member.name == MANIFEST:
                    if member.size > MAX_MANIFEST_BYTES:
                        raise ValueError(f"the manifest is larger than {MAX_MANIFEST_BYTES} bytes")
                    manifest = _manifest(source.read())
                    continue
                digests[member.name] = _copy(source, target)
        whole = reader.rest()
    if sha256 is not None and whole != sha256.strip().lower():
        raise ValueError(f"the archive's SHA-256 is {whole}, not the {sha256.strip()} given: "
                         "it is not the published archive")
    if manifest is None:
        raise KeyError(MANIFEST)
    digests.pop(README, None)
    if set(digests) != set(manifest):
        raise ValueError(f"archive members {sorted(set(digests) ^ set(manifest))} do not "
                         "match the manifest")
    for name, actual in digests.items():
        if actual != manifest[name]:
            raise ValueError(f"{name}: SHA-256 {actual} does not match the manifest")
    return sorted(manifest)


def _refuse_links_on_the_way(root: Path, relative: str) -> None:
    """``ValueError`` if a folder on the way from ``root`` to ``relative`` is a symbolic link
    (a restore writes inside the clone only)."""
    here = root
    for part in relative.split("/")[:-1]:
        here = here / part
        if here.is_symlink():
            raise ValueError(f"{here} is a symbolic link: a restore writes only inside {root}")


def verify_archive(path: str | Path, sha256: str | None = None) -> list[str]:
    """Check every member against the manifest, and the whole file against ``sha256`` (a digest
    kept outside the archive: the ``.sha256`` file the build writes beside it, or the one
    published with it) when given; return the archived file paths.

    Raises ``ValueError`` on a missing, extra, corrupted or refused member (a link, a device, a
    name leaving the archive's folder, a special mode, a size over the bounds), on a digest that
    differs, and on a file that is not a complete gzip-compressed tar archive. Reads the
    archive once as a stream, in blocks of 1 MiB.
    """
    return _checked(path, sha256, None)


def restore_archive(path: str | Path, sha256: str, root: str | Path = ".") -> list[str]:
    """Restore an archive into the clone at ``root``, trusting nothing in it: the archive's
    SHA-256 must be ``sha256`` (kept outside the archive), every member is checked as by
    :func:`verify_archive`, and only the members of :data:`RESTORED` are written, after every
    check has passed (staged in a private folder inside ``root``, then moved into place).
    Returns the restored paths."""
    root = Path(root).resolve()
    stage = Path(tempfile.mkdtemp(prefix=".restore-", dir=root))
    try:
        names = _checked(path, sha256, stage)
        restored = [name for name in names if name.startswith(RESTORED)]
        for name in restored:
            _refuse_links_on_the_way(root, name)
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            os.replace(stage / name, root / name)
        return restored
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def _checked(path, sha256, stage) -> list[str]:
    try:
        return _scan(path, sha256, stage)
    except (EOFError, OSError, tarfile.TarError, zlib.error, KeyError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not a complete rotorvib archive ({type(e).__name__}: {e})") \
            from None


def main(argv=None) -> int:
    """``python -m rotorvib.pipeline.archive restore ARCHIVE --sha256 DIGEST``: restore into the
    current folder (a clone of the repository), or ``verify ARCHIVE [--sha256 DIGEST]``."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m rotorvib.pipeline.archive",
                                     description="Verify or restore a rotorvib results archive.")
    parser.add_argument("action", choices=("verify", "restore"))
    parser.add_argument("archive")
    parser.add_argument("--sha256", help="the archive's SHA-256, as published beside it "
                        "(required to restore)")
    args = parser.parse_args(argv)
    if args.action == "restore" and not args.sha256:
        parser.error("restore needs --sha256: the digest published with the archive (its "
                     ".sha256 file), not one read from the archive itself")
    try:
        if args.action == "verify":
            names = verify_archive(args.archive, args.sha256)
            print(f"verified: {len(names)} files match the manifest"
                  + ("" if args.sha256 else " (no --sha256 given: the manifest itself is "
                                            "not checked against a published digest)"))
        else:
            names = restore_archive(args.archive, args.sha256)
            print(f"restored {len(names)} files; now run: snakemake -j1 --touch")
    except ValueError as error:
        print(f"refused: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
