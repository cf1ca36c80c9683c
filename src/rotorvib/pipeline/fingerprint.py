"""Code fingerprints derived from imports: which library source a workflow job runs.

The workflow gives every script rule a ``code`` parameter, the SHA-256 of the *behaviour* of the
library modules the script can load: the import closure of the script inside the ``rotorvib``
package (every ``import`` and ``from ... import`` statement, at any depth but inside an
``if TYPE_CHECKING:`` block, followed transitively, with the ``__init__`` of every enclosing
package).  Each module enters the hash as
its syntax tree with docstrings removed and without positions, so comments, docstrings and
formatting do not change it and a comment does not rerun a long study.  Nothing is declared by
hand: a new import is a new dependency.

Modules a script loads by name at run time (``importlib.import_module(params.module)``) are not
visible in its source; the rule passes them as extra entry points.

Parsing every module costs about half a second, paid by every ``snakemake`` command: a module's
imports and the digest of its normalised tree are kept in a memo (``__pycache__/fingerprints``
beside this module), keyed by the module's text, this module's own code and Python's version,
so an entry never outlives what it was computed from.  Within a process each module is read
once, for every script that imports it (:func:`forget_modules` reads the tree afresh).
"""

from __future__ import annotations

import ast
import hashlib
import json
import sys
from functools import lru_cache
from pathlib import Path

from rotorvib.io.cache_files import read_checked, warn_damaged, write_checked

PACKAGE = "rotorvib"
#: The memo's folder, and what its entries depend on besides a module's text.
MEMO = Path(__file__).parent / "__pycache__" / "fingerprints"
#: The folder the imported package lives in (``src`` of a clone, or ``site-packages``): the
#: closures and fingerprints read the code that runs, wherever Snakemake's working folder is.
SOURCES = Path(__file__).resolve().parents[2]
_MEMO_VERSION = hashlib.sha256(Path(__file__).read_bytes() + sys.version.encode()).hexdigest()


def _names(value) -> bool:
    return isinstance(value, list) and all(isinstance(v, str) for v in value)


def _hex_digest(value) -> bool:
    return isinstance(value, str) and len(value) == 64 and set(value) <= set("0123456789abcdef")


def _memo(kind: str, text: str, compute, valid):
    """``compute()`` (a JSON value for which ``valid`` holds) for ``text``, from the memo when
    an intact, valid entry exists (a damaged one is rebuilt, :mod:`cache_files`)."""
    key = hashlib.sha256("\0".join((_MEMO_VERSION, kind, text)).encode()).hexdigest()
    path = MEMO / f"{key[:32]}.json"
    stored = read_checked(path)
    if stored is not None:
        try:
            value = json.loads(stored)
        except ValueError:
            value = None
        if valid(value):
            return value
        warn_damaged(path, f" (not a {kind} entry)")
    value = compute()
    write_checked(path, json.dumps(value))
    return value


