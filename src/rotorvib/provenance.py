"""Provenance of a result: code version, configuration and software environment."""

from __future__ import annotations

import hashlib
import importlib.metadata
import subprocess
from pathlib import Path

#: Packages whose versions are recorded in every dataset.
RECORDED_PACKAGES = ("rotorvib", "numpy", "scipy", "numba", "xarray", "netCDF4", "pymoo",
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


def package_versions(names=RECORDED_PACKAGES) -> dict[str, str]:
    versions = {}
    for name in names:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def source_fingerprint(*modules: str, root: str | Path = "src") -> str:
    """SHA-256 over the source files of the named modules or packages under ``root``.

    ``"rotorvib.dva.figures"`` hashes ``root/rotorvib/dva/figures.py``; a package name hashes
    every ``.py`` file below it.  Files are read, not imported, so the hash follows the work
    tree the workflow runs in.  Used as a Snakemake ``params`` value so that editing library
    code under ``src/`` reruns exactly the jobs whose code changed.
    """
    root = Path(root)
    files = []
    for name in modules:
        base = root.joinpath(*name.split("."))
        if base.with_suffix(".py").is_file():
            files.append(base.with_suffix(".py"))
        elif (base / "__init__.py").is_file():
            files += sorted(base.rglob("*.py"))
        else:
            raise ModuleNotFoundError(f"no source for module {name!r} under {root}")
    digest = hashlib.sha256()
    for path in sorted(set(files)):
        digest.update(path.relative_to(root).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()
