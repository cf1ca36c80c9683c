"""The check (:func:`verify_archive`) and restore (:func:`restore_archive`) of a results archive
(rotorvib.pipeline.archive), trusting nothing in it.

In order: the archive file's SHA-256 against the published digest, before anything is staged;
one streamed read that bounds each header before tarfile reads it (:class:`_BoundedInfo`),
checks each member (:func:`_member_problem`), counts every member's bytes towards the bounds (a
hard link's are its target's, which a restore writes again), refuses any job record that is not
one Snakemake writes for this workflow (:func:`record_problem`) and stages what a restore takes
(:func:`taken`); the digest of the bytes read, again, and every member against the manifest;
then every destination in the clone (:func:`_destination_problem`), and the moves, all or
nothing (:func:`_move_all`).

Nothing Snakemake evaluates is taken from an archive: the Snakefile and configuration stay the
clone's, job records are checked field by field (Snakemake's report loads a record's
``conda_env`` with an unsafe YAML loader), and the report's words, pages and the copies it
shows (:data:`REBUILT`; Snakemake renders the landing page and captions as Jinja templates)
are left out, rebuilt from the restored comparison by two short jobs (the restore notes'
steps, rotorvib.pipeline.archive.RESTORE_NOTES).
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import io
import json
import os
import re
import shutil
import sys
import tarfile
import tempfile
import zlib
from pathlib import Path

from rotorvib.pipeline.archive import (
    CRATE,
    LINKED,
    MANIFEST,
    METADATA_DIR,
    README,
    RESTORE_STEPS,
    record_path,
)

#: What a restore takes from an archive: the results, Snakemake's job records and the crate
#: that describes them (that name exactly, at the clone's root), but :data:`REBUILT`. The rest
#: (the Snakefile, the configuration files, the licence and the citation) is checked against
#: the manifest but never written.
RESTORED = ("results/", f"{METADATA_DIR}/")
#: The report's words (landing page, captions), pages and the copies it shows: never restored,
#: since Snakemake renders the words as Jinja templates. Rules report_text and report_results
#: rebuild them from the restored comparison and figures in seconds.
REBUILT = "results/report/"
#: Bounds on what a verify or a restore reads: members, bytes of one member and of all (a hard
#: link counts its target's), of the manifest, of a job record and of an extended header (a
#: pax header, a GNU long name or link), and extended headers in a row (a member has at most a
#: global one, a long name and a long link, or one pax header). The paper configuration's
#: archive: about 700 members, 60 MB, its longest job record 60 kB.
MAX_MEMBERS = 100_000
MAX_MEMBER_BYTES = 1 << 30
MAX_TOTAL_BYTES = 16 << 30
MAX_MANIFEST_BYTES = 32 << 20
MAX_RECORD_BYTES = 4 << 20
MAX_HEADER_BYTES = 64 << 10
MAX_HEADERS_IN_A_ROW = 3
#: Free space a restore leaves on the clone's file system beyond what it stages.
SPARE_BYTES = 64 << 20
_BLOCK = 1 << 20
_EXTENDED = (tarfile.GNUTYPE_LONGNAME, tarfile.GNUTYPE_LONGLINK, tarfile.XHDTYPE,
             tarfile.XGLTYPE, tarfile.SOLARIS_XHDTYPE)


def _is_name(value) -> bool:
    return isinstance(value, str) and re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", value) is not None


def _is_strings(value) -> bool:
    return isinstance(value, list) and all(isinstance(v, str) for v in value)


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


#: The fields of a job record as Snakemake (record format 6) writes them for this workflow,
#: each with its test: no shell command, conda environment, container or cluster job, and
#: the run times the archive sets (rotorvib.pipeline.archive.RUN_TIMES).
RECORD_FIELDS = {
    "rule": _is_name,
    "input": _is_strings,
    "log": _is_strings,
    "shellcmd": lambda v: v is None,
    "params": lambda v: isinstance(v, list),
    "code": lambda v: isinstance(v, str),
    "record_format_version": lambda v: v == 6,
    "conda_env": lambda v: v is None,
    "container_img_url": lambda v: v is None,
    "software_stack_hash": lambda v: isinstance(v, str),
    "job_hash": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "starttime": _is_number,
    "endtime": _is_number,
    "incomplete": lambda v: v is False,
    "external_jobid": lambda v: v is None,
    "input_checksums": lambda v: isinstance(v, dict) and all(
        isinstance(k, str) and isinstance(c, str) for k, c in v.items()),
}


def record_problem(data: bytes) -> str | None:
    """Why a job record's bytes are not a record of :data:`RECORD_FIELDS` (exactly those keys,
    each passing its test), or None."""
    try:
        record = json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as error:
        return f"is not JSON ({error})"
    if not isinstance(record, dict) or set(record) != set(RECORD_FIELDS):
        keys = sorted(set(record) ^ set(RECORD_FIELDS)) if isinstance(record, dict) else "all"
        return f"is not a job record (keys that differ: {keys})"
    bad = [key for key, test in RECORD_FIELDS.items() if not test(record[key])]
    return f"has fields not as this workflow writes them: {bad}" if bad else None


def record_output(name: str) -> str | None:
    """The output file whose job record a member ``name`` under :data:`METADATA_DIR` is (its
    path in Snakemake's layout, :func:`rotorvib.pipeline.archive.record_path`), or None."""
    parts = name[len(METADATA_DIR) + 1:].split("/")
    if not name.startswith(f"{METADATA_DIR}/") or any(
            not p.startswith("@") for p in parts[:-1]) or parts[-1].startswith("@"):
        return None
    encoded = "".join(p.removeprefix("@") for p in parts[:-1]) + parts[-1]
    try:
        output = base64.urlsafe_b64decode(encoded.encode("ascii")).decode("utf-8")
    except (binascii.Error, UnicodeError, ValueError):
        return None
    canonical = base64.urlsafe_b64encode(output.encode()).decode() == encoded
    return output if canonical else None


def taken(name: str) -> bool:
    """Whether a restore writes the archive's file ``name`` (by its name; a job record by the
    file it records)."""
    if name.startswith(f"{METADATA_DIR}/"):
        output = record_output(name)
        return output is not None and output.startswith(RESTORED[0]) and taken(output)
    return name == CRATE or (name.startswith(RESTORED) and not name.startswith(REBUILT))


class _BoundedInfo(tarfile.TarInfo):
    """A tar header that refuses, before tarfile reads it, an extended header over
    :data:`MAX_HEADER_BYTES` or more than :data:`MAX_HEADERS_IN_A_ROW` of them in a row
    (tarfile reads one whole, and a chain by recursion), and any sparse file (whose map tarfile
    reads unbounded)."""

    def _proc_member(self, tarfile_):
        if self.type in _EXTENDED:
            tarfile_.headers_in_a_row += 1
            if self.size > MAX_HEADER_BYTES:
                raise ValueError(f"member {self.name!r}: an extended header of {self.size} "
                                 f"bytes, over the bound of {MAX_HEADER_BYTES}")
            if tarfile_.headers_in_a_row > MAX_HEADERS_IN_A_ROW:
                raise ValueError(f"member {self.name!r}: more than {MAX_HEADERS_IN_A_ROW} "
                                 "extended headers in a row")
        else:
            tarfile_.headers_in_a_row = 0
        if self.type == tarfile.GNUTYPE_SPARSE:
            self._sparse()
        return super()._proc_member(tarfile_)

    def _sparse(self, *_):
        raise ValueError(f"member {self.name!r} is a sparse file")

    _proc_gnusparse_00 = _proc_gnusparse_01 = _proc_gnusparse_10 = _sparse


class _BoundedTar(tarfile.TarFile):
    """A tar reader whose headers are :class:`_BoundedInfo`."""

    tarinfo = _BoundedInfo
    headers_in_a_row = 0


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
        for _ in iter(lambda: self.read(_BLOCK), b""):
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
    elif not member.isfile() or member.type == tarfile.CONTTYPE:
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
        if not sep or not _is_digest(digest) or name in expected:
            raise ValueError(f"manifest line {line[:80]!r} is not '<sha256>  <name>'")
        expected[name] = digest
    return expected


def _is_digest(text: str) -> bool:
    return re.fullmatch(r"[0-9a-f]{64}", text) is not None


def _copy(source, target: Path | None) -> str:
    """The SHA-256 of ``source`` read in blocks, written to ``target`` (a new file, created
    exclusively, never through a link) when given; a write that fails (a full disk) is a
    ``ValueError`` naming the file."""
    digest = hashlib.sha256()
    if target is None:
        for block in iter(lambda: source.read(_BLOCK), b""):
            digest.update(block)
        return digest.hexdigest()
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        with os.fdopen(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW,
                               0o644), "wb") as sink:
            for block in iter(lambda: source.read(_BLOCK), b""):
                digest.update(block)
                sink.write(block)
    except OSError as error:
        raise ValueError(f"could not stage {target}: "
                         f"{error.strerror or error}") from None
    return digest.hexdigest()


