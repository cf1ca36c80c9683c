"""Code fingerprints derived from imports (rotorvib.pipeline.fingerprint) on a small package tree."""

import textwrap

import pytest

from rotorvib.pipeline import fingerprint as fingerprints
from rotorvib.pipeline.fingerprint import (
    behaviour_digest,
    code_fingerprint,
    forget_modules,
    import_closure,
    imported_names,
    normalised_source,
)


def write(root, name, text):
    path = root.joinpath(*name.split("/"))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture
def tree(tmp_path):
    src = tmp_path / "src"
    write(src, "rotorvib/__init__.py", '"""Package."""\n')
    write(src, "rotorvib/models/__init__.py", "")
    write(src, "rotorvib/models/engine.py", "import numpy as np\n\nSTEP = 1\n")
    write(src, "rotorvib/models/run.py", "from . import engine\n\n\ndef run():\n    return engine.STEP\n")
    write(src, "rotorvib/papers/__init__.py", "")
    write(src, "rotorvib/papers/b.py", "from ..models.run import run\n")
    write(src, "rotorvib/papers/c.py", "X = 2\n")
    script = write(tmp_path, "script.py", "import sys\nfrom rotorvib.papers.b import run\n")
    return src, script


def fingerprint(tree, *extra):
    forget_modules()
    src, script = tree
    return code_fingerprint(str(script), *extra, root=str(src))


def test_relative_imports_resolve_to_absolute_names():
    assert imported_names("from . import engine", "rotorvib.models.run") == {
        "rotorvib.models", "rotorvib.models.engine"}
    assert imported_names("from ..models.run import run", "rotorvib.papers.b") == {
        "rotorvib.models.run", "rotorvib.models.run.run"}
    assert imported_names("from .x import y", "rotorvib.pkg", is_package=True) == {
        "rotorvib.pkg.x", "rotorvib.pkg.x.y"}


def test_closure_follows_imports_transitively_with_enclosing_packages(tree):
    src, script = tree
    assert import_closure(script, root=src) == (
        "rotorvib", "rotorvib.models", "rotorvib.models.engine", "rotorvib.models.run",
        "rotorvib.papers", "rotorvib.papers.b")
    assert "rotorvib.papers.c" in import_closure(script, "rotorvib.papers.c", root=src)


def test_imports_inside_functions_count(tree):
    src, _ = tree
    write(src, "rotorvib/papers/c.py", "def f():\n    from rotorvib.models import engine\n")
    assert "rotorvib.models.engine" in import_closure("rotorvib.papers.c", root=src)


def test_imports_a_type_checker_alone_reads_are_not_dependencies(tree):
    """An ``if TYPE_CHECKING:`` block never runs (its ``else`` does): an annotation's type is no
    code of the job's."""
    src, _ = tree
    write(src, "rotorvib/papers/c.py", """\
        import typing
        from typing import TYPE_CHECKING
        if TYPE_CHECKING:
            from rotorvib.models import engine
        else:
            import rotorvib.models
        if typing.TYPE_CHECKING:
            import rotorvib.papers.b
        """)
    closure = import_closure("rotorvib.papers.c", root=src)
    assert "rotorvib.models" in closure
    assert not {"rotorvib.models.engine", "rotorvib.models.run", "rotorvib.papers.b"} & set(closure)


def test_comments_docstrings_and_layout_do_not_change_the_fingerprint(tree):
    src, _ = tree
    before = fingerprint(tree)
    write(src, "rotorvib/models/engine.py",
          '"""The engine."""\nimport numpy as np  # arrays\n\n\n# the step\nSTEP = (\n    1\n)\n')
    assert fingerprint(tree) == before


def test_a_code_edit_anywhere_in_the_closure_changes_the_fingerprint(tree):
    src, _ = tree
    before = fingerprint(tree)
    write(src, "rotorvib/models/engine.py", "import numpy as np\n\nSTEP = 2\n")
    assert fingerprint(tree) != before


def test_an_edit_outside_the_closure_does_not(tree):
    src, _ = tree
    before = fingerprint(tree)
    write(src, "rotorvib/papers/c.py", "X = 3\n")
    assert fingerprint(tree) == before
    assert fingerprint(tree, "rotorvib.papers.c") != before


def test_normalised_source_keeps_string_constants_that_are_not_docstrings():
    assert normalised_source('x = "a"\n') != normalised_source('x = "b"\n')
    assert normalised_source('def f():\n    """doc"""\n    return 1\n') == \
        normalised_source("def f():\n    return 1\n")


def test_the_memo_serves_later_processes_and_a_damaged_entry_is_recomputed(tree, tmp_path,
                                                                           monkeypatch):
    """A process with an empty in-process cache takes every module's imports and digest from the
    memo on disk (parsing nothing) and gets the same fingerprint; damaged entries are computed
    again."""
    monkeypatch.setattr(fingerprints, "MEMO", tmp_path / "memo")

    def in_a_new_process():
        imported_names.cache_clear()
        behaviour_digest.cache_clear()
        return fingerprint(tree)

    first = in_a_new_process()
    entries = sorted((tmp_path / "memo").glob("*.json"))
    assert entries

    def parse(*_):
        raise AssertionError("parsed although the memo holds the answer")

    with monkeypatch.context() as patched:
        patched.setattr(fingerprints.ast, "parse", parse)
        assert in_a_new_process() == first
    for entry in entries:
        entry.write_text("{damaged")
    assert in_a_new_process() == first
