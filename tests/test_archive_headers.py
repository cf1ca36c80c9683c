"""The check of an archive's tar headers from the tar format itself, in the stream tarfile reads
(rotorvib.pipeline.archive_checks.CheckedTarStream): archives that tarfile writes pass whole
and read as they do without it; a wrong checksum, a size that does not parse, a chain of
extended headers, a sparse file and a pax header that sets a size are refused, each from its
header, before tarfile reads it."""

import io
import tarfile
from functools import partial

import pytest

from rotorvib.pipeline.archive_checks import (
    MAX_HEADER_BYTES,
    MAX_HEADERS_IN_A_ROW,
    CheckedTarStream,
)

LONG = "results/" + "/".join(["d" * 40] * 4) + "/" + "f" * 50 + ".nc"    # 225 characters


def _written(fmt, pax_headers=None) -> bytes:
    """An archive as tarfile writes it in format ``fmt``: long names and a long link (under the
    bound), an empty file, a file of 100 kB, a folder, a symbolic and a hard link."""
    out, target = io.BytesIO(), "results/empty" if fmt == tarfile.USTAR_FORMAT else LONG
    with tarfile.open(fileobj=out, mode="w", format=fmt, pax_headers=pax_headers) as tar:
        for name, data in [(LONG, b"a" * 1000), ("results/empty", b""),
                           ("results/big.bin", bytes(range(256)) * 400),
                           ("results/" + "n" * 90 + "/" + "m" * 90, b"b")]:
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
        for name, kind, link in [("results/dir", tarfile.DIRTYPE, ""),
                                 ("results/sym", tarfile.SYMTYPE, target),
                                 ("results/hard", tarfile.LNKTYPE, target)]:
            info = tarfile.TarInfo(name)
            info.type, info.linkname = kind, link
            tar.addfile(info)
    return out.getvalue()


def _members(stream) -> list:
    """Each member of the tar stream ``stream`` as tarfile reads it: name, type, link, bytes."""
    with tarfile.open(fileobj=stream, mode="r|") as tar:
        return [(m.name, m.type, m.linkname, tar.extractfile(m).read() if m.isfile() else None)
                for m in tar]


def _with(block: bytes, at: int, field: bytes) -> bytes:
    """A header block with ``field`` written at offset ``at``, its checksum made right again."""
    block = bytearray(block)
    block[at:at + len(field)] = field
    block[148:156] = b" " * 8
    block[148:156] = b"%06o\0 " % sum(block)
    return bytes(block)


def _header(name, kind=tarfile.REGTYPE, size=0) -> bytes:
    info = tarfile.TarInfo(name)
    info.type, info.size = kind, size
    return info.tobuf(tarfile.USTAR_FORMAT)


def _record(text: bytes) -> bytes:
    """A pax record of ``text`` (``keyword=value``), its length in front."""
    length = len(text) + 3
    while len(b"%d %s\n" % (length, text)) != length:
        length += 1
    return b"%d %s\n" % (length, text)


def _pax(records: bytes, kind=tarfile.XHDTYPE) -> bytes:
    """A pax header of ``records``, in its blocks."""
    return _header("././@PaxHeader", kind, len(records)) + records + b"\0" * (-len(records) % 512)


def _refused(data: bytes, words: str):
    """The check refuses ``data`` with a line holding ``words``, before tarfile reads it."""
    with pytest.raises(ValueError, match=words) as error:
        _members(CheckedTarStream(io.BytesIO(data)))
    assert len(str(error.value).splitlines()) == 1
    return str(error.value)


END = b"\0" * 1024


@pytest.mark.parametrize("fmt", [tarfile.USTAR_FORMAT, tarfile.GNU_FORMAT, tarfile.PAX_FORMAT])
def test_an_archive_tarfile_writes_passes_whole_and_reads_the_same(fmt):
    data = _written(fmt, {"comment": "global"} if fmt == tarfile.PAX_FORMAT else None)
    assert CheckedTarStream(io.BytesIO(data)).read() == data
    members = _members(CheckedTarStream(io.BytesIO(data)))
    assert members == _members(io.BytesIO(data))
    assert [m[0] for m in members][:1] == [LONG] and len(members) == 7


def test_the_bytes_pass_unchanged_whatever_the_reads():
    data = _written(tarfile.GNU_FORMAT)
    for size in (1, 7, 512, 10240):
        stream = CheckedTarStream(io.BytesIO(data))
        assert b"".join(iter(partial(stream.read, size), b"")) == data


@pytest.mark.parametrize("at", [0, 1536])
def test_a_header_whose_checksum_is_wrong_is_refused(at):
    """A byte of a header changed (the first member's name; the second's), not its checksum."""
    data = bytearray(_written(tarfile.USTAR_FORMAT))
    data[at + 3] ^= 0x01
    _refused(bytes(data), f"member '.*: a tar header whose checksum is wrong \\(at byte {at} ")