def _file_digest(path: str | Path) -> str:
    with open(path, "rb") as fh:
        return _HashingReader(fh).rest()


def _scan(path: str | Path, sha256: str | None, stage: Path | None) -> dict[str, str]:
    """Read the archive once, as a stream: check each header and member (the bounds above),
    hash it, and write it under ``stage`` when a restore takes it (:func:`taken`); then check
    the digest of the bytes read against ``sha256`` (when given) and every member against the
    manifest. Returns the archived files' digests by name; ``ValueError`` otherwise."""
    digests, sizes, manifest, total = {}, {}, None, 0
    with open(path, "rb") as raw:
        reader = _HashingReader(raw)
        with _BoundedTar.open(fileobj=reader, mode="r|gz") as tar:
            for member in tar:
                if problem := _member_problem(member, digests):
                    raise ValueError(f"member {member.name!r} {problem}")
                if member.name in digests or (member.name == MANIFEST and manifest is not None):
                    raise ValueError(f"member {member.name!r} appears twice")
                size = sizes[member.linkname] if member.islnk() else member.size
                total += size
                if len(digests) >= MAX_MEMBERS or total > MAX_TOTAL_BYTES:
                    raise ValueError(f"member {member.name!r}: more than {MAX_MEMBERS} members "
                                     f"or {MAX_TOTAL_BYTES} bytes (hard links count their "
                                     "target's)")
                target = stage / member.name if stage is not None and taken(member.name) \
                    else None
                if target is not None and shutil.disk_usage(stage).free < size + SPARE_BYTES:
                    raise ValueError(f"member {member.name!r}: {size} bytes would leave less "
                                     f"than {SPARE_BYTES} bytes free in {stage.parent}")
                sizes[member.name] = size
                if member.islnk():      # a copy of an earlier member, staged when taken
                    digests[member.name] = digests[member.linkname]
                    if target is not None:
                        with open(stage / member.linkname, "rb") as copied:
                            _copy(copied, target)
                    continue
                source = tar.extractfile(member)
                if member.name == MANIFEST:
                    if member.size > MAX_MANIFEST_BYTES:
                        raise ValueError(f"the manifest is larger than {MAX_MANIFEST_BYTES} bytes")
                    manifest = _manifest(source.read())
                    continue
                if member.name.startswith(f"{METADATA_DIR}/"):
                    source = io.BytesIO(_checked_record(member, source))
                digests[member.name] = _copy(source, target)
        whole = reader.rest()
    if sha256 is not None and whole != sha256:
        raise ValueError(f"{path} changed while it was read: it is not the published archive")
    if manifest is None:
        raise KeyError(MANIFEST)
    digests.pop(README, None)
    if set(digests) != set(manifest):
        raise ValueError(f"archive members {sorted(set(digests) ^ set(manifest))[:5]} do not "
                         "match the manifest")
    for name, actual in digests.items():
        if actual != manifest[name]:
            raise ValueError(f"{name}: SHA-256 {actual} does not match the manifest")
    return digests


