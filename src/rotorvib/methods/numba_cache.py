"""Keeping numba's on-disk cache true to the source of a whole package, and intact.

numba's ``cache=True`` checks only the file of the function it compiled: a compiled caller keeps
calling the old version of a function from another module that has since been edited (the
balancer's integrators call the right-hand sides, analysers and stop test of other modules).
And it trusts its files: a damaged index or code file (``*.nbi``, ``*.nbc``) fails every later
process that loads it.  :func:`drop_if_stale`, which the package calls before it compiles or
loads anything, keeps a manifest in the package's cache folder (a checked file,
:mod:`rotorvib.io.cache_files`, sealed without the user's key where that key is unusable, so
that numba's cache is still checked and used then, not dropped by every job): the hash of all
the package's modules and the SHA-256 of every numba file it has seen.  It empties the
folder's numba files when the sources changed or, with a one-line warning, when the manifest
itself is damaged; when a file it recorded no
longer matches, it deletes, with a warning, the files of that function only, which numba then
compiles again.  :func:`record` adds the files a process wrote (the package calls it once a compiled
function has been compiled or loaded).  :func:`compile_lock` lets processes that start at once
take turns to compile, so that the later ones load what the first one compiled; a lock held
longer than :data:`LOCK_TIMEOUT` is an error naming the lock file.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import re
import sys
import time
from contextlib import contextmanager
from pathlib import Path

from rotorvib.io.cache_files import read_checked, warn_damaged, write_checked

MANIFEST = "numba-manifest.json"
LOCK = "numba-compile.lock"
#: Seconds to wait for another process's compilation (a cold compile of the balancer takes
#: about a minute on two cores) before saying so, and before giving up.
LOCK_NOTICE, LOCK_TIMEOUT = 10.0, 1800.0


def sources_digest(package_dir: Path) -> str:
    """SHA-256 of the names and contents of the package's modules."""
    h = hashlib.sha256()
    for path in sorted(Path(package_dir).glob("*.py")):
        h.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def _numba_files(cache: Path) -> list[Path]:
    return sorted([*cache.glob("*.nbi"), *cache.glob("*.nbc")])


def _file_digest(path: Path) -> str | None:
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError:
        return None


def _manifest(cache: Path) -> dict | None:
    """The manifest ``{"sources": digest, "files": {name: sha256}}``, None where there is none,
    ``{}`` where it is damaged."""
    text = read_checked(cache / MANIFEST, unkeyed=True)
    if text is None:
        return {} if (cache / MANIFEST).exists() else None
    try:
        manifest = json.loads(text)
    except ValueError:
        return {}
    ok = (isinstance(manifest, dict) and isinstance(manifest.get("sources"), str)
          and isinstance(manifest.get("files"), dict))
    return manifest if ok else {}


def _function(name: str) -> str:
    """The function a numba file belongs to: ``engine._integrate-269.py311`` of both
    ``engine._integrate-269.py311.nbi`` and ``engine._integrate-269.py311.1.nbc``."""
    return re.sub(r"(\.\d+)?\.nb[ic]$", "", name)


def drop_if_stale(package_dir: Path) -> bool:
    """Delete the numba cache files of ``package_dir`` unless they were written for its present
    sources (all of them, where the sources changed or the manifest is missing or damaged) and
    the files of every function whose recorded files no longer match (with a warning); return
    whether any were deleted.  A folder that cannot be written is left as it is (numba then
    compiles in memory)."""
    cache = Path(package_dir) / "__pycache__"
    digest = sources_digest(package_dir)
    manifest = _manifest(cache)
    files = _numba_files(cache)
    if manifest and manifest["sources"] == digest:
        recorded = manifest["files"]
        damaged = {_function(f.name) for f in files
                   if f.name in recorded and _file_digest(f) != recorded[f.name]}
        if not damaged:
            return False
        for function in sorted(damaged):
            warn_damaged(cache / function, " (numba)")
        drop = [f for f in files if _function(f.name) in damaged]
        kept = {name: d for name, d in recorded.items() if _function(name) not in damaged}
    else:
        if manifest == {} and files:
            warn_damaged(cache / MANIFEST)
        drop, kept = files, {}
    try:
        for path in drop:
            path.unlink(missing_ok=True)
    except OSError:
        return True                      # not recorded: the next process tries again
    write_checked(cache / MANIFEST, json.dumps({"sources": digest, "files": kept},
                                               sort_keys=True), unkeyed=True)
    return True


def record(package_dir: Path) -> None:
    """Add the numba files now in the package's cache folder to its manifest (call under
    :func:`compile_lock`, once compiled functions have been compiled or loaded)."""
    cache = Path(package_dir) / "__pycache__"
    manifest = _manifest(cache) or {"sources": sources_digest(package_dir), "files": {}}
    for path in _numba_files(cache):
        if path.name not in manifest["files"] and (digest := _file_digest(path)):
            manifest["files"][path.name] = digest
    write_checked(cache / MANIFEST, json.dumps(manifest, sort_keys=True), unkeyed=True)


@contextmanager
def compile_lock(package_dir: Path, timeout: float = LOCK_TIMEOUT):
    """Hold the package's compile lock, an exclusive ``flock`` on a file in its cache folder,
    while the block compiles (or loads) compiled functions: two workflow jobs that start on an
    empty cache compile one after the other's cache is written, the second in the time it takes
    to load it, instead of both compiling at once.  A wait longer than :data:`LOCK_NOTICE` is
    said on stderr, one longer than ``timeout`` raises ``TimeoutError`` naming the lock file.
    Where the folder cannot be written or the file system has no locks, nothing is held."""
    cache = Path(package_dir) / "__pycache__"
    try:
        cache.mkdir(exist_ok=True)
        handle = open(cache / LOCK, "a")
    except OSError:
        yield
        return
    with handle:
        try:
            _acquire(handle, cache / LOCK, timeout)
        except TimeoutError:
            raise
        except OSError:                        # no locks on this file system
            pass
        yield                                  # closing the file releases the lock


def _acquire(handle, path: Path, timeout: float) -> None:
    start, noticed = time.monotonic(), False
    while True:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except BlockingIOError:
            waited = time.monotonic() - start
            if waited > timeout:
                raise TimeoutError(f"the compile lock {path} has been held by another process "
                                   f"for over {timeout:.0f} s; if no rotorvib process is "
                                   "compiling, delete the file") from None
            if waited > LOCK_NOTICE and not noticed:
                print(f"rotorvib: waiting for the compile lock {path} (another process is "
                      "compiling)", file=sys.stderr, flush=True)
                noticed = True
            time.sleep(0.2)
