"""Cache files beside the package's modules, written whole or not at all, and read only when
they are what the package wrote.

The package keeps derived data in its ``__pycache__`` folders (generated numeric functions,
numba's manifest, code-fingerprint memos); parallel workflow jobs may write the same file at
once, and a file may be damaged (a full disk, an interrupted copy, an edit).  A checked file
begins with the SHA-256 of the rest: :func:`read_checked` gives back what
:func:`write_checked` wrote, or nothing, with a one-line warning, for a file that does not
match (the caller then rebuilds it).  The checksum detects damage; it is no signature: whoever
can write the package's folders can also change its code.
"""

from __future__ import annotations

import hashlib
import os
import sys
import tempfile
from pathlib import Path


def write_atomic(path: str | Path, text: str) -> bool:
    """Write ``text`` to ``path`` through a temporary file and a rename, so that a reader sees
    the old file or the whole new one; return False, writing nothing, where the folder cannot
    be written (a read-only install: the cache is then simply not kept)."""
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except OSError:
        return False
    return True


def _digest(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def write_checked(path: str | Path, text: str) -> bool:
    """:func:`write_atomic` of ``text`` preceded by a line holding its SHA-256."""
    return write_atomic(path, f"{_digest(text)}\n{text}")


def warn_damaged(path: str | Path, what: str = "") -> None:
    """The one-line warning of a damaged cache file that is ignored and rebuilt."""
    print(f"rotorvib: damaged cache file {path}{what} ignored; it is rebuilt", file=sys.stderr)


def discard(path: str | Path) -> None:
    """Remove a cache file if it is there; a file that cannot be removed is left for the next
    writer to replace."""
    try:
        Path(path).unlink(missing_ok=True)
    except OSError:
        pass


def read_checked(path: str | Path) -> str | None:
    """The text :func:`write_checked` wrote to ``path``; None where there is no such file, and
    None with a warning (the file deleted) where it cannot be read as UTF-8 or its checksum does
    not match."""
    try:
        raw = Path(path).read_bytes()
    except OSError:
        return None
    try:
        digest, _, text = raw.decode("utf-8").partition("\n")
    except UnicodeDecodeError:
        digest, text = "", ""
    if digest != _digest(text):
        warn_damaged(path)
        discard(path)
        return None
    return text