def module_file(name: str, root: Path) -> Path | None:
    """Source file of module ``name`` under ``root`` (a package's ``__init__.py``), or None."""
    base = root.joinpath(*name.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


@lru_cache(maxsize=None)
def _module(name: str, root: Path) -> tuple[str, frozenset[str], str] | None:
    """Module ``name`` under ``root`` as this process first reads it: its text, the names its
    imports may load and its behaviour digest, or None when it has no source there.  Read once
    per process, for every script's closure: a ``snakemake`` command evaluates its rules
    against one state of the tree (as :func:`code_fingerprint` is memoised)."""
    path = module_file(name, root)
    if path is None:
        return None
    text = path.read_text(encoding="utf-8")
    return text, imported_names(text, name, path.name == "__init__.py"), behaviour_digest(text)


def _absolute(node: ast.ImportFrom, importer: str | None, is_package: bool) -> str:
    """Absolute module name of a ``from ... import`` statement (relative ones resolved)."""
    if not node.level:
        return node.module or ""
    if importer is None:
        raise ImportError("relative import outside a package")
    parts = importer.split(".")
    anchor = parts if is_package else parts[:-1]
    anchor = anchor[:len(anchor) - (node.level - 1)]
    return ".".join(anchor + ([node.module] if node.module else []))


@lru_cache(maxsize=None)
def imported_names(source: str, importer: str | None = None,
                   is_package: bool = False) -> frozenset[str]:
    """Every name an import statement of ``source`` may load as a module (not those under
    ``if TYPE_CHECKING:``, which only name types for annotations).

    ``from a.b import c`` yields ``a.b`` and ``a.b.c`` (``c`` may be a submodule); names that are
    not modules are dropped by the caller when no source file exists for them.  Memoised on the
    source text, in the process and on disk.
    """
    return frozenset(_memo(f"imports {importer} {is_package}", source,
                           lambda: sorted(_imported_names(source, importer, is_package)),
                           _names))


def _type_checking(node: ast.AST) -> bool:
    """An ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``) block: never run."""
    return isinstance(node, ast.If) and (
        (isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING")
        or (isinstance(node.test, ast.Attribute) and node.test.attr == "TYPE_CHECKING"))


def _run_nodes(tree: ast.AST):
    """Every node of ``tree`` but those only a type checker reads (an ``if TYPE_CHECKING:``
    block's body; its ``else`` runs)."""
    pending = [tree]
    while pending:
        node = pending.pop()
        yield node
        pending += node.orelse if _type_checking(node) else ast.iter_child_nodes(node)


def _imported_names(source: str, importer: str | None, is_package: bool) -> set[str]:
    names = set()
    for node in _run_nodes(ast.parse(source)):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = _absolute(node, importer, is_package)
            names.add(base)
            names |= {f"{base}.{alias.name}" for alias in node.names}
    return frozenset(names)


def _with_parents(name: str) -> list[str]:
    parts = name.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts) + 1)]


def import_closure(*entries: str | Path, root: str | Path = SOURCES) -> tuple[str, ...]:
    """Sorted names of the ``rotorvib`` modules that ``entries`` (script paths or module names)
    import, directly or through each other, including enclosing packages."""
    root = Path(root)
    pending, seen = [], set()
    for entry in entries:
        if str(entry).endswith(".py"):
            pending += imported_names(Path(entry).read_text(encoding="utf-8"))
        else:
            pending.append(str(entry))
    while pending:
        for name in _with_parents(pending.pop()):
            if name in seen or name.split(".")[0] != PACKAGE:
                continue
            if (module := _module(name, root)) is None:
                continue
            seen.add(name)
            pending += module[1]
    return tuple(sorted(seen))


def _strip_docstrings(tree: ast.AST) -> ast.AST:
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return tree


def normalised_source(source: str) -> str:
    """The syntax tree of ``source`` without docstrings and positions, as text: equal for two
    sources that differ only in comments, docstrings or layout."""
    return ast.dump(_strip_docstrings(ast.parse(source)), include_attributes=False)


@lru_cache(maxsize=None)
def behaviour_digest(source: str) -> str:
    """SHA-256 of :func:`normalised_source` (memoised on the text, in the process and on disk)."""
    return _memo("behaviour", source,
                 lambda: hashlib.sha256(normalised_source(source).encode()).hexdigest(),
                 _hex_digest)


@lru_cache(maxsize=None)
def code_fingerprint(*entries: str, root: str | Path = SOURCES) -> str:
    """SHA-256 over the names and :func:`behaviour_digest` of every module in
    ``import_closure(*entries)``."""
    digest = hashlib.sha256()
    for name in import_closure(*entries, root=root):
        digest.update(f"{name}\0{_module(name, Path(root))[2]}\0".encode())
    return digest.hexdigest()


def forget_modules() -> None:
    """Read the tree afresh: forget the modules and fingerprints this process has read (as a
    new ``snakemake`` command would), keeping the memo of parsed texts."""
    _module.cache_clear()
    code_fingerprint.cache_clear()
