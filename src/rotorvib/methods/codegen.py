"""Numeric functions generated from sympy expressions, cached on disk as Python source.

Deriving the balancer's linearisation, characteristic polynomial and Taylor terms takes sympy
seconds (simplification, a symbolic determinant), and every workflow job that needs them is a
new process.  :func:`cached_lambdify` keeps the source that ``sympy.lambdify`` generates in the
``__pycache__`` folder beside the module that asks for it, as numba's ``cache=True`` keeps
compiled code, and later processes execute that source instead of deriving again: without
importing sympy, which only a derivation needs.

The cache key is a SHA-256 of the function's name, sympy's version and the source of every
module whose code defines the function's arguments and expressions: editing any of them, or
another sympy, derives afresh.  A cache file is executed only when its checksum matches the
source this module wrote (:mod:`rotorvib.io.cache_files`), in the namespace that
``lambdify(..., "numpy")`` gives its functions (:func:`numpy_namespace`); a cache that cannot be
written (read-only install), is damaged or fails to run is ignored (with a one-line warning)
and the expressions are derived as without it.
"""

from __future__ import annotations

import builtins
import hashlib
import inspect
from importlib.metadata import version
from pathlib import Path
from typing import Callable

from rotorvib.io.cache_files import discard, read_checked, warn_damaged, write_checked


#: The files this process's generated functions are keyed on (:func:`cached_lambdify`'s
#: ``sources``): code its results rest on that it need not have imported.
KEYED: set[Path] = set()


def _key(name: str, sources: tuple[Path, ...]) -> str:
    h = hashlib.sha256(f"{name}|sympy {version('sympy')}".encode())
    for source in sources:
        h.update(source.read_bytes())
    return h.hexdigest()[:20]


def numpy_namespace() -> dict:
    """The globals ``sympy.lambdify(..., "numpy")`` gives its generated functions, built as
    sympy builds them (``sympy.utilities.lambdify``: its numpy module's default ``I``, imports
    and translation, ``Abs``, ``builtins`` and ``range``) without importing sympy;
    ``tests/test_codegen.py`` compares them with sympy's."""
    namespace = {"I": 1j}
    exec("import numpy; from numpy import *; from numpy.linalg import *", {}, namespace)
    namespace["Heaviside"] = namespace["heaviside"]
    namespace.setdefault("Abs", abs)
    namespace.update(builtins=builtins, range=range)
    return namespace


def _load(path: Path) -> Callable | None:
    """The function cached at ``path``, or None (a damaged file, one whose checksum does not
    match what :func:`cached_lambdify` wrote, or one that fails to run, is ignored and
    rebuilt, with a one-line warning)."""
    source = read_checked(path)
    if source is None:
        return None
    try:
        namespace = numpy_namespace()
        exec(compile(source, str(path), "exec"), namespace)
        return namespace["_lambdifygenerated"]
    except Exception as error:  # whatever the file does: derive afresh
        warn_damaged(path, f" ({type(error).__name__})")
        discard(path)
        return None


def cached_lambdify(name: str, build: Callable[[], tuple[tuple, object]], *,
                    sources: tuple[str | Path, ...]) -> Callable:
    """``sympy.lambdify(args, expr, "numpy")`` for ``(args, expr) = build()``, from the disk
    cache when the ``sources`` (the files whose code defines ``build``'s arguments and
    expressions, one function for each ``name``; the first one's folder holds the cache) and
    sympy are unchanged since it was generated: sympy is imported only to generate it."""
    sources = tuple(Path(source) for source in sources)
    KEYED.update(sources)
    path = sources[0].parent / "__pycache__" / f"{name}.{_key(name, sources)}.lambdify"
    if (f := _load(path)) is not None:
        return f
    import sympy as sp

    f = sp.lambdify(*build(), "numpy")
    write_checked(path, inspect.getsource(f))      # parallel jobs never read half a file
    return f
