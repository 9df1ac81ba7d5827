"""Every notebook runs top to bottom without an error (with FORMOPT_QUICK=1: a notebook that reads
it runs a cheaper case, e.g. stride.ipynb's 18 nodes and one start; its text says so).

The notebooks run one after another in one kernel (`kernel`), each from an empty namespace
(`%reset -f` first): a kernel's start and formopt's imports cost about 2 s of CPU a notebook
(2.2 s against 0.6 for an empty one, 2026-11-27). A notebook that uses a name it does not define
still fails; one that leaves a module imported or sys.path changed could hide another's missing
import or path (paper.ipynb adds problems/ to the path itself)."""

import os

import nbclient
import nbformat
import pytest
from helpers import ROOT
from jupyter_client.manager import AsyncKernelManager
from jupyter_core.utils import run_sync

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@pytest.fixture(scope="module")
def kernel():
    """One Python kernel for the file, started in notebooks/ (where each notebook runs from)
    with FORMOPT_QUICK=1 in its environment, shut down after the last notebook."""
    km = AsyncKernelManager(kernel_name="python3")
    run_sync(km.start_kernel)(cwd=str(ROOT / "notebooks"), env={**os.environ, "FORMOPT_QUICK": "1"})
    yield km
    run_sync(km.shutdown_kernel)(now=True)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs_top_to_bottom(path, kernel):
    nb = nbformat.read(path, as_version=4)
    # the namespace the last notebook left, emptied; no stride compiled by chance (conftest's
    # no_compile_by_chance, which does not reach the kernel: its NLPs' solves add up across notebooks)
    nb.cells.insert(0, nbformat.v4.new_code_cell(
        "%reset -f\nfrom formopt.optim.stride import collocation as _c\n"
        "_c.COMPILE_FROM = _c.RENT_ITERATIONS = 10**9\ndel _c"))
    client = nbclient.NotebookClient(nb, timeout=600, km=kernel)
    try:
        client.execute()
    finally:
        if client.kc is not None:
            client.kc.stop_channels()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors


def test_there_are_notebooks():
    assert {p.name for p in NOTEBOOKS} >= {"own_scene.ipynb", "paper.ipynb", "stride.ipynb", "own_runner.ipynb",
                                            "sweep.ipynb"}
