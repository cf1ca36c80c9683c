"""xarray's probe for pint answered without pint (rotorvib.pipeline.pint_probe), each case in a
fresh interpreter, where xarray's cache of probed modules starts empty. These tests fail loudly
when the pinned xarray changes what the module relies on."""

import subprocess
import sys
import textwrap

#: A dataset made, written and read again, as a job does: every coordinate gets an index.
ROUND_TRIP = """
import numpy as np, xarray as xr
ds = xr.Dataset({"a": ("x", np.arange(3.0), {"units": "m"})}, coords={"x": [0.0, 1.0, 2.0]})
ds.to_netcdf(path)
assert xr.load_dataset(path).identical(ds)
"""


def _run(code: str, tmp_path) -> str:
    program = f"import sys\npath = {str(tmp_path / 'd.nc')!r}\n" + textwrap.dedent(code)
    run = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                         check=False)
    assert run.returncode == 0, run.stderr
    return run.stdout.strip()


def test_xarray_imports_pint_to_read_a_dataset_unless_told(tmp_path):
    """The probe is there to skip: without it, making and reading a dataset imports pint (when
    this fails, xarray no longer probes pint this way, and the module can go)."""
    assert _run(ROUND_TRIP + "print('pint' in sys.modules)", tmp_path) == "True"


def test_skipped_a_dataset_round_trip_imports_no_pint(tmp_path):
    code = ("import xarray\nfrom rotorvib.pipeline import pint_probe\nassert pint_probe.skip()\n"
            + ROUND_TRIP + "print('pint' in sys.modules)")
    assert _run(code, tmp_path) == "False"


def test_the_answer_is_what_xarray_gives_for_an_absent_pint(tmp_path):
    """What :func:`skip` stores equals what xarray builds when pint cannot be imported, and it
    is the answer xarray reads."""
    code = """
    from xarray.namedarray import pycompat
    from rotorvib.pipeline import pint_probe
    assert pint_probe.skip()
    ours = vars(pycompat._cached_duck_array_modules["pint"])
    sys.modules["pint"] = None                          # import pint now raises ImportError
    assert vars(pycompat.DuckArrayModule("pint")) == ours, ours
    assert pycompat.array_type("pint") == ()
    print("ok")
    """
    assert _run(code, tmp_path) == "ok"


def test_with_pint_imported_xarray_keeps_its_quantities(tmp_path):
    """Where pint is loaded already (the job that runs ROSS) nothing changes: xarray still knows
    a quantity and takes its magnitude."""
    code = """
    import numpy as np, pint, xarray
    from xarray.namedarray import pycompat
    from rotorvib.pipeline import pint_probe
    assert not pint_probe.skip()
    q = pint.UnitRegistry().Quantity(np.arange(3.0), "m")
    assert pycompat.array_type("pint") == (pint.Quantity,) and isinstance(q, pint.Quantity)
    assert np.array_equal(pycompat.to_numpy(q), np.arange(3.0))
    print("ok")
    """
    assert _run(code, tmp_path) == "ok"


def test_without_xarray_it_does_nothing(tmp_path):
    code = """
    from rotorvib.pipeline import pint_probe
    print(pint_probe.skip(), "xarray" in sys.modules)
    """
    assert _run(code, tmp_path) == "False False"
