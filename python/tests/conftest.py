import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture
def examples():
    return EXAMPLES


@pytest.fixture
def cli():
    """The nbar program built beside the module (ctest sets NBAR_CLI)."""
    path = os.environ.get("NBAR_CLI") or str(ROOT / "build" / "apps" / "nbar" / "nbar")
    if not os.path.exists(path):
        pytest.skip("the nbar program is not built")
    return path


def pytest_report_header(config):
    return f"python: {sys.executable}"
