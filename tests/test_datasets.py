import hashlib
import json

import netCDF4
import numpy as np
import pytest
import xarray as xr

from conftest import cf_check
from rotorvib.io.config import config_hash
from rotorvib.io.config import INPUTS_CONFIG_PARAM, job_config
from rotorvib.io.datasets import DatasetError, Provenance, read_dataset, write_dataset


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


def test_the_cf_check_of_many_files_fails_on_one_bad_file(tmp_path):
    """The workflow test checks all datasets in one call: one file breaking CF fails it, named."""
    good = write_dataset(_dataset(), tmp_path / "good.nc", Provenance("r", {}))
    bad = tmp_path / "bad.nc"
    xr.Dataset({"x": ("t", np.arange(3.0), {"units": "furlongs_per_blorp"})}).to_netcdf(bad)
    passed, report = cf_check(good, bad)
    assert not passed and "bad.nc has" in report and "good.nc has" not in report


def test_read_dataset_returns_what_was_written_with_nan_kept(tmp_path):
    ds = _dataset()
    ds["D"][3] = np.nan  # a legitimate NaN (e.g. a censored run) is part of the checksum
    path = write_dataset(ds, tmp_path / "a.nc", Provenance("r", {}))
    np.testing.assert_array_equal(read_dataset(path).D.values, ds.D.values)


def test_a_nan_poisoned_variable_is_named_with_its_rule(tmp_path):
    path = write_dataset(_dataset(), tmp_path / "a.nc", Provenance("b_ga", {}))
    with netCDF4.Dataset(path, "r+") as nc:
        nc["D"][5] = np.nan
    with pytest.raises(DatasetError, match=r"variable 'D' is not what rule 'b_ga' wrote.*"
                                           r"snakemake --forcerun b_ga"):
        read_dataset(path)


def test_a_truncated_dataset_says_how_to_rebuild_it(tmp_path):
    path = write_dataset(_dataset(), tmp_path / "a.nc", Provenance("r", {}))
    path.write_bytes(path.read_bytes()[:200])
    with pytest.raises(DatasetError, match="cannot be read.*rerun snakemake"):
        read_dataset(path)


def test_a_dataset_from_another_configuration_is_refused(tmp_path):
    """The reader passes the hash of the configuration it expects the producer to have used;
    the hash is that of the producer's parameters less the input check (job_config)."""
    made = {"grid": [0.7, 1.3], INPUTS_CONFIG_PARAM: {"x.nc": "ignored"}}
    path = write_dataset(_dataset(), tmp_path / "a.nc", Provenance("c_mass_ratio", job_config(made)))
    same = config_hash({"grid": [0.7, 1.3]})
    assert read_dataset(path, {str(path): same}).D.size == 11
    assert read_dataset(path, {"other.nc": "0" * 64}).D.size == 11    # not an input checked
    with pytest.raises(DatasetError, match=r"made by rule 'c_mass_ratio' under another "
                                           r"configuration.*snakemake --forcerun c_mass_ratio"):
        read_dataset(path, {str(path): config_hash({"grid": [0.7, 1.4]})})