def _checked_record(member: tarfile.TarInfo, source) -> bytes:
    """The bytes of a member under :data:`METADATA_DIR`; ``ValueError`` unless it is a job
    record, named after a file of the archive's ``results/`` (:func:`record_output`), of
    :data:`RECORD_FIELDS`."""
    output = record_output(member.name)
    if output is None or not output.startswith(RESTORED[0]):
        raise ValueError(f"member {member.name!r} is not named as the job record of a file of "
                         f"{RESTORED[0]}")
    if member.size > MAX_RECORD_BYTES:
        raise ValueError(f"member {member.name!r} (the job record of {output}) is larger than "
                         f"{MAX_RECORD_BYTES} bytes")
    data = source.read()
    if problem := record_problem(data):
        raise ValueError(f"member {member.name!r} (the job record of {output}) {problem}")
    return data


def _checked(path, sha256, stage) -> dict[str, str]:
    """:func:`_scan` after the whole file's digest is checked against ``sha256`` (when given),
    with a damaged archive's error as ``ValueError``."""
    try:
        if sha256 is not None:
            sha256 = sha256.strip().lower()
            whole = _file_digest(path)
            if whole != sha256:
                raise ValueError(f"the archive's SHA-256 is {whole}, not the {sha256} given: "
                                 "it is not the published archive")
        return _scan(path, sha256, stage)
    except (EOFError, OSError, tarfile.TarError, zlib.error, KeyError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not a complete rotorvib archive ({type(e).__name__}: {e})") \
            from None


def verify_archive(path: str | Path, sha256: str | None = None) -> list[str]:
    """Check every member against the manifest, and the whole file against ``sha256`` (a digest
    kept outside the archive: the ``.sha256`` file the build writes beside it, or the one
    published with it) when given; return the archived file paths.

    Raises ``ValueError`` on a missing, extra, corrupted or refused member (a link, a device, a
    name leaving the archive's folder, a special mode, a size or header over the bounds, a job
    record Snakemake does not write), on a digest that differs, and on a file that is not a
    complete gzip-compressed tar archive. Reads the archive as a stream, in blocks of 1 MiB.
    """
    return sorted(_checked(path, sha256, None))


def _plan(root: Path, names) -> dict[str, str]:
    """Where each taken member goes in the clone: its own name, or for a job record the path
    Snakemake reads it from on the clone's file system (its names' length limit)."""
    name_max = os.pathconf(root, "PC_NAME_MAX")
    plan = {}
    for name in sorted(n for n in names if taken(n)):
        output = record_output(name)
        plan[name] = name if output is None else record_path(output, name_max)
    return plan


def _destination_problem(root: Path, relative: str) -> str | None:
    """Why a file cannot be written at ``relative`` in the clone at ``root``, or None: a folder
    on the way that is a symbolic link or not a folder, or something not a regular file in the
    file's place."""
    here = root
    for part in relative.split("/")[:-1]:
        here = here / part
        if here.is_symlink():
            return f"{here} is a symbolic link: a restore writes only inside {root}"
        if here.exists() and not here.is_dir():
            return f"{here} is not a folder"
    target = root / relative
    if target.is_symlink() or (target.exists() and not target.is_file()):
        return f"{target} is not a regular file"
    return None


def _move_all(root: Path, stage: Path, plan: dict[str, str]) -> None:
    """Move each staged member to its destination; on any failure (a full disk, a race that put
    a link on the way) undo every move, restoring the files replaced (kept under ``stage``,
    on the same file system) and removing the folders made, and raise ``ValueError``."""
    moved, made = [], []        # (destination, its backup or None); folders made
    try:
        for name, relative in plan.items():
            if problem := _destination_problem(root, relative):
                raise ValueError(problem)
            here = root
            for part in relative.split("/")[:-1]:
                here = here / part
                if not here.exists():
                    here.mkdir()
                    made.append(here)
            target, backup = root / relative, None
            if target.exists():
                backup = stage / ".replaced" / relative
                backup.parent.mkdir(parents=True, exist_ok=True)
                os.replace(target, backup)
            moved.append((target, backup))
            os.replace(stage / name, target)
    except (OSError, ValueError) as error:
        undone = _undo(moved, made)
        reason = error.strerror if isinstance(error, OSError) and error.strerror else error
        raise ValueError(f"{relative}: {reason}; "
                         + ("the clone is as it was" if undone else
                            f"could not undo every move (the replaced files are in {stage})")) \
            from None


def _undo(moved, made) -> bool:
    """Undo :func:`_move_all`'s moves, last first; whether all were undone."""
    undone = True
    for target, backup in reversed(moved):
        try:
            if target.exists() or target.is_symlink():
                target.unlink()
            if backup is not None:
                os.replace(backup, target)
        except OSError:
            undone = False
    for folder in reversed(made):
        try:
            folder.rmdir()
        except OSError:
            undone = False
    return undone


def restore_archive(path: str | Path, sha256: str, root: str | Path = ".") -> list[str]:
    """Restore an archive into the clone at ``root``, trusting nothing in it: the archive's
    SHA-256 must be ``sha256`` (kept outside the archive), every member is checked as by
    :func:`verify_archive`, and only the members :func:`taken` are written, after every check
    has passed, all or none (staged in a private folder inside ``root``, then moved into
    place). Returns the paths written."""
    root = Path(root).resolve()
    stage = Path(tempfile.mkdtemp(prefix=".restore-", dir=root))
    try:
        plan = _plan(root, _checked(path, sha256, stage))
        if len(set(plan.values())) < len(plan):
            raise ValueError("two job records of the archive are records of the same file")
        for relative in plan.values():
            if problem := _destination_problem(root, relative):
                raise ValueError(problem)
        _move_all(root, stage, plan)
        return sorted(plan.values())
    except OSError as error:
        raise ValueError(f"could not stage the archive in {root}: {error}") from None
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def main(argv=None) -> int:
    """``python -m rotorvib.pipeline.archive restore ARCHIVE --sha256 DIGEST``: restore into the
    current folder (a clone of the repository), or ``verify ARCHIVE [--sha256 DIGEST]``; a
    refusal is one line on stderr, exit status 1."""
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
    if args.sha256 and not _is_digest(args.sha256.strip().lower()):
        parser.error("--sha256 takes 64 hexadecimal digits")
    try:
        if args.action == "verify":
            names = verify_archive(args.archive, args.sha256)
            print(f"verified: {len(names)} files match the manifest"
                  + ("" if args.sha256 else " (no --sha256 given: the manifest itself is "
                                            "not checked against a published digest)"))
        else:
            names = restore_archive(args.archive, args.sha256)
            print(f"restored {len(names)} files ({REBUILT} left out: its texts are rebuilt, "
                  f"not restored); now run: {RESTORE_STEPS}")
    except ValueError as error:
        print(f"refused: {error}", file=sys.stderr)
        return 1
    return 0
