"""The disk cache of sympy-generated functions: same numbers as sympy, derived once, re-derived
when the defining module changes, and harmless when damaged or unwritable."""

import importlib.util

import numpy as np
import pytest
import sympy as sp

from rotorvib.methods.codegen import cached_lambdify

X, Y = sp.symbols("x y")


def _module(folder, text="EXPR = 'x**2 + sin(y)'\n"):
    path = folder / "defining.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location("defining", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _counted(calls):
    def build():
        calls.append(1)
        return [sp.diff(X**2 * sp.sin(Y), X), sp.sqrt(X) * sp.cos(Y)]
    return build


def test_the_cache_gives_sympys_numbers_and_derives_once(tmp_path):
    module, calls = _module(tmp_path), []
    first = cached_lambdify("f", (X, Y), _counted(calls), modules=(module,))
    second = cached_lambdify("f", (X, Y), _counted(calls), modules=(module,))
    assert len(calls) == 1 and len(list((tmp_path / "__pycache__").glob("f.*.lambdify"))) == 1
    x, y = np.random.default_rng(0).uniform(0.1, 2.0, (2, 50))
    reference = sp.lambdify((X, Y), _counted([])(), "numpy")(x, y)
    np.testing.assert_array_equal(second(x, y), reference)
    np.testing.assert_array_equal(first(x, y), reference)


def test_an_edit_of_the_defining_module_derives_again(tmp_path):
    calls = []
    cached_lambdify("f", (X, Y), _counted(calls), modules=(_module(tmp_path),))
    edited = _module(tmp_path, "EXPR = 'x**3'\n")
    cached_lambdify("f", (X, Y), _counted(calls), modules=(edited,))
    assert len(calls) == 2 and len(list((tmp_path / "__pycache__").glob("f.*"))) == 2


def test_a_damaged_or_unwritable_cache_is_derived_around(tmp_path):
    module, calls = _module(tmp_path), []
    cached_lambdify("f", (X, Y), _counted(calls), modules=(module,))
    (cached,) = (tmp_path / "__pycache__").glob("f.*.lambdify")
    cached.write_text("def _lambdifygenerated(x, y):\n    return [x +\n")     # truncated
    f = cached_lambdify("f", (X, Y), _counted(calls), modules=(module,))
    assert len(calls) == 2 and f(1.0, 0.0) == pytest.approx([0.0, 1.0])
    assert "sqrt(x)*cos(y)]" in cached.read_text()                           # rewritten
    cached.unlink()
    (tmp_path / "__pycache__").rmdir()
    (tmp_path / "__pycache__").write_text("")       # not a folder: nothing can be stored
    f = cached_lambdify("f", (X, Y), _counted(calls), modules=(module,))
    assert len(calls) == 3 and f(1.0, 0.0) == pytest.approx([0.0, 1.0])
