"""The check (:func:`verify_archive`) and restore (:func:`restore_archive`) of a results archive
(rotorvib.pipeline.archive), trusting nothing in it.

In order: the archive file's SHA-256 against the published digest, before anything is staged;
then one streamed read that checks each tar header before tarfile reads it (from the tar
format itself: rotorvib.pipeline.archive_checks.CheckedTarStream), checks each member,
counts every member's bytes towards the bounds (a hard link's are its target's, which a restore
writes again), refuses any job record that is not one Snakemake writes for this workflow and
stages what a restore takes (rotorvib.pipeline.archive_checks); the digest of the bytes read,
again, and every member against the manifest; then every destination in the clone
(:func:`_destination_problem`), and the moves, all or nothing (:func:`_move_all`).

Nothing Snakemake evaluates is taken from an archive: the Snakefile and configuration stay the
clone's, job records are checked field by field (Snakemake's report loads a record's
``conda_env`` with an unsafe YAML loader), and the report's words, pages and the copies it
shows (``results/report/``; Snakemake renders the landing page and captions as Jinja templates)
are left out, rebuilt from the restored comparison by two short jobs (the restore notes'
steps, rotorvib.pipeline.archive.RESTORE_NOTES).
"""

from __future__ import annotations

import errno
import gzip
import hashlib
import io
import os
import shutil
import stat
import sys
import tarfile
import tempfile
import zlib
from pathlib import Path

from rotorvib.pipeline.archive import (
    LINKED,
    MANIFEST,
    METADATA_DIR,
    README,
    RESTORE_STEPS,
    record_path,
)
from rotorvib.pipeline.archive_checks import (
    MAX_MANIFEST_BYTES,
    MAX_MEMBERS,
    MAX_RECORD_BYTES,
    MAX_TOTAL_BYTES,
    REBUILT,
    RESTORED,
    CheckedTarStream,
    is_digest,
    manifest_digests,
    member_problem,
    record_output,
    record_problem,
    taken,
)

