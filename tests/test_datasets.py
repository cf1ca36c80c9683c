import hashlib
import json
import numpy as np
import pytest
import xarray as xr

from conftest import cf_check
from rotorvib.io.datasets import Provenance, write_dataset


def _dataset():
    return xr.Dataset(
        {"D": ("w", np.linspace(1.0, 2.0, 11), {"long_name": "amplitude", "units": "1"})},
        coords={"w": ("w", np.linspace(0.5, 1.5, 11), {"long_name": "ratio", "units": "1"})},
        attrs={"title": "test", "summary": "test data", "references": "none"},
    )


def _sha(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_files_are_byte_identical_and_carry_provenance(tmp_path):
    prov = Provenance(rule="r", config={"x": 1, "y": [2, 3]}, seed=7)
    a = write_dataset(_dataset(), tmp_path / "a.nc", prov)
    b = write_dataset(_dataset(), tmp_path / "b.nc", prov)
    assert _sha(a) == _sha(b)
    ds = xr.load_dataset(a)
    assert ds.attrs["Conventions"] == "CF-1.11, ACDD-1.3"
    assert json.loads(ds.attrs["provenance_config"]) == {"x": 1, "y": [2, 3]}
    assert ds.attrs["provenance_seed"] == 7
    assert "numpy" in json.loads(ds.attrs["provenance_packages"])
    assert len(ds.attrs["provenance_config_sha256"]) == 64
    np.testing.assert_array_equal(ds.D.values, _dataset().D.values)


def test_missing_units_or_title_are_refused(tmp_path):
    ds = _dataset()
    del ds.D.attrs["units"]
    with pytest.raises(ValueError, match="D.units"):
        write_dataset(ds, tmp_path / "x.nc", Provenance("r", {}))
    ds = _dataset()
    del ds.attrs["title"]
    with pytest.raises(ValueError, match="title"):
        write_dataset(ds, tmp_path / "x.nc", Provenance("r", {}))


def test_written_file_passes_cf_1_11(tmp_path):
    passed, report = cf_check(write_dataset(_dataset(), tmp_path / "a.nc", Provenance("r", {})))
    assert passed, report
