"""Every notebook runs top to bottom without an error (with FORMOPT_QUICK=1: a notebook that reads
it runs a cheaper case, e.g. stride.ipynb's 20 nodes and one start; its text says so)."""


import nbclient
import nbformat
import pytest
from helpers import ROOT

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs_top_to_bottom(path, monkeypatch):
    monkeypatch.setenv("FORMOPT_QUICK", "1")  # the kernel inherits it
    nb = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors


def test_there_are_notebooks():
    assert {p.name for p in NOTEBOOKS} >= {"own_scene.ipynb", "paper.ipynb", "stride.ipynb", "own_runner.ipynb",
                                            "sweep.ipynb"}
