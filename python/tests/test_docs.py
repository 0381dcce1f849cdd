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
