"""Cache files beside the package's modules, written whole or not at all, and read only when
they are what the package wrote.

The package keeps derived data in its ``__pycache__`` folders (generated numeric functions,
numba's manifest, code-fingerprint memos); parallel workflow jobs may write the same file at
once, and a file may be damaged (a full disk, an interrupted copy, an edit) or planted (a
cache copied in from elsewhere, a folder others can write).  A checked file begins with an
HMAC-SHA-256 of the rest under this user's key (:func:`user_key`, kept private outside the
package): :func:`read_checked` gives back what :func:`write_checked` wrote for this user, or
nothing, with a one-line warning, for a file that does not match (the caller then rebuilds it).
So generated code runs only if this user's own process wrote it; a checksum computed by anyone
without the key does not match. Where no private key can be kept, nothing is cached.
"""

from __future__ import annotations

import functools
import hashlib
import hmac
import os
import secrets
import stat
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


def key_file() -> Path:
    """Where this user's cache key lives: ``$XDG_CACHE_HOME/rotorvib/cache.key``, by default
    under ``~/.cache``."""
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "rotorvib" / "cache.key"


def _read_key(path: Path) -> bytes | None:
    """The key at ``path`` if it is a regular file of this user that nobody else can read or
    write (opened without following a link), else None."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC)
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        private = stat.S_ISREG(info.st_mode) and info.st_uid == os.getuid() and \
            not info.st_mode & 0o077
        key = os.read(fd, 256).strip() if private else b""
    finally:
        os.close(fd)
    return key if len(key) == 64 else None


@functools.cache
def user_key() -> bytes | None:
    """This user's cache key (32 random bytes, hex), made on first use with mode 600 in a
    folder of mode 700 (written aside and linked into place, so that processes starting at
    once agree on one key); None where it cannot be kept privately (no caching then)."""
    path = key_file()
    if (key := _read_key(path)) is not None:
        return key
    try:
        path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".key-")
        with os.fdopen(fd, "w") as fh:
            fh.write(secrets.token_hex(32) + "\n")
        try:
            os.link(tmp, path)
        except FileExistsError:
            pass                                      # another process made it first
        finally:
            os.unlink(tmp)
    except OSError:
        return None
    return _read_key(path)


def _digest(text: str) -> str | None:
    key = user_key()
    if key is None:
        return None
    return hmac.new(key, text.encode("utf-8", "surrogateescape"), hashlib.sha256).hexdigest()


def write_checked(path: str | Path, text: str) -> bool:
    """:func:`write_atomic` of ``text`` preceded by a line holding its keyed digest; False,
    writing nothing, where there is no key (:func:`user_key`)."""
    digest = _digest(text)
    return digest is not None and write_atomic(path, f"{digest}\n{text}")


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
    """The text :func:`write_checked` wrote to ``path`` for this user; None where there is no
    such file or no key, and None with a warning (the file deleted) where it cannot be read as
    UTF-8 or its keyed digest does not match."""
    try:
        raw = Path(path).read_bytes()
    except OSError:
        return None
    try:
        digest, _, text = raw.decode("utf-8").partition("\n")
    except UnicodeDecodeError:
        digest, text = "", ""
    expected = _digest(text)
    if expected is None:
        return None
    if not hmac.compare_digest(digest.encode("utf-8", "surrogateescape"), expected.encode()):
        warn_damaged(path)
        discard(path)
        return None
    return text
