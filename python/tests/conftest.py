import os
import pathlib
import sys

import pytest

import nbar

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture
def examples():
    return EXAMPLES


# A non-Grashof four-bar swept round: every sweep of it stops at its toggle, crank = 99.7151 deg,
# and a stop is placed at its driver, dr.yaml:6:5.
TOGGLE_STOP = """units: {length: mm, angle: deg}
points: {O2: [0, 0], O4: [200, 0], A: [0, 80], B: [150, 150]}
ground: [O2, O4]
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
drivers:
  - {angle: crank, from: 0, to: 360, speed: 120 rpm}
lengths: {crank: 120, coupler: 100, rocker: 150}
"""


@pytest.fixture
def toggle_stop():
    return nbar.loads(TOGGLE_STOP, "dr.yaml")


@pytest.fixture
def cli():
    """The nbar program built beside the module (ctest sets NBAR_CLI)."""
    path = os.environ.get("NBAR_CLI") or str(ROOT / "build" / "apps" / "nbar" / "nbar")
    if not os.path.exists(path):
        pytest.skip("the nbar program is not built")
    return path


def pytest_report_header(config):
    return f"python: {sys.executable}"
