"""Provenance of a result: code version, configuration and software environment."""

from __future__ import annotations

import hashlib
import importlib.metadata
import json
import os
import subprocess
from datetime import datetime, timezone
from pathlib import Path

def canonical_json(obj) -> str:
    """Key-sorted, compact JSON: the canonical text of a configuration (section)."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def config_hash(obj) -> str:
    """SHA-256 of :func:`canonical_json`; equal configs give equal hashes."""
    return hashlib.sha256(canonical_json(obj).encode()).hexdigest()


#: Packages whose versions are recorded in every dataset.
RECORDED_PACKAGES = ("rotorvib", "numpy", "scipy", "numba", "xarray", "netCDF4", "pymoo", "SALib",
                     "sympy", "matplotlib", "snakemake")


def git_state(repo: str | Path) -> tuple[str, bool]:
    """Return ``(commit, dirty)`` of the git work tree at ``repo``; ``("unknown", False)`` outside git."""
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=repo, capture_output=True,
                                text=True, check=True).stdout.strip()
        status = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                                cwd=repo, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return "unknown", False
    return commit, bool(status.strip())


#: The imported package's folder: its provenance is read from where its code is, never from
#: the working folder (a project that uses the workflow as a module is a git work tree of its
#: own).
PACKAGE_DIR = Path(__file__).resolve().parents[1]


def code_origin(package: str | Path = PACKAGE_DIR) -> str:
    """``"git checkout"`` where ``package``'s files are tracked by the git work tree they lie
    in (a clone, an editable install), else ``"untracked copy"`` (a wheel in site-packages,
    a copy of the sources, even one inside another project's work tree)."""
    try:
        subprocess.run(["git", "ls-files", "--error-unmatch", "__init__.py"], cwd=package,
                       capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return "untracked copy"
    return "git checkout"


def code_state(package: str | Path = PACKAGE_DIR) -> tuple[str, bool, str]:
    """``(commit, dirty, origin)`` of the code that runs: the commit of the work tree the
    package is checked out in (:func:`git_state`) and :func:`code_origin`; an untracked copy's
    commit is ``"unknown"`` (its version is among :func:`package_versions`)."""
    origin = code_origin(package)
    if origin != "git checkout":
        return "unknown", False, origin
    return (*git_state(package), origin)


def git_date(package: str | Path = PACKAGE_DIR) -> str:
    """ISO 8601 date of the commit the package is checked out at (the archive's publication
    date, the same for every build of one commit); ``SOURCE_DATE_EPOCH`` (else 0) for an
    untracked copy or outside git."""
    try:
        if code_origin(package) != "git checkout":
            raise OSError("an untracked copy")
        return subprocess.run(["git", "log", "-1", "--format=%cI"], cwd=package,
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        epoch = int(os.environ.get("SOURCE_DATE_EPOCH", 0))
        return datetime.fromtimestamp(epoch, timezone.utc).isoformat()


def package_versions(names=RECORDED_PACKAGES) -> dict[str, str]:
    """Installed version of each package of ``names`` ("not installed" for one that is not), as
    recorded in every dataset's provenance."""
    versions = {}
    for name in names:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions
