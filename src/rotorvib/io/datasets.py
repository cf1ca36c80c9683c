"""The one writer of every netCDF dataset of the pipeline.

Each file carries CF-1.11 and ACDD-1.3 global attributes, ``long_name`` and ``units`` on every
variable and coordinate, and its provenance (git commit and dirty flag, hash and canonical text
of the configuration, package versions, rule, seed).  Files are deterministic: the same data and
provenance give byte-identical files (no wall-clock time is written; the date, if any, comes from
``SOURCE_DATE_EPOCH``).  Every variable and coordinate carries the SHA-256 of its name,
dimensions, type, values and attributes (``sha256``) and the file the SHA-256 of all of them and
of its global attributes (``content_sha256``); :func:`read_dataset` checks both, and a missing
checksum is itself an error: a dataset damaged or edited after its rule wrote it (a variable
overwritten with NaN, two variables swapped, a coordinate, a unit or the provenance edited)
stops the reading job with an error that names the file, what changed and the rule to rerun.
Given the rule that makes the file in this run and the hash of the configuration it uses (the
workflow passes both as the parameter :data:`rotorvib.pipeline.job.INPUT_PRODUCERS_PARAM`), it also
refuses a dataset made by another rule or under another configuration (copied in, restored from
another run, or marked current with ``--touch``).

A full disk is said as such, naming the file: the netCDF library reports it as something else
(``Permission denied`` where the file could not even be created, ``NetCDF: HDF error`` where
it ran out midway), so a failed write on a file system left with less than :data:`FULL` free is
reported as no space left, and the partial file, which only holds the space, removed.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import xarray as xr

from rotorvib.io.provenance import canonical_json, code_state, config_hash, package_versions

PROJECT_URL = "https://github.com/rotorvib/rotorvib"
LICENSE = "CC-BY-4.0 (data); MIT (code)"


@dataclass(frozen=True)
class Provenance:
    """What produced a dataset: the rule, the configuration section it used and the seed."""

    rule: str
    config: dict
    seed: int | None = None
    extra: dict = field(default_factory=dict)

    def attrs(self) -> dict:
        commit, dirty, origin = code_state()
        attrs = {
            "provenance_rule": self.rule,
            "provenance_git_commit": commit,
            "provenance_git_dirty": int(dirty),
            "provenance_code_origin": origin,
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


#: Free bytes below which a failed write is put down to a full file system (HDF5 writes its
#: data and metadata in pieces of kilobytes to a megabyte).
FULL = 1 << 20

#: The global attribute holding the checksum of a whole dataset (:func:`content_sha256`).
CHECKSUM = "content_sha256"


def _plain(value):
    """An attribute value as JSON can hold it, the same before writing and after reading
    (netCDF turns tuples and scalars into arrays)."""
    if isinstance(value, (np.ndarray, np.generic, list, tuple)):
        value = np.asarray(value).tolist()
        return [_plain(v) for v in value] if isinstance(value, list) else value
    return value


def _attrs_text(attrs: dict) -> str:
    return json.dumps({k: _plain(v) for k, v in attrs.items() if k != "sha256"},
                      sort_keys=True, ensure_ascii=True)


def variable_sha256(name: str, var: xr.Variable) -> str:
    """SHA-256 of one variable or coordinate: its name, dimensions, shape, type, values and
    attributes (but its own ``sha256``). Text arrays hash their UTF-8 text (they come back as
    objects from netCDF)."""
    h = hashlib.sha256()
    values = np.asarray(var.values)
    text = values.dtype.kind in "OUS"
    h.update(json.dumps([name, list(var.dims), list(values.shape),
                         "text" if text else values.dtype.str]).encode())
    if text:
        h.update("\0".join(str(v) for v in values.ravel()).encode())
    else:
        h.update(np.ascontiguousarray(values).tobytes())
    h.update(_attrs_text(var.attrs).encode())
    return h.hexdigest()


def content_sha256(ds: xr.Dataset) -> str:
    """SHA-256 of a whole dataset: its global attributes (but :data:`CHECKSUM`) and the name
    and checksum of every variable and coordinate."""
    h = hashlib.sha256(_attrs_text({k: v for k, v in ds.attrs.items() if k != CHECKSUM})
                       .encode())
    for name in sorted(ds.variables):
        h.update(f"{name}:{variable_sha256(name, ds.variables[name])};".encode())
    return h.hexdigest()


def _rerun(rule: str) -> str:
    return f"rebuild it: snakemake --forcerun {rule}"


def read_dataset(path: str | Path, expected: dict[str, dict] | None = None) -> xr.Dataset:
    """Load a dataset written by :func:`write_dataset` into memory, checking every byte of it:
    that it opens, that every variable and coordinate (values, dimensions, type, attributes)
    has its ``sha256`` and the whole its :data:`CHECKSUM` (global attributes included), as
    written.  Where ``expected[str(path)]`` is given (``{"rule", "config_sha256"}``: the rule
    that makes this path in this run and the hash of its configuration), the dataset must have
    been made by that rule under that configuration (a copied-in, restored or ``--touch``-ed
    file is not), and the messages name that rule to rerun."""
    want = (expected or {}).get(str(path), {})
    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError, RuntimeError) as error:
        raise DatasetError(f"{path} cannot be read ({error}); delete it and rerun snakemake to "
                           "rebuild it") from None
    made_by = ds.attrs.get("provenance_rule", "?")
    rerun = _rerun(want.get("rule", made_by))
    for name, var in ds.variables.items():
        if "sha256" not in var.attrs:
            raise DatasetError(f"{path}: variable {name!r} has no checksum (sha256): it was "
                               f"not written by the pipeline, or was edited; {rerun}")
        if variable_sha256(name, var) != var.attrs["sha256"]:
            raise DatasetError(f"{path}: variable {name!r} is not what rule {made_by!r} wrote "
                               f"(its values, dimensions or attributes changed since); {rerun}")
    if CHECKSUM not in ds.attrs:
        raise DatasetError(f"{path} has no checksum ({CHECKSUM}): it was not written by the "
                           f"pipeline, or was edited; {rerun}")
    if content_sha256(ds) != ds.attrs[CHECKSUM]:
        raise DatasetError(f"{path} is not what rule {made_by!r} wrote (its variables or global "
                           f"attributes changed since); {rerun}")
    if want.get("rule") not in (None, made_by):
        raise DatasetError(f"{path} was made by rule {made_by!r}, but rule {want['rule']!r} "
                           f"makes this file (copied in?); {rerun}")
    got = ds.attrs.get("provenance_config_sha256")
    if want.get("config_sha256") not in (None, got):
        raise DatasetError(f"{path} was made by rule {made_by!r} under another configuration "
                           f"(config sha256 {str(got)[:12]}…, this run expects "
                           f"{want['config_sha256'][:12]}…); {rerun}")
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
    for name, var in list(out.variables.items()):
        if var.dtype.kind == "O" and var.size == 0:
            # text without an element to tell its type, which xarray would write as floats
            # (found by the fuzzer: a law dataset of no balanced run failed its own checksum)
            out[name] = var.copy(data=np.empty(var.shape, dtype=str))
    for name, var in out.variables.items():
        var.attrs["sha256"] = variable_sha256(name, var)
    out.attrs[CHECKSUM] = content_sha256(out)
    encoding = {}
    for name, var in out.variables.items():
        if name in out.coords or var.dtype.kind not in "fiuc":
            encoding[name] = {"_FillValue": None}
        else:
            encoding[name] = {"zlib": True, "complevel": 4, "shuffle": True, "_FillValue": None}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        out.to_netcdf(path, engine="netcdf4", format="NETCDF4", encoding=encoding)
    except (OSError, RuntimeError) as error:
        free = _free_bytes(path.parent)
        if getattr(error, "errno", None) != errno.ENOSPC and (free is None or free >= FULL):
            raise
        path.unlink(missing_ok=True)
        raise OSError(errno.ENOSPC, f"no space left on device to write the dataset ({free} "
                      f"bytes free; the netCDF library said: {error})", str(path)) from None
    return path


def _free_bytes(folder: Path) -> int | None:
    """The bytes free for this user on ``folder``'s file system, None where it cannot say."""
    try:
        info = os.statvfs(folder)
    except OSError:
        return None
    return info.f_bavail * info.f_frsize
