"""Keeping numba's on-disk cache true to the source of a whole package.

numba's ``cache=True`` checks only the file of the function it compiled: a compiled caller keeps
calling the old version of a function from another module that has since been edited (the
balancer's integrators call the right-hand sides, analysers and stop test of other modules).
:func:`drop_if_stale` stamps the package's cache folder with a hash of all its modules and empties
the folder's numba files when the stamp no longer matches; the package calls it before it
compiles or loads anything.  :func:`compile_lock` lets processes that start at once take turns
to compile, so that the later ones load what the first one compiled.
"""

from __future__ import annotations

import fcntl
import hashlib
from contextlib import contextmanager
from pathlib import Path

from rotorvib.io.cache_files import write_atomic

STAMP = "numba-sources.sha256"
LOCK = "numba-compile.lock"


def sources_digest(package_dir: Path) -> str:
    """SHA-256 of the names and contents of the package's modules."""
    h = hashlib.sha256()
    for path in sorted(Path(package_dir).glob("*.py")):
        h.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return h.hexdigest()


def drop_if_stale(package_dir: Path) -> bool:
    """Delete the numba cache files (``*.nbi``, ``*.nbc``) of ``package_dir`` unless they were
    written for its present sources; return whether they were deleted.  A folder that cannot be
    written is left as it is (numba then compiles in memory)."""
    cache = Path(package_dir) / "__pycache__"
    digest = sources_digest(package_dir)
    try:
        if (cache / STAMP).read_text() == digest:
            return False
    except OSError:
        pass
    try:
        for path in [*cache.glob("*.nbi"), *cache.glob("*.nbc")]:
            path.unlink(missing_ok=True)
    except OSError:
        return True                      # not stamped: the next process tries again
    write_atomic(cache / STAMP, digest)
    return True


@contextmanager
def compile_lock(package_dir: Path):
    """Hold the package's compile lock, an exclusive ``flock`` on a file in its cache folder,
    while the block compiles (or loads) compiled functions: two workflow jobs that start on an
    empty cache compile one after the other's cache is written, the second in the time it takes
    to load it, instead of both compiling at once. Where the folder cannot be written or the
    file system has no locks, nothing is held."""
    cache = Path(package_dir) / "__pycache__"
    try:
        cache.mkdir(exist_ok=True)
        handle = open(cache / LOCK, "a")
    except OSError:
        yield
        return
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX)
        except OSError:
            pass
        yield                                  # closing the file releases the lock
