"""Every example runs as a user would run it, prints its result and writes its figure."""

import subprocess
import sys

import pytest

from helpers import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.stem for e in EXAMPLES])
def test_example_runs_and_writes_its_figure(example, tmp_path):
    out = subprocess.run([sys.executable, str(example), str(tmp_path)], capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert list(tmp_path.rglob("*.png")), "the example's figure"
