"""A landing
=========

From the forefoot's touchdown until the heel comes down, with passive knee and
ankle: the running joints (formopt/scenes/landing_spring.toml).

    python examples/landing.py [OUT]
"""

import sys
from pathlib import Path

import formopt
from formopt.io.files import save_figure
from formopt.report.figures import landing_figures
from formopt.report.tables import landing_table

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

scene = formopt.load("landing_spring")
landing = formopt.simulate(scene)
print(landing_table(scene, landing))
for name, fig in landing_figures(landing, scene.model(), scene.slope, scene.strike).items():
    print("wrote", save_figure(fig, out / f"landing_{name}.png"))
