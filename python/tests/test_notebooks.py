"""Every notebook runs top to bottom, from a copy in a folder of its own (as a student copies one);
their cells assert the key numbers."""

import os
import pathlib

import pytest

NOTEBOOKS = sorted((pathlib.Path(__file__).resolve().parents[2] / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(path, as_version=4)
    assert "../" not in "".join(c.source for c in notebook.cells), "a notebook finds files through nbar.examples"
    os.environ.setdefault("MPLBACKEND", "Agg")
    # The kernel runs in a folder with nothing else in it: it finds the module where this process did.
    import nbar
    os.environ["PYTHONPATH"] = os.pathsep.join(
        [str(pathlib.Path(nbar.__file__).resolve().parents[1])] + os.environ.get("PYTHONPATH", "").split(os.pathsep))
    client = nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    errors = [o for c in notebook.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors
