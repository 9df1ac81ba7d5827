"""A posture optimum
=================

The touchdown posture of formopt/scenes/demo.toml that absorbs the least
energy, what holds it there, and how it differs from the reference.

    python examples/posture_optimum.py [OUT]
"""

import sys
from pathlib import Path

import formopt
from formopt.io.files import save_figure
from formopt.report.figures import posture_figure
from formopt.report.tables import solve_table

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

scene = formopt.load("demo")
optimum = formopt.solve(scene)
print(solve_table(scene, optimum))
fig = posture_figure(scene.body, scene.strike, scene.slope,
                     [(scene.state, "reference", "0.55"), (optimum.state, "optimum", "tab:blue")])
print("wrote", save_figure(fig, out / "posture_optimum.png"))
