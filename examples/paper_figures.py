"""The paper's figures
=====================

The figures of the paper "Energy efficient walking and running - impact dynamics based on
varying geometric constraints" under fair comparisons: runs problems/paper.py, which draws
Fig. 4-6 and the model comparison and prints what each shows.

    python examples/paper_figures.py [OUT] [--quick]

--quick (the test suite's mode) draws only the model comparison: `make docs` runs this example
in full, and notebooks/paper.ipynb (also run by the tests) calls every section of paper.py.
"""

import runpy
import sys
from pathlib import Path

import formopt

ROOT = Path(formopt.__file__).resolve().parents[1]  # the repository (examples run from a checkout)
quick = "--quick" in sys.argv[1:]
args = [a for a in sys.argv[1:] if a != "--quick"]
out = Path(args[0] if args else "out/examples") / "paper"
if quick:
    paper = runpy.run_path(str(ROOT / "problems" / "paper.py"), run_name="paper")
    for line in paper["models"](out):
        print(line)
else:
    sys.argv = ["paper.py", "--out", str(out)]
    runpy.run_path(str(ROOT / "problems" / "paper.py"), run_name="__main__")
