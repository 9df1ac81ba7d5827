"""The impact of one touchdown
===========================

What the forefoot strike of formopt/scenes/forefoot_strike.toml
absorbs, the ground's impulse, and whether the no-slip assumption holds.

    python examples/impact_of_a_touchdown.py [OUT]
"""

import sys
from pathlib import Path

import formopt
from formopt.io.files import save_figure
from formopt.report.figures import indicator_figure

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

scene = formopt.load("forefoot_strike")
result = formopt.impact(scene)
print(f"T = {result.T:.2f} J, absorbed T_c = {result.T_c:.3f} J, after T_a = {result.T_a:.2f} J")
print(f"ground impulse (t, n) = {result.impulse['forefoot']} N s; mu_c = {result.mu_c:.2f}; "
      f"valid: {result.valid}")
for w in result.warnings:
    print("warning:", w)
print("wrote", save_figure(indicator_figure({"forefoot strike": result}), out / "impact.png"))
