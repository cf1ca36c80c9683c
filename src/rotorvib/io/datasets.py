"""The one writer of every netCDF dataset of the pipeline.

Each file carries CF-1.11 and ACDD-1.3 global attributes, ``long_name`` and ``units`` on every
variable and coordinate, and its provenance (git commit and dirty flag, hash and canonical text
of the configuration, package versions, rule, seed).  Files are deterministic: the same data and
provenance give byte-identical files (no wall-clock time is written; the date, if any, comes from
``SOURCE_DATE_EPOCH``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

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
