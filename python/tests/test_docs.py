"""The Python examples of the README and docs/python.md run as they are written."""

import os
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BLOCK = re.compile(r"```python\n(.*?)```", re.S)


@pytest.mark.parametrize("doc", ["README.md", "docs/python.md"])
def test_examples_run_in_order(doc, tmp_path, monkeypatch):
    """A document's blocks are one session: each runs after the ones before it."""
    import matplotlib
    matplotlib.use("Agg")
    monkeypatch.chdir(ROOT)
    session = {}
    codes = BLOCK.findall((ROOT / doc).read_text())
    assert codes, f"{doc} has no Python example"
    for i, code in enumerate(codes):
        # Files the examples write go to a temporary folder.
        for name in ["report.html", "designs", "curves.svg", "four-bar.gif"]:
            code = code.replace(f'"{name}"', repr(str(tmp_path / name)))
        exec(compile(code, f"{doc}, Python example {i + 1}", "exec"), session)


@pytest.mark.parametrize("doc", ["README.md", "docs/python.md"])
def test_examples_ask_for_no_sweep_a_student_kernel_cannot_hold(doc):
    """A sweep keeps about 0.6 kB a step (the four-bar): 20 000 000 steps took 60 s and 11.9 GB."""
    code = "\n".join(BLOCK.findall((ROOT / doc).read_text()))
    steps = [int(n.replace("_", "")) for n in re.findall(r"\bsteps=([\d_]+)", code)]
    assert steps and max(steps) <= 100_000, steps