def test_a_base256_size_is_read_as_tarfile_reads_it():
    """GNU's base-256 size field (a first byte of 0x80): the member's data is skipped by that
    size, and the next header found where tarfile finds it."""
    data = b"z" * 1000
    header = _with(_header("results/a.bin", size=1000), 124, b"\x80" + (1000).to_bytes(11, "big"))
    archive = (header + data + b"\0" * 24 + _header("results/b", size=0) + END)
    assert _members(CheckedTarStream(io.BytesIO(archive))) == [
        ("results/a.bin", tarfile.REGTYPE, "", data), ("results/b", tarfile.REGTYPE, "", b"")]


@pytest.mark.parametrize("field", [b"\xff" * 12, b"\x81" + b"\0" * 11, b"0000000001x\0",
                                   b"0o000000017\0", b"-0000000001\0"])
def test_a_size_field_that_does_not_parse_is_refused(field):
    """A negative base-256 number, a high first byte other than 0x80, and octal ASCII with
    anything but digits 0-7 and blanks (Python's int would take a sign or a prefix)."""
    header = _with(_header("results/a.bin"), 124, field)
    _refused(header + END, "member 'results/a.bin': a tar header whose size field does not parse")


@pytest.mark.parametrize("kind", [tarfile.XHDTYPE, tarfile.GNUTYPE_LONGNAME])
def test_a_long_chain_of_extended_headers_is_refused_at_the_first_too_many(kind):
    """Three extended headers before a member pass; a fourth, of a chain of 10 000, is refused
    after reading four headers' blocks (tarfile would read the chain by recursion)."""
    one = _pax(b"11 path=ab\n", kind) if kind == tarfile.XHDTYPE else (
        _header("././@LongLink", kind, 3) + b"ab\0" + b"\0" * 509)
    member = _header("results/a", size=1) + b"x" + b"\0" * 511
    assert _members(CheckedTarStream(io.BytesIO(one * MAX_HEADERS_IN_A_ROW + member + END))) == [
        ("ab", tarfile.REGTYPE, "", b"x")]
    stream = CheckedTarStream(io.BytesIO(one * 10_000 + member + END))
    with pytest.raises(ValueError, match=f"more than {MAX_HEADERS_IN_A_ROW} extended headers "
                                         "in a row"):
        _members(stream)
    assert stream.offset == MAX_HEADERS_IN_A_ROW * len(one) + 512


def test_an_extended_header_over_the_bound_is_refused_from_its_header():
    stream = CheckedTarStream(io.BytesIO(_header("././@LongLink", tarfile.GNUTYPE_LONGNAME,
                                                 MAX_HEADER_BYTES + 1) + b"a" * (1 << 20)))
    with pytest.raises(ValueError, match=f"an extended header of {MAX_HEADER_BYTES + 1} bytes"):
        _members(stream)
    assert stream.offset == 512


SPARSE = {   # how a sparse member is announced -> its header(s)
    "GNU type S": _header("results/s", tarfile.GNUTYPE_SPARSE, 0),
    "pax 0.1 map": _pax(_record(b"GNU.sparse.map=0,1")) + _header("results/s", size=1),
    "pax 1.0": _pax(_record(b"GNU.sparse.major=1") + _record(b"GNU.sparse.minor=0"))
               + _header("results/s"),
    "pax global": _pax(_record(b"GNU.sparse.size=10"), tarfile.XGLTYPE) + _header("results/s"),
    # a record after the header's size, in its last block: tarfile reads it too
    "pax padding": _header("././@PaxHeader", tarfile.XHDTYPE, 11)
                   + (b"11 path=ab\n" + _record(b"GNU.sparse.map=0,1")).ljust(512, b"\0")
                   + _header("results/s", size=1),
}


@pytest.mark.parametrize("kind", sorted(SPARSE))
def test_a_sparse_member_is_refused(kind):
    assert len(SPARSE[kind]) % 512 == 0
    _refused(SPARSE[kind] + b"\0" * 512 + END, "is a sparse file")


@pytest.mark.parametrize("records, words", [
    (b"12 size=100\n", "a pax header that sets a member's size"),
    (b"11 path=ab\n9 x\n", "a pax header whose records do not parse"),
    (b"11 path=ab", "a pax header whose records do not parse"),
    (b"99 path=ab\n", "a pax header whose records do not parse"),
    (b"0 path=ab\n", "a pax header whose records do not parse"),
])
def test_a_pax_header_that_sets_a_size_or_does_not_parse_is_refused(records, words):
    """The check reads each member's size from its own header, and the keys of records it can
    delimit as tarfile does."""
    _refused(_pax(records) + _header("results/a") + END, words)


@pytest.mark.parametrize("kind", [tarfile.DIRTYPE, tarfile.SYMTYPE, tarfile.LNKTYPE,
                                  tarfile.CHRTYPE, tarfile.FIFOTYPE, "old folder"])
def test_no_data_is_skipped_after_a_member_that_has_none_whatever_its_size(kind):
    """A folder, link or device whose size field says 512 bytes: tarfile reads the next header
    right after it (here a sparse member), and so does the check, which refuses it."""
    header = (_header("results/d/", tarfile.AREGTYPE, 512) if kind == "old folder"
              else _header("results/d", kind, 512))
    _refused(header + SPARSE["GNU type S"] + END, "member 'results/s' is a sparse file")
