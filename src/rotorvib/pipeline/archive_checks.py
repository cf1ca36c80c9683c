"""What a results archive may hold (rotorvib.pipeline.archive_restore reads it): the members
a restore takes (:func:`taken`), the bounds on what it reads, tar headers checked from the
tar format itself before tarfile reads them (:class:`CheckedTarStream`), the members
(:func:`member_problem`) and job records (:func:`record_problem`) accepted, and the manifest's
lines (:func:`manifest_digests`)."""

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
#: A tar header's block, and the typeflags :class:`CheckedTarStream` reads: the extended
#: headers (GNU's long name and long link, pax headers, for one member or global, and Solaris'
#: pax header), of them pax's, GNU's types and sparse file, and the types no data follows (hard
#: and symbolic links, devices, folders, fifos).
_TAR_BLOCK = 512
_EXTENDED = (b"L", b"K", b"x", b"g", b"X")
_PAX = (b"x", b"g", b"X")
_GNU = (b"L", b"K", b"S")
_SPARSE = b"S"
_NO_DATA = (b"1", b"2", b"3", b"4", b"5", b"6")


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


class CheckedTarStream:
    """A decompressed tar stream (``fh``: its ``read``), read through so that each header is
    checked before any byte of it is passed on: given to ``tarfile.open(fileobj=...,
    mode="r|")``, it lets tarfile read only headers that passed. Each header is read from the
    public tar format (a 512-byte block: the typeflag at offset 156, the size at 124, the
    checksum at 148) and refused, as ``ValueError``, when its checksum is wrong or its size
    does not parse (:func:`_number`), when it is an extended header (:data:`_EXTENDED`, whose
    data tarfile reads whole, and a chain of them by recursion) over :data:`MAX_HEADER_BYTES`
    or more than :data:`MAX_HEADERS_IN_A_ROW` in a row, and when it makes a sparse file (its
    typeflag, or a pax header's keys: tarfile reads a sparse map unbounded). A pax header's
    records, bounded so, are read before it is passed on (:func:`_pax_problem`). A member's data
    passes unchecked, in the reads tarfile asks for, never held whole; after the
    all-zero block that ends the archive, tarfile reads no header, and the rest passes too.

    The check runs in the same pass as tarfile's read (and the hash of the bytes read,
    rotorvib.pipeline.archive_restore), one header ahead of it, not as a pass of its own: a file
    replaced between two passes would have its headers read by tarfile unchecked (the digest
    of the bytes read is compared only after, and a verify without a published digest compares
    none), whereas here the bytes checked are the bytes tarfile reads."""

    def __init__(self, fh):
        self.fh, self.offset, self.ready = fh, 0, b""
        self.data = 0           # bytes of the current member's data (in blocks) still to pass
        self.in_a_row = 0       # extended headers just passed
        self.ended = False      # after the archive's end (or a truncated header)

    def read(self, size=-1) -> bytes:
        if size is None or size < 0:
            return b"".join(iter(lambda: self.read(_TAR_BLOCK * 20), b""))
        if not self.ready and size:
            if self.ended or self.data:
                data = self.fh.read(size if self.ended else min(size, self.data))
                self.offset += len(data)
                self.data -= 0 if self.ended else len(data)
                return data
            self.ready = self._header()
        passed, self.ready = self.ready[:size], self.ready[size:]
        return passed

    def _exactly(self, size: int) -> bytes:
        """``size`` bytes of the stream, fewer only at its end."""
        parts, left = [], size
        while left and (part := self.fh.read(left)):
            parts.append(part)
            left -= len(part)
        self.offset += size - left
        return b"".join(parts)

    def _header(self) -> bytes:
        """The next header, checked, with an extended header's data; what the archive ends
        with (an all-zero block, a truncated one) unchecked."""
        block = self._exactly(_TAR_BLOCK)
        if len(block) < _TAR_BLOCK or block.count(0) == _TAR_BLOCK:
            self.ended = True
            return block
        kind, name, size = block[156:157], _header_name(block), _number(block[124:136])
        if not _checksum_holds(block):
            raise ValueError(f"member {name!r}: a tar header whose checksum is wrong (at byte "
                             f"{self.offset - _TAR_BLOCK} of the tar stream)")
        if size is None:
            raise ValueError(f"member {name!r}: a tar header whose size field does not parse "
                             f"({block[124:136]!r})")
        if kind == _SPARSE:
            raise ValueError(f"member {name!r} is a sparse file")
        blocks = -(-size // _TAR_BLOCK) * _TAR_BLOCK
        if kind not in _EXTENDED:
            self.in_a_row = 0
            # as tarfile: no data after a link, device, folder or fifo, whatever the size says
            # (nor after a regular file of the old format named as a folder, ending in '/')
            folder = kind == b"\0" and block[:100].split(b"\0", 1)[0].endswith(b"/")
            self.data = 0 if kind in _NO_DATA or folder else blocks
            return block
        self.in_a_row += 1
        if size > MAX_HEADER_BYTES:
            raise ValueError(f"member {name!r}: an extended header of {size} bytes, over the "
                             f"bound of {MAX_HEADER_BYTES}")
        if self.in_a_row > MAX_HEADERS_IN_A_ROW:
            raise ValueError(f"member {name!r}: more than {MAX_HEADERS_IN_A_ROW} extended "
                             "headers in a row")
        data = self._exactly(blocks)
        if kind in _PAX and (problem := _pax_problem(data)):
            raise ValueError(f"member {name!r}{problem}")
        return block + data


def _number(field: bytes) -> int | None:
    """A tar header's number field as tarfile reads it, or None: octal digits (up to a NUL,
    blanks around; none is 0), or GNU's base-256 (a first byte of 0x80, then the number
    big-endian). Anything else, a negative base-256 number (first byte 0xff) too, is None."""
    if field[0] == 0x80:
        return int.from_bytes(field[1:], "big")
    digits = field.split(b"\0", 1)[0].strip()
    return int(digits or b"0", 8) if re.fullmatch(rb"[0-7]*", digits) else None


def _checksum_holds(block: bytes) -> bool:
    """Whether a header's checksum field (offset 148, 8 bytes, a number as :func:`_number`
    reads it) is the sum of its bytes, the field counted as spaces: unsigned, as the format has
    it, or signed, as some old tars wrote it (tarfile takes either)."""
    stored, rest = _number(block[148:156]), block[:148] + block[156:]
    unsigned = sum(rest) + 8 * 0x20
    return stored == unsigned or stored == unsigned - 256 * sum(byte >= 0x80 for byte in rest)


def _header_name(block: bytes) -> str:
    """A header's name, as tarfile gives it (ustar's prefix joined, but to GNU's headers)."""
    name, prefix = (block[a:b].split(b"\0", 1)[0].decode(tarfile.ENCODING, "surrogateescape")
                    for a, b in ((0, 100), (345, 500)))
    return f"{prefix}/{name}" if prefix and block[156:157] not in _GNU else name


def _pax_problem(data: bytes) -> str | None:
    """Why a pax header's records (``<length> <keyword>=<value>\\n``, in all its blocks, up
    to a NUL) are refused, or None: records that do not parse, a key of GNU's sparse files, or
    a size (:class:`CheckedTarStream` takes each member's size from its own header; members are
    bounded well under the 8 GiB its field holds)."""
    at = 0
    while at < len(data) and data[at] != 0:
        match = re.match(rb"([0-9]{1,20}) ", data[at:at + 21])
        end = at + int(match[1]) if match else at
        if not match or not at + match.end() < end <= len(data) or data[end - 1] != 0x0A:
            return ": a pax header whose records do not parse"
        keyword, equals, _ = data[at + match.end():end - 1].partition(b"=")
        if not keyword or not equals:
            return ": a pax header whose records do not parse"
        if keyword.startswith(b"GNU.sparse."):
            return " is a sparse file"
        if keyword == b"size":
            return ": a pax header that sets a member's size"
        at = end
    return None


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
