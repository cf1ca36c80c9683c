"""Shared fixtures: paper C's rotor and Table 2 from the repository's configuration."""

from pathlib import Path

import pytest

from rotorvib.io.config import load_yaml, validate_config
from rotorvib.models.absorber.parameters import Rotor, dual_absorber

ROOT = Path(__file__).resolve().parents[1]


def pytest_collection_modifyitems(items):
    """The workflow tests first: most of the suite's time, in one file, which pytest-xdist
    (pyproject.toml) then starts on one worker at once while the other takes the library
    tests."""
    items.sort(key=lambda item: item.get_closest_marker("workflow") is None)


@pytest.fixture(scope="session")
def config():
    return validate_config(load_yaml(ROOT / "config/config.yaml"),
                           load_yaml(ROOT / "config/schema.yaml"))


@pytest.fixture(scope="session")
def schema():
    return load_yaml(ROOT / "config/schema.yaml")


@pytest.fixture(scope="session")
def rotor(config):
    return Rotor(**config["paper_c"]["rotor"])


@pytest.fixture(scope="session")
def table2(config):
    return dual_absorber(**config["paper_c"]["table2"])


def cf_check(*paths):
    """Run the compliance-checker (CF 1.11) on ``paths`` in one process; return (all passed,
    report naming each file's issues)."""
    import subprocess
    import sys

    checker = Path(sys.executable).parent / "compliance-checker"
    run = subprocess.run([str(checker), "--test", "cf:1.11", "--criteria", "normal",
                          *map(str, paths)], capture_output=True, text=True)
    return run.returncode == 0, run.stdout
