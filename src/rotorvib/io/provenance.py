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


def git_state(repo: str | Path = ".") -> tuple[str, bool]:
    """Return ``(commit, dirty)`` of the git work tree at ``repo``; ``("unknown", False)`` outside git."""
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=repo, capture_output=True,
                                text=True, check=True).stdout.strip()
        status = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                                cwd=repo, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return "unknown", False
    return commit, bool(status.strip())


def git_date(repo: str | Path = ".") -> str:
    """ISO 8601 date of the commit checked out at ``repo`` (the archive's publication date, the
    same for every build of one commit); ``SOURCE_DATE_EPOCH`` (else 0) outside git."""
    try:
        return subprocess.run(["git", "log", "-1", "--format=%cI"], cwd=repo,
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
