"""The library's linear-algebra tests under a second OpenBLAS kernel: a result that moves with
the kernel beyond a test's tolerance fails here, whatever kernel this machine picks.

OpenBLAS (bundled with numpy and scipy) chooses its kernels by the processor (``SkylakeX`` on an
AVX-512 one, ``Haswell`` or ``Zen`` on others) unless ``OPENBLAS_CORETYPE`` names one; their
sums are ordered differently, so an ill-conditioned solve or eigenproblem answers differently
on each.  The second kernel is ``Prescott``, the generic SSE3 one that no modern processor
picks by itself (``Haswell`` where this run already uses ``Prescott``).  The files run again are
the tests of the modules that call LAPACK or BLAS (:data:`LINEAR_ALGEBRA`): those that import
one of them themselves (a file that reaches one only through another module tests that
module's own work).
"""

import os
import re
import subprocess
import sys

from conftest import ROOT
from rotorvib.pipeline.fingerprint import imported_names

#: The library's modules that call BLAS or LAPACK (``numpy.linalg``, ``scipy.linalg``, matrix
#: products), each for what it solves.
LINEAR_ALGEBRA = {
    "rotorvib.models.balancer.stability": "the balanced state's Jacobian",
    "rotorvib.papers.b.stability_maps": "eigenvalues and modes of the balanced state",
    "rotorvib.papers.a.studies": "paper A's Lyapunov eigenvalues",
    "rotorvib.papers.a.responses": "paper A's slow-flow directions",
    "rotorvib.models.balancer.certificates": "Lyapunov certificates",
    "rotorvib.models.balancer.expansion": "the Taylor expansion's solves",
    "rotorvib.methods.continuation": "pseudo-arclength continuation",
    "rotorvib.methods.multiple_scales": "paper A's multiple-scales eigenproblem",
    "rotorvib.models.absorber.frequency_response": "paper C's frequency response",
    "rotorvib.models.absorber.time_response": "paper C's modal time response",
    "rotorvib.papers.b.ross_model": "ROSS's solve",
    "rotorvib.papers.b.boundary_limits": "the boundary's least-squares fit",
}
KERNELS = ("Prescott", "Haswell")


def second_kernel(environ=os.environ) -> str:
    """``Prescott``, or ``Haswell`` where this run already uses ``Prescott``."""
    return next(k for k in KERNELS if environ.get("OPENBLAS_CORETYPE", "").lower() != k.lower())


def linear_algebra_tests() -> list[str]:
    """The test files (but this one) that import a module of :data:`LINEAR_ALGEBRA`, or a
    function or class of one, themselves (a constant, in capitals, runs none of its code)."""
    def tests_one(path):
        names = imported_names(path.read_text(encoding="utf-8"))   # "m" and "m.name" for each
        for m in LINEAR_ALGEBRA:                                    # name imported from m
            taken = [n.rsplit(".", 1)[1] for n in names if n.startswith(m + ".")]
            if m in names and (not taken or not all(name.isupper() for name in taken)):
                return True
        return False
    return sorted(str(path.relative_to(ROOT)) for path in (ROOT / "tests").glob("test_*.py")
                  if path.name != "test_blas_kernels.py" and tests_one(path))


def test_every_module_named_calls_linear_algebra():
    """The table is the code's: each module named calls BLAS or LAPACK (a ``linalg`` function,
    ``scipy.linalg``, a matrix product ``@``), and no other module of the library does (a new
    one must be named, with what it solves)."""
    calls = re.compile(r"\blinalg\.(?!LinAlgError)\w+\(|from scipy\.linalg import|\w @ \w")
    found = {".".join(path.relative_to(ROOT / "src").with_suffix("").parts)
             for path in (ROOT / "src/rotorvib").rglob("*.py")
             if calls.search(path.read_text(encoding="utf-8"))}
    assert found == set(LINEAR_ALGEBRA)


def test_the_linear_algebra_tests_pass_under_a_second_kernel():
    files = linear_algebra_tests()
    assert "tests/test_ross_jeffcott.py" in files and "tests/test_paper_b_boundaries.py" in files
    kernel = second_kernel()
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--numprocesses=0",
         "-m", "not workflow", *files],
        cwd=ROOT, capture_output=True, text=True,
        env={**os.environ, "OPENBLAS_CORETYPE": kernel})
    assert run.returncode == 0, f"under OPENBLAS_CORETYPE={kernel}:\n{run.stdout[-6000:]}"
