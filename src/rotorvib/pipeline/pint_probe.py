"""xarray's probe for pint quantities, answered without importing pint in a job process.

Whenever xarray turns a variable into numpy (an index is built for every coordinate of a dataset
that is made or read) it asks whether the data is a pint quantity, and to know pint's type it
imports pint once per process (``xarray.namedarray.pycompat.to_numpy``).  pint is installed
here only because ROSS needs it; no dataset of the workflow holds a quantity, and importing
pint with what it imports (flexparser, flexcache, babel, platformdirs) is most of the start-up
a job spends beyond its own imports on reading a dataset.  :func:`skip` records pint in
xarray's cache of such modules as absent, unless the process has imported pint already (the
job that runs ROSS), where the probe costs nothing.

The cache is private to xarray: this module is the only place that touches it, and
``tests/test_pint_probe.py`` fails loudly when the pinned xarray stops probing pint this way,
or probes it elsewhere, or when this module's answer is no longer read.
"""

from __future__ import annotations

import sys


def skip() -> bool:
    """Make xarray's pint probe answer "absent" without importing pint, if xarray is loaded
    and pint is not; return whether it was done."""
    if "pint" in sys.modules or "xarray" not in sys.modules:
        return False
    from xarray.namedarray import pycompat

    absent = object.__new__(pycompat.DuckArrayModule)      # what __init__ sets without pint
    absent.module, absent.type, absent.available = None, (), False
    absent.version = pycompat.Version("0.0.0")
    pycompat._cached_duck_array_modules.setdefault("pint", absent)
    return True
