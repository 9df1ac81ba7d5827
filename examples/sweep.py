"""A sweep
=======

The landing of formopt/scenes/landing_spring.toml across touchdown knee angles, written
row by row to a CSV file (rerun the same command and it resumes).

    python examples/sweep.py [OUT]
"""

import sys
from pathlib import Path

import numpy as np

import formopt
import formopt.studies.sweep
from formopt.io.files import save_figure
from formopt.report.figures import sweep_figure

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

scene = formopt.load("landing_spring")
rows = formopt.sweep(scene, [("knee_deg", np.linspace(5.0, 30.0, 11))], out / "sweep_knee.csv",
                     progress=False)
good = [r for r in rows if formopt.studies.sweep.valid(r)]
failed = sum(bool(r["error"]) for r in rows)
print(f"{len(good)} valid, {len(rows) - len(good) - failed} invalid, {failed} failed of {len(rows)} "
      f"landings; T_c_total of the valid ones from {min(float(r['T_c_total']) for r in good):.3f} to "
      f"{max(float(r['T_c_total']) for r in good):.3f} J")
print("wrote", save_figure(sweep_figure(rows, ["knee_deg"]), out / "sweep_knee.png"))
