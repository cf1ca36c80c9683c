"""The disk cache of sympy-generated functions: same numbers as sympy, derived once, re-derived
when the defining module changes, and harmless when damaged or unwritable."""

import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

from conftest import ROOT
from rotorvib.methods import codegen
from rotorvib.methods.codegen import cached_lambdify, numpy_namespace

X, Y = sp.symbols("x y")


def _module(folder, text="EXPR = 'x**2 + sin(y)'\n"):
    """A file that stands for the module defining the expressions."""
    path = folder / "defining.py"
    path.write_text(text)
    return path


def _counted(calls):
    def build():
        calls.append(1)
        return (X, Y), [sp.diff(X**2 * sp.sin(Y), X), sp.sqrt(X) * sp.cos(Y)]
    return build


def test_the_cache_gives_sympys_numbers_and_derives_once(tmp_path):
    module, calls = _module(tmp_path), []
    first = cached_lambdify("f", _counted(calls), sources=(module,))
    second = cached_lambdify("f", _counted(calls), sources=(module,))
    assert len(calls) == 1 and len(list((tmp_path / "__pycache__").glob("f.*.lambdify"))) == 1
    assert module in codegen.KEYED          # what the process's results rest on, recorded
    x, y = np.random.default_rng(0).uniform(0.1, 2.0, (2, 50))
    reference = sp.lambdify(*_counted([])(), "numpy")(x, y)
    np.testing.assert_array_equal(second(x, y), reference)
    np.testing.assert_array_equal(first(x, y), reference)


def test_an_edit_of_the_defining_module_derives_again(tmp_path):
    calls = []
    cached_lambdify("f", _counted(calls), sources=(_module(tmp_path),))
    edited = _module(tmp_path, "EXPR = 'x**3'\n")
    cached_lambdify("f", _counted(calls), sources=(edited,))
    assert len(calls) == 2 and len(list((tmp_path / "__pycache__").glob("f.*"))) == 2


def test_a_damaged_or_unwritable_cache_is_derived_around(tmp_path):
    module, calls = _module(tmp_path), []
    cached_lambdify("f", _counted(calls), sources=(module,))
    (cached,) = (tmp_path / "__pycache__").glob("f.*.lambdify")
    cached.write_text("def _lambdifygenerated(x, y):\n    return [x +\n")     # truncated
    f = cached_lambdify("f", _counted(calls), sources=(module,))
    assert len(calls) == 2 and f(1.0, 0.0) == pytest.approx([0.0, 1.0])
    assert "sqrt(x)*cos(y)]" in cached.read_text()                           # rewritten
    cached.unlink()
    (tmp_path / "__pycache__").rmdir()
    (tmp_path / "__pycache__").write_text("")       # not a folder: nothing can be stored
    f = cached_lambdify("f", _counted(calls), sources=(module,))
    assert len(calls) == 3 and f(1.0, 0.0) == pytest.approx([0.0, 1.0])


def test_the_namespace_of_cached_code_is_sympys_own():
    """A cached function runs in the globals ``lambdify(..., "numpy")`` would give it, built
    without sympy (fails when the pinned sympy builds them otherwise)."""
    ours = numpy_namespace()
    theirs = dict(sp.lambdify((), 0, "numpy").__globals__)
    names = set(theirs) - {"__builtins__"}
    assert set(ours) - {"__builtins__"} == names
    assert all(ours[n] is theirs[n] or ours[n] == theirs[n] for n in names)


def test_the_balancers_generated_functions_run_without_sympy_once_cached():
    """The stability and multiple-scales code a job runs, generated once (here), then in a fresh
    process from the cache: the same numbers, and sympy never imported."""
    from rotorvib.models.balancer import expansion, stability

    program = """
import sys
import numpy as np
from rotorvib.models.balancer import expansion, stability
values = (stability.max_real_part(0.01, 0.75, 0.01, 0.5, np.array([0.5, 2.0])),
          stability.polynomial_roots(0.01, 0.75, 0.01, 0.5, 2.0),
          expansion.taylor_at(0.01, 0.75, 0.01, 0.5, 2.0, expansion.balanced_state(0.75))[1])
print(repr([np.asarray(v).tolist() for v in values]), "sympy" in sys.modules)
"""
    here = (stability.max_real_part(0.01, 0.75, 0.01, 0.5, np.array([0.5, 2.0])),
            stability.polynomial_roots(0.01, 0.75, 0.01, 0.5, 2.0),
            expansion.taylor_at(0.01, 0.75, 0.01, 0.5, 2.0, expansion.balanced_state(0.75))[1])
    run = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                         check=False, env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert run.returncode == 0, run.stderr
    text, loaded = run.stdout.rsplit(" ", 1)
    assert loaded.strip() == "False"
    assert text == repr([np.asarray(v).tolist() for v in here])
