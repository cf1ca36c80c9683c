"""Cache files beside the package's modules, written whole or not at all, and read only when
they are what the package wrote.

The package keeps derived data in its ``__pycache__`` folders (generated numeric functions,
numba's manifest, code-fingerprint memos); parallel workflow jobs may write the same file at
once, and a file may be damaged (a full disk, an interrupted copy, an edit) or planted (a
cache copied in from elsewhere, a folder others can write).  A checked file begins with an
HMAC-SHA-256 under this user's key (:func:`user_key`, kept private outside the package) of its
name and the rest: :func:`read_checked` gives back what :func:`write_checked` wrote for this
user under that name, or nothing, with a one-line warning, for a file that does not match (the
caller then rebuilds it).  So generated code runs only if this user's own process wrote it,
and only as the function it was written for (its file's name, the function's name and the
hash of its sources, is signed with it: a valid file of another function copied over it does
not match); a checksum computed by anyone without the key does not match.

Where no private key can be kept (a key file others can read, a link, not a regular file, a
read-only home), one warning per process names the key file and why, and nothing keyed is
cached.  A file that guards against damage and staleness rather than planting (numba's
manifest, whose files numba loads unchecked from the folder, as Python its ``.pyc`` files, so
that whoever can plant a manifest there can plant code anyway) is then sealed with a plain
SHA-256 (``unkeyed=True``), so that numba's cache is still checked and kept, not dropped by
every job.
"""

from __future__ import annotations

import errno
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


def _read_key(path: Path) -> tuple[bytes | None, str]:
    """The key at ``path`` and ``""``, or None and why it is refused (``""``: there is none).
    The file must be a regular file of this user that nobody else can read or write; it is
    opened without following a link and without blocking (a FIFO would block the open, and
    the job, for ever) and checked on the descriptor before anything is read."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except FileNotFoundError:
        return None, ""
    except OSError as error:
        if error.errno == errno.ELOOP:
            return None, "it is a symbolic link"
        return None, f"it cannot be opened ({error.strerror})"
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            return None, "it is not a regular file"
        if info.st_uid != os.getuid():
            return None, f"it belongs to uid {info.st_uid}, not to this user"
        if info.st_mode & 0o077:
            return None, f"others can read or write it (mode {stat.S_IMODE(info.st_mode):o})"
        key = os.read(fd, 256).strip()
    finally:
        os.close(fd)
    if len(key) != 64:
        return None, "it does not hold a key (64 hexadecimal digits)"
    return key, ""


def _refuse_key(path: Path, why: str) -> None:
    print(f"rotorvib: cache key {path} refused: {why}; generated code and memos are not "
          "cached, numba's cache is checked without the key (delete the file, or fix its "
          "folder, for a new key)", file=sys.stderr)


@functools.cache
def user_key() -> bytes | None:
    """This user's cache key (32 random bytes, hex), made on first use with mode 600 in a
    folder of mode 700 (written aside and linked into place, so that processes starting at
    once agree on one key); None, with one warning per process naming the file and why, where
    it cannot be kept privately (nothing keyed is cached then)."""
    path = key_file()
    key, why = _read_key(path)
    if key is None and not why:
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
        except OSError as error:
            why = f"it cannot be made ({error.strerror})"
        else:
            key, why = _read_key(path)
    if key is None:
        _refuse_key(path, why or "it vanished as it was made")
    return key


UNKEYED = "sha256:"


def _seal(path: str | Path, text: str, unkeyed: bool) -> str | None:
    """The seal of ``text`` written at ``path``: its name and text's HMAC under the user's key;
    where there is none, their plain SHA-256 (prefixed :data:`UNKEYED`) if ``unkeyed``, else
    None."""
    message = f"{Path(path).name}\0{text}".encode("utf-8", "surrogateescape")
    key = user_key()
    if key is not None:
        return hmac.new(key, message, hashlib.sha256).hexdigest()
    return UNKEYED + hashlib.sha256(message).hexdigest() if unkeyed else None


def write_checked(path: str | Path, text: str, *, unkeyed: bool = False) -> bool:
    """:func:`write_atomic` of ``text`` preceded by a line holding its seal (:func:`_seal`);
    False, writing nothing, where there is no key and not ``unkeyed``."""
    seal = _seal(path, text, unkeyed)
    return seal is not None and write_atomic(path, f"{seal}\n{text}")


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


def read_checked(path: str | Path, *, unkeyed: bool = False) -> str | None:
    """The text :func:`write_checked` wrote to ``path`` (under this name) for this user; None
    where there is no such file or no seal to check it with, None with the file deleted where
    ``unkeyed`` and it was sealed the other way (with a key while there is none, or without
    one while there is: it is rebuilt, not damaged), and None with a warning (the file
    deleted) where it cannot be read as UTF-8 or its seal does not match."""
    try:
        raw = Path(path).read_bytes()
    except OSError:
        return None
    try:
        seal, _, text = raw.decode("utf-8").partition("\n")
    except UnicodeDecodeError:
        seal, text = "", ""
    expected = _seal(path, text, unkeyed)
    if expected is None:
        return None
    if unkeyed and seal.startswith(UNKEYED) != expected.startswith(UNKEYED):
        discard(path)
        return None
    if not hmac.compare_digest(seal.encode("utf-8", "surrogateescape"), expected.encode()):
        warn_damaged(path)
        discard(path)
        return None
    return text
