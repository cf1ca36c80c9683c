import errno
import hashlib
import json
import os
import re

import netCDF4
import numpy as np
import pytest
import xarray as xr

from conftest import cf_check
from rotorvib.io import datasets
from rotorvib.io.datasets import DatasetError, Provenance, read_dataset, write_dataset
from rotorvib.io.provenance import config_hash
from rotorvib.pipeline.job import INPUT_PRODUCERS_PARAM, job_config


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


def test_a_dataset_of_no_runs_reads_back_with_its_text_as_text(tmp_path):
    """A study with no run to record (found by the fuzzer: a balance-time law over no balanced
    run) has empty text coordinates and variables: they are written as text, not as the floats
    xarray would infer, so the file passes its own checksums; with one run, the same."""
    for labels in ([], ["beta study"]):
        ds = xr.Dataset(
            {"t": ("run", np.ones(len(labels)), {"long_name": "time", "units": "s"}),
             "kind": ("run", np.array(labels, dtype=object), {"long_name": "kind"})},
            coords={"source": ("run", np.array(labels, dtype=object), {"long_name": "study"})},
            attrs={"title": "test", "summary": "no runs", "references": "none"})
        back = read_dataset(write_dataset(ds, tmp_path / f"runs{len(labels)}.nc",
                                          Provenance("r", {})))
        assert "source" in back.coords and back.sizes["run"] == len(labels)
        assert list(back.source.values) == labels == list(back.kind.values)


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
    """The reader passes the rule it expects to have made the file and the hash of that rule's
    configuration; the hash is that of the producer's parameters less the input check
    (job_config)."""
    made = {"grid": [0.7, 1.3], INPUT_PRODUCERS_PARAM: {"x.nc": "ignored"}}
    path = write_dataset(_dataset(), tmp_path / "a.nc", Provenance("c_mass_ratio", job_config(made)))
    same = {"rule": "c_mass_ratio", "config_sha256": config_hash({"grid": [0.7, 1.3]})}
    assert read_dataset(path, {str(path): same}).D.size == 11
    assert read_dataset(path, {"other.nc": {"rule": "x"}}).D.size == 11   # not an input checked
    with pytest.raises(DatasetError, match=r"made by rule 'c_mass_ratio' under another "
                                           r"configuration.*snakemake --forcerun c_mass_ratio"):
        read_dataset(path, {str(path): {**same, "config_sha256": config_hash({"grid": [0.7]})}})


def test_a_copied_in_dataset_names_the_rule_that_makes_its_path(tmp_path):
    path = write_dataset(_dataset(), tmp_path / "a.nc", Provenance("c_mass_ratio", {}))
    with pytest.raises(DatasetError, match=r"made by rule 'c_mass_ratio', but rule 'c_ga' makes "
                                           r"this file \(copied in\?\); rebuild it: "
                                           r"snakemake --forcerun c_ga"):
        read_dataset(path, {str(path): {"rule": "c_ga", "config_sha256": config_hash({})}})


def _two_variables():
    ds = _dataset()
    ds["E"] = ("w", np.linspace(5.0, 9.0, 11), {"long_name": "other", "units": "1"})
    return ds


def _swap(nc):
    d, e = nc["D"][:], nc["E"][:]
    nc["D"][:], nc["E"][:] = e, d


def _rename_swap(nc):
    nc.renameVariable("D", "tmp")
    nc.renameVariable("E", "D")
    nc.renameVariable("tmp", "E")


def _nan_without_checksum(nc):
    nc["D"].delncattr("sha256")
    nc["D"][3] = np.nan


#: Every kind of damage the reader catches: (edit of the open file, what the message says)
DAMAGE = [
    (lambda nc: nc["D"].__setitem__(5, np.nan), "variable 'D' is not what rule 'b_ga' wrote"),
    (_swap, "variable 'D' is not what rule 'b_ga' wrote"),
    (_rename_swap, "variable '[DE]' is not what rule 'b_ga' wrote"),
    (lambda nc: nc["w"].__setitem__(3, 0.9899), "variable 'w' is not what"),
    (lambda nc: nc["D"].setncattr("units", "m"), "variable 'D' is not what"),
    (lambda nc: nc["w"].setncattr("long_name", "edited"), "variable 'w' is not what"),
    (lambda nc: nc.setncattr("provenance_config", '{"x": 2}'),
     r"a.nc is not what rule 'b_ga' wrote \(its variables or global attributes changed"),
    (lambda nc: nc.setncattr("title", "edited"), "its variables or global attributes changed"),
    (_nan_without_checksum, "variable 'D' has no checksum"),
    (lambda nc: nc.delncattr("content_sha256"), r"a.nc has no checksum \(content_sha256\)"),
    (lambda nc: nc.createVariable("extra", "f8", ("w",)).setncattr("sha256", "0" * 64),
     "variable 'extra' is not what"),
]


