"""Keeping numba's on-disk cache true to the source of a whole package.

numba's ``cache=True`` checks only the file of the function it compiled: a compiled caller keeps
calling the old version of a function from another module that has since been edited (the
balancer's integrators call the right-hand sides, analysers and stop test of other modules).
:func:`drop_if_stale` stamps the package's cache folder with a hash of all its modules and empties
the folder's numba files when the stamp no longer matches; the package calls it before it
compiles or loads anything.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from rotorvib.io.cache_files import write_atomic

STAMP = "numba-sources.sha256"


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