#: Free space a restore leaves on the clone's file system beyond what it stages.
SPARE_BYTES = 64 << 20
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
        for _ in iter(lambda: self.read(_BLOCK), b""):
            pass
        return self.digest.hexdigest()


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
    hash it, and write it under ``stage`` when a restore takes it; then check
    the digest of the bytes read against ``sha256`` (when given) and every member against the
    manifest. Returns the archived files' digests by name; ``ValueError`` otherwise."""
    digests, sizes, manifest, total = {}, {}, None, 0
    with open(path, "rb") as raw:
        reader = _HashingReader(raw)
        # gzip's reader, not tarfile's: it inflates no more than it is asked for (tarfile's
        # inflates each 10 kB read whole, 10 MB of zeros)
        with gzip.GzipFile(fileobj=reader, mode="rb") as inflated, \
                tarfile.open(fileobj=CheckedTarStream(inflated), mode="r|") as tar:
            for member in tar:
                if problem := member_problem(member, digests):
                    raise ValueError(f"member {member.name!r} {problem}")
                if member.name in digests or (member.name == MANIFEST and manifest is not None):
                    raise ValueError(f"member {member.name!r} appears twice")
                size = sizes[member.linkname] if member.islnk() else member.size
                total += size
                if len(digests) >= MAX_MEMBERS or total > MAX_TOTAL_BYTES:
                    raise ValueError(f"member {member.name!r}: more than {MAX_MEMBERS} members "
                                     f"or {MAX_TOTAL_BYTES} bytes (hard links count their "
                                     "target's)")
                # staged: what a restore takes, and any file a later link may copy
                staged = taken(member.name) or member.name.startswith(LINKED)
                target = stage / member.name if stage is not None and staged else None
                if target is not None and shutil.disk_usage(stage).free < size + SPARE_BYTES:
                    raise ValueError(f"member {member.name!r}: {size} bytes would leave less "
                                     f"than {SPARE_BYTES} bytes free in {stage.parent}")
                sizes[member.name] = size
                if member.islnk():      # a copy of an earlier member
                    digests[member.name] = digests[member.linkname]
                    if target is not None:
                        with open(stage / member.linkname, "rb") as copied:
                            _copy(copied, target)
                    continue
                source = tar.extractfile(member)
                if member.name == MANIFEST:
                    if member.size > MAX_MANIFEST_BYTES:
                        raise ValueError(f"the manifest is larger than {MAX_MANIFEST_BYTES} bytes")
                    manifest = manifest_digests(source.read())
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
    record, named after a file of the archive's ``results/``, of the fields Snakemake writes
    (rotorvib.pipeline.archive_checks.record_problem)."""
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


class _Folders:
    """The clone's folders on the way to the destinations, each opened once, from the clone's
    root down, without following a link (``O_NOFOLLOW``): a file moved into a folder so opened
    lands in that folder, whatever link a racer puts on its path after the checks."""

    def __init__(self, root: Path):
        self.root = root
        self.open_ = {(): os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)}
        self.made: list[tuple[int, str]] = []      # (parent's descriptor, name), in order

    def get(self, parts: tuple[str, ...]) -> int:
        """The descriptor of the folder ``parts`` below the root, made where missing."""
        if parts not in self.open_:
            parent, name = self.get(parts[:-1]), parts[-1]
            flags = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
            try:
                try:
                    fd = os.open(name, flags, dir_fd=parent)
                except FileNotFoundError:
                    os.mkdir(name, dir_fd=parent)
                    self.made.append((parent, name))
                    fd = os.open(name, flags, dir_fd=parent)
            except OSError as error:
                here = self.root.joinpath(*parts)
                if error.errno == errno.ELOOP:
                    raise ValueError(f"{here} is a symbolic link: a restore writes only "
                                     f"inside {self.root}") from None
                if error.errno == errno.ENOTDIR:
                    raise ValueError(f"{here} is not a folder") from None
                raise
            self.open_[parts] = fd
        return self.open_[parts]

    def close(self) -> None:
        for fd in self.open_.values():
            os.close(fd)


def _move_all(root: Path, stage: Path, plan: dict[str, str]) -> None:
    """Move each staged member to its destination, into its folder as :class:`_Folders` opened
    it; on any failure (a full disk, a race that put a link on the way) undo every move,
    restoring the files replaced (kept under ``stage``, on the same file system) and removing
    the folders made, and raise ``ValueError``."""
    folders, moved = _Folders(root), []     # (folder's descriptor, file name, backup or None)
    (stage / ".replaced").mkdir()
    try:
        for i, (name, relative) in enumerate(plan.items()):
            *parts, leaf = relative.split("/")
            folder, backup = folders.get(tuple(parts)), None
            try:
                mode = os.stat(leaf, dir_fd=folder, follow_symlinks=False).st_mode
            except FileNotFoundError:
                mode = None
            if mode is not None and not stat.S_ISREG(mode):
                raise ValueError(f"{root / relative} is not a regular file")
            if mode is not None:
                backup = stage / ".replaced" / str(i)
                os.replace(leaf, backup, src_dir_fd=folder)
            moved.append((folder, leaf, backup))
            os.replace(stage / name, leaf, dst_dir_fd=folder)
    except (OSError, ValueError) as error:
        undone = _undo(moved, folders.made)
        reason = error.strerror if isinstance(error, OSError) and error.strerror else error
        raise ValueError(f"{relative}: {reason}; "
                         + ("the clone is as it was" if undone else
                            f"could not undo every move (the replaced files are in {stage})")) \
            from None
    finally:
        folders.close()


def _undo(moved, made) -> bool:
    """Undo :func:`_move_all`'s moves, last first, and remove the folders it made; whether all
    were undone."""
    undone = True
    for folder, leaf, backup in reversed(moved):
        try:
            try:
                os.unlink(leaf, dir_fd=folder)
            except FileNotFoundError:
                pass
            if backup is not None:
                os.replace(backup, leaf, dst_dir_fd=folder)
        except OSError:
            undone = False
    for parent, name in reversed(made):
        try:
            os.rmdir(name, dir_fd=parent)
        except OSError:
            undone = False
    return undone


def restore_archive(path: str | Path, sha256: str, root: str | Path = ".") -> list[str]:
    """Restore an archive into the clone at ``root``, trusting nothing in it: the archive's
    SHA-256 must be ``sha256`` (kept outside the archive), every member is checked as by
    :func:`verify_archive`, and only the members it takes
    (rotorvib.pipeline.archive_checks.taken) are written, after every check
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
    if args.sha256 and not is_digest(args.sha256.strip().lower()):
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
