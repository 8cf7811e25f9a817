"""Shared paths for the Python tests (run by ctest with the build tree's
package first on PYTHONPATH; ATTENUVIS_SOURCE_DIR and ATTENUVIS_CLI come from
ctest, with fallbacks for a direct pytest run)."""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("ATTENUVIS_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("ATTENUVIS_CLI", str(SOURCE_DIR / "build" / "apps" / "attenuvis"))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def cli():
    if not os.path.exists(CLI):
        pytest.skip(f"the attenuvis program is not built ({CLI})")
    return CLI
