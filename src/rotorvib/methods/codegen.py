"""Numeric functions generated from sympy expressions, cached on disk as Python source.

Deriving the balancer's linearisation, characteristic polynomial and Taylor terms takes sympy
seconds (simplification, a symbolic determinant), and every workflow job that needs them is a
new process.  :func:`cached_lambdify` keeps the source that ``sympy.lambdify`` generates in the
``__pycache__`` folder beside the module that asks for it, as numba's ``cache=True`` keeps
compiled code, and later processes execute that source instead of deriving again.

The cache key is a SHA-256 of the function's name and arguments, sympy's version and the source
of every module whose code defines the expressions: editing any of them, or another sympy,
derives afresh.  A cache file is executed only when its checksum matches the source this
module wrote (:mod:`rotorvib.io.cache_files`); a cache that cannot be written (read-only
install), is damaged or fails to run is ignored (with a one-line warning) and the expressions
are derived as without it.
"""

from __future__ import annotations

import hashlib
import inspect
from pathlib import Path
from types import ModuleType
from typing import Callable

import sympy as sp

from rotorvib.io.cache_files import discard, read_checked, warn_damaged, write_checked


def _key(name: str, args, modules: tuple[ModuleType, ...]) -> str:
    h = hashlib.sha256(f"{name}|{args!r}|sympy {sp.__version__}".encode())
    for module in modules:
        h.update(inspect.getsource(module).encode())
    return h.hexdigest()[:20]


def _numpy_namespace() -> dict:
    """The globals ``sympy.lambdify(..., "numpy")`` gives its generated functions."""
    return dict(sp.lambdify((), 0, "numpy").__globals__)


def _load(path: Path) -> Callable | None:
    """The function cached at ``path``, or None (a damaged file, one whose checksum does not
    match what :func:`cached_lambdify` wrote, or one that fails to run, is ignored and
    rebuilt, with a one-line warning)."""
    source = read_checked(path)
    if source is None:
        return None
    try:
        namespace = _numpy_namespace()
        exec(compile(source, str(path), "exec"), namespace)
        return namespace["_lambdifygenerated"]
    except Exception as error:  # whatever the file does: derive afresh
        warn_damaged(path, f" ({type(error).__name__})")
        discard(path)
        return None


def cached_lambdify(name: str, args, build: Callable[[], object], *,
                    modules: tuple[ModuleType, ...]) -> Callable:
    """``sympy.lambdify(args, build(), "numpy")``, from the disk cache when ``modules`` (the
    first one's folder holds the cache) and sympy are unchanged since it was generated."""
    path = (Path(modules[0].__file__).parent / "__pycache__"
            / f"{name}.{_key(name, args, modules)}.lambdify")
    if (f := _load(path)) is not None:
        return f
    f = sp.lambdify(args, build(), "numpy")
    write_checked(path, inspect.getsource(f))      # parallel jobs never read half a file
    return f
