"""The one writer of every netCDF dataset of the pipeline.

Each file carries CF-1.11 and ACDD-1.3 global attributes, ``long_name`` and ``units`` on every
variable and coordinate, and its provenance (git commit and dirty flag, hash and canonical text
of the configuration, package versions, rule, seed).  Files are deterministic: the same data and
provenance give byte-identical files (no wall-clock time is written; the date, if any, comes from
``SOURCE_DATE_EPOCH``).  Every numeric data variable carries the SHA-256 of its values
(``sha256``), and :func:`read_dataset` checks it: a dataset damaged or edited after its rule
wrote it (say, a variable overwritten with NaN) stops the reading job with an error that names
the file, the variable and the rule to rerun.  Given the hash of the configuration the reading job
expects its producer to have used (the workflow passes it as the parameter
:data:`rotorvib.io.config.INPUTS_CONFIG_PARAM`), it also refuses a dataset made under another
configuration (copied in, restored from another run, or marked current with ``--touch``).
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import xarray as xr

from rotorvib.io.config import canonical_json, config_hash
from rotorvib.io.provenance import git_state, package_versions

PROJECT_URL = "https://github.com/rotorvib/rotorvib"
LICENSE = "CC-BY-4.0 (data); MIT (code)"


@dataclass(frozen=True)
class Provenance:
    """What produced a dataset: the rule, the configuration section it used and the seed."""

    rule: str
    config: dict
    seed: int | None = None
    repo: str = "."
    extra: dict = field(default_factory=dict)

    def attrs(self) -> dict:
        commit, dirty = git_state(self.repo)
        attrs = {
            "provenance_rule": self.rule,
            "provenance_git_commit": commit,
            "provenance_git_dirty": int(dirty),
            "provenance_config_sha256": config_hash(self.config),
            "provenance_config": canonical_json(self.config),
            "provenance_packages": canonical_json(package_versions()),
        }
        if self.seed is not None:
            attrs["provenance_seed"] = int(self.seed)
        attrs.update({f"provenance_{k}": v for k, v in self.extra.items()})
        return attrs


def _date_attrs() -> dict:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch is None:
        return {}
    stamp = datetime.fromtimestamp(int(epoch), tz=timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    return {"date_created": stamp}


class DatasetError(ValueError):
    """A dataset cannot be read, or is not what its rule wrote."""


def values_sha256(values) -> str:
    """SHA-256 of an array's values (C order, native dtype)."""
    return hashlib.sha256(np.ascontiguousarray(values).tobytes()).hexdigest()


def read_dataset(path: str | Path, expected_config: dict[str, str] | None = None) -> xr.Dataset:
    """Load a dataset written by :func:`write_dataset` into memory, checking that it opens, that
    every numeric data variable still has the values its rule wrote and, where
    ``expected_config[str(path)]`` is given, that its ``provenance_config_sha256`` is that hash."""
    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError, RuntimeError) as error:
        raise DatasetError(f"{path} cannot be read ({error}); delete it and rerun snakemake to "
                           "rebuild it") from None
    rule = ds.attrs.get("provenance_rule", "?")
    for name, var in ds.data_vars.items():
        expected = var.attrs.get("sha256")
        if expected is not None and values_sha256(var.values) != expected:
            raise DatasetError(f"{path}: variable {name!r} is not what rule {rule!r} wrote (its "
                               f"values changed since); rerun it: snakemake --forcerun {rule}")
    want = (expected_config or {}).get(str(path))
    got = ds.attrs.get("provenance_config_sha256")
    if want is not None and got != want:
        raise DatasetError(f"{path} was made by rule {rule!r} under another configuration "
                           f"(config sha256 {str(got)[:12]}…, this run expects {want[:12]}…); "
                           f"rerun it: snakemake --forcerun {rule}")
    return ds


def check_metadata(ds: xr.Dataset) -> None:
    """Raise ``ValueError`` if a variable lacks ``long_name``, or a numeric one ``units``."""
    missing = [f"{name}.{attr}" for name, var in ds.variables.items()
               for attr in ("long_name", "units") if attr not in var.attrs
               and (attr == "long_name" or var.dtype.kind in "fiuc")]
    if missing:
        raise ValueError("dataset variables lack CF metadata: " + ", ".join(missing))


def write_dataset(ds: xr.Dataset, path: str | Path, provenance: Provenance) -> Path:
    """Write ``ds`` to ``path`` as compressed netCDF-4 with full metadata (see module docstring).

    ``ds.attrs`` must hold ``title``, ``summary`` and ``references`` (the paper and the
    figure/table/equation the data reproduce); other attributes are kept.
    """
    check_metadata(ds)
    missing = [k for k in ("title", "summary", "references") if not ds.attrs.get(k)]
    if missing:
        raise ValueError(f"dataset lacks global attribute(s) {missing}")
    out = ds.copy()
    out.attrs = {
        "Conventions": "CF-1.11, ACDD-1.3",
        "institution": "rotorvib reproduction project",
        "source": "rotorvib numerical reproduction (see provenance_* attributes)",
        "history": f"created by rule '{provenance.rule}' of the rotorvib Snakemake workflow",
        "license": LICENSE,
        "project": PROJECT_URL,
        **_date_attrs(),
        **ds.attrs,
        **provenance.attrs(),
    }
    for var in out.data_vars.values():
        if var.dtype.kind in "fiuc":
            var.attrs["sha256"] = values_sha256(var.values)
    encoding = {}
    for name, var in out.variables.items():
        if name in out.coords or var.dtype.kind not in "fiuc":
            encoding[name] = {"_FillValue": None}
        else:
            encoding[name] = {"zlib": True, "complevel": 4, "shuffle": True, "_FillValue": None}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    out.to_netcdf(path, engine="netcdf4", format="NETCDF4", encoding=encoding)
    return path