@pytest.mark.parametrize("damage, said", DAMAGE)
def test_every_kind_of_damage_is_named_with_the_rule_to_rerun(tmp_path, damage, said):
    path = write_dataset(_two_variables(), tmp_path / "a.nc", Provenance("b_ga", {}))
    read_dataset(path)
    with netCDF4.Dataset(path, "r+") as nc:
        damage(nc)
    with pytest.raises(DatasetError, match=said + ".*snakemake --forcerun b_ga"):
        read_dataset(path)


def test_a_file_not_written_by_the_pipeline_is_refused(tmp_path):
    path = tmp_path / "plain.nc"
    _dataset().to_netcdf(path)
    with pytest.raises(DatasetError, match="has no checksum"):
        read_dataset(path)


def test_variables_take_their_long_name_and_units_from_one_table():
    """rotorvib.io.variables.described: each variable its table's long name and units (a label
    none), and a variable without a description or a description of no variable refused."""
    from rotorvib.io.variables import described

    table = {"t": ("time", "s"), "name": ("what it is", None)}
    out = described({"t": ("run", [1.0]), "name": ("run", ["a"])}, table)
    assert out == {"t": ("run", [1.0], {"long_name": "time", "units": "s"}),
                   "name": ("run", ["a"], {"long_name": "what it is"})}
    with pytest.raises(KeyError, match=r"without a description: \['x'\]"):
        described({"t": ("run", [1.0]), "name": ("run", ["a"]), "x": ((), 0.0)}, table)
    with pytest.raises(KeyError, match=r"descriptions of no variable: \['name'\]"):
        described({"t": ("run", [1.0])}, table)


def _failing_write(error, partial=b""):
    """``to_netcdf`` as the netCDF library fails: ``partial`` bytes written, then ``error``."""
    def write(self, path, **kwargs):
        with open(path, "wb") as fh:
            fh.write(partial)
        raise error
    return write


def _free(n):
    return lambda folder: os.statvfs_result((4096, 1, 0, 0, n, 0, 0, 0, 0, 255))


@pytest.mark.parametrize("error, free", [
    (OSError(errno.ENOSPC, "No space left on device"), 10 << 30),    # said plainly
    (PermissionError(errno.EACCES, "Permission denied"), 0),           # a full disk, netCDF's
    (RuntimeError("NetCDF: HDF error"), 100),                          # words for it
], ids=["ENOSPC", "permission denied", "HDF error"])
def test_a_full_disk_is_said_naming_the_file(tmp_path, monkeypatch, error, free):
    """Before, a dataset written on a full disk failed with "Permission denied" (or "NetCDF:
    HDF error" when it ran out midway, leaving the partial file); now the error says that no
    space is left, names the file and removes the partial one."""
    monkeypatch.setattr(xr.Dataset, "to_netcdf", _failing_write(error, b"\x89HDF" * 100))
    monkeypatch.setattr(datasets.os, "statvfs", _free(free))
    path = tmp_path / "a.nc"
    with pytest.raises(OSError, match=r"^\[Errno 28\] no space left on device to write the "
                                      r"dataset .*: '" + re.escape(str(path)) + "'$") as raised:
        write_dataset(_dataset(), path, Provenance(rule="r", config={}))
    assert raised.value.errno == errno.ENOSPC and str(error) in str(raised.value)
    assert not path.exists()


def test_another_write_error_is_left_as_it_is(tmp_path, monkeypatch):
    """Where space is left, a refused write is what the library said (a read-only folder)."""
    monkeypatch.setattr(xr.Dataset, "to_netcdf",
                        _failing_write(PermissionError(errno.EACCES, "Permission denied")))
    monkeypatch.setattr(datasets.os, "statvfs", _free(10 << 30))
    with pytest.raises(PermissionError, match="Permission denied"):
        write_dataset(_dataset(), tmp_path / "a.nc", Provenance(rule="r", config={}))
