"""The stubs are the package's typed face: stubtest finds no difference between them and the
module, and the documentation's examples pass `mypy --strict` against them."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

import nbar

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = pathlib.Path(nbar.__file__).resolve().parent
BLOCK = re.compile(r"```python\n(.*?)```", re.S)

pytest.importorskip("mypy", reason="the typing checks need mypy: apt-get install python3-mypy")


def run_mypy_tool(arguments, cwd):
    """mypy (or stubtest) on the package this process imported."""
    env = dict(os.environ, PYTHONPATH=str(PACKAGE.parent), MYPY_FORCE_COLOR="0")
    return subprocess.run([sys.executable, "-m", *arguments], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=600)


def test_every_module_has_a_stub():
    modules = {p.stem for p in PACKAGE.glob("*.py")} | {"_nbar"}
    stubs = {p.stem for p in PACKAGE.glob("*.pyi")}
    assert modules == stubs


def test_stubtest_finds_no_mismatch(tmp_path, cache):
    done = run_mypy_tool(["mypy.stubtest", "nbar", "--mypy-config-file", str(write_config(tmp_path, cache))], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Success" in done.stdout


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    """One mypy cache for the module's runs: numpy's stubs are analysed once, not once a test."""
    return tmp_path_factory.mktemp("mypy-cache")


def write_config(folder, cache):
    config = folder / "mypy.ini"
    config.write_text(f"[mypy]\ncache_dir = {cache}\n")
    return config


@pytest.mark.parametrize("doc", ["README.md", "docs/python.md"])
def test_documented_examples_pass_mypy_strict(doc, tmp_path, cache):
    """Each document's blocks are one session (as test_docs runs them): one file, checked whole."""
    code = "\n".join(BLOCK.findall((ROOT / doc).read_text()))
    source = tmp_path / "examples.py"
    source.write_text(code)
    # matplotlib and pandas ship no type information in Debian: their imports are the only ones let pass.
    done = run_mypy_tool(["mypy", "--strict", "--config-file", str(write_config(tmp_path, cache)), str(source)], tmp_path)
    assert done.returncode == 0, f"{doc}:\n" + done.stdout + done.stderr


NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_cells_pass_mypy_strict(path, tmp_path, cache):
    """A notebook's code cells, in order, as one file. matplotlib ships no type information in
    Debian and sympy's is partial: both are let pass as untyped (Any), nothing else is."""
    import json
    cells = ["".join(c["source"]) for c in json.loads(path.read_text())["cells"] if c["cell_type"] == "code"]
    source = tmp_path / (path.stem.replace("-", "_") + ".py")
    source.write_text("\n\n".join(cells) + "\n")
    config = write_config(tmp_path, cache)
    config.write_text(config.read_text() + "[mypy-matplotlib.*]\nignore_missing_imports = True\n"
                      "[mypy-sympy.*]\nfollow_imports = skip\n")
    done = run_mypy_tool(["mypy", "--strict", "--config-file", str(config), str(source)], tmp_path)
    assert done.returncode == 0, f"{path.name}:\n" + done.stdout + done.stderr


def test_a_typing_mistake_is_found(tmp_path, cache):
    """The check can fail: a wrong argument type in the same kind of code is reported."""
    source = tmp_path / "wrong.py"
    source.write_text('import nbar\nm = nbar.load("x.yaml")\nr = m.solve(steps="361")\nn: str = r.rows\n')
    done = run_mypy_tool(["mypy", "--strict", "--config-file", str(write_config(tmp_path, cache)), str(source)], tmp_path)
    assert done.returncode == 1
    assert 'Argument "steps" to "solve" of "Model" has incompatible type "str"' in done.stdout
    assert 'Incompatible types in assignment (expression has type "int", variable has type "str")' in done.stdout
