"""What a results archive may hold (rotorvib.pipeline.archive_restore reads it): the members
a restore takes (:func:`taken`), the bounds on what it reads, tar headers bounded before
tarfile reads them (:class:`BoundedTar`), the members (:func:`member_problem`) and job records
(:func:`record_problem`) accepted, and the manifest's lines (:func:`manifest_digests`)."""

from __future__ import annotations

import base64
import binascii
import json
import re
import tarfile

from rotorvib.pipeline.archive import CRATE, LINKED, METADATA_DIR

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
#: archive: about 700 members, 60 MB.
MAX_MEMBERS = 100_000
MAX_MEMBER_BYTES = 1 << 30
MAX_TOTAL_BYTES = 16 << 30
MAX_MANIFEST_BYTES = 32 << 20
MAX_RECORD_BYTES = 4 << 20
MAX_HEADER_BYTES = 64 << 10
MAX_HEADERS_IN_A_ROW = 3
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


class BoundedTar(tarfile.TarFile):
    """A tar reader whose headers are bounded (:class:`_BoundedInfo`)."""

    tarinfo = _BoundedInfo
    headers_in_a_row = 0


def member_problem(member: tarfile.TarInfo, earlier: dict[str, str]) -> str | None:
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


def manifest_digests(data: bytes) -> dict[str, str]:
    """The manifest's lines, ``<64 hex digits>  <name>``, as name -> digest."""
    expected = {}
    for line in data.decode("utf-8").splitlines():
        digest, sep, name = line.partition("  ")
        if not sep or not is_digest(digest) or name in expected:
            raise ValueError(f"manifest line {line[:80]!r} is not '<sha256>  <name>'")
        expected[name] = digest
    return expected


def is_digest(text: str) -> bool:
    """Whether ``text`` is a SHA-256 as ``sha256sum`` writes it: 64 lowercase hex digits."""
    return re.fullmatch(r"[0-9a-f]{64}", text) is not None
