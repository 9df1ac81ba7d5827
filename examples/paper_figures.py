"""The paper's figures
=====================

The figures of the paper "Energy efficient walking and running - impact dynamics based on
varying geometric constraints" under fair comparisons: runs problems/paper.py, which draws
Fig. 4-6 and the model comparison and prints what each shows.

    python examples/paper_figures.py [OUT]
"""

import runpy
import sys
from pathlib import Path

import formopt

ROOT = Path(formopt.__file__).resolve().parents[1]  # the repository (examples run from a checkout)
out = sys.argv[1] if len(sys.argv) > 1 else "out/examples"
sys.argv = ["paper.py", "--out", str(Path(out) / "paper")]
runpy.run_path(str(ROOT / "problems" / "paper.py"), run_name="__main__")
