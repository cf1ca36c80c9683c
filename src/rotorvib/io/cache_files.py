"""Cache files beside the package's modules, written whole or not at all.

The package keeps derived data in its ``__pycache__`` folders (generated numeric functions,
numba's stamp, code-fingerprint memos); parallel workflow jobs may write the same file at once.
"""

from __future__ import annotations

import os
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
