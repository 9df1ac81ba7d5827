"""A stride: what a form costs
=============================

The periodic running half stride of the paper's body at 3.5 m/s with a heel strike
(formopt/scenes/stride.toml): cadence, step length, contact and flight, the ground force, and
the energy budget of one step, which closes to round-off.

    python examples/stride.py [OUT] [--quick]    (``--quick``: 18 collocation nodes and one start,
                                                  not 40 nodes and 4 starts)
"""

import sys
import tomllib
from pathlib import Path

import formopt
from formopt.io.files import save_figure
from formopt.io.stride_scene import parse
from formopt.report.stride import budget_figure, stride_table

out = Path(sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "out/examples")

data = tomllib.loads(formopt.scene_path("stride").read_text())
if "--quick" in sys.argv:  # the tests' run: seconds, not a minute
    data["stride"].update(nodes=18, starts=1)  # the heel strike's fewest
study = formopt.stride(parse(data, "stride.toml"))
print(stride_table(study))
best = study.best
b = best.budget
print(f"\nper step: positive work {b['positive_work_J']:.1f} J = negative work {b['negative_work_J']:.1f} J"
      f" + tendons' loss {b['spring_J']:.1f} J + impacts {b['impacts_J']:.2f} J + the rest, "
      f"balance {b['balance_J']:+.1e} J; {best.mechanical_power_W:.0f} W at {best.cadence_spm:.1f} steps/min")
if "--quick" in sys.argv:
    print("(--quick, 18 nodes and one start: the cadence and the cost move with the mesh; the scene's 40 nodes are "
          "what formopt stride stride reports)")
print("wrote", save_figure(budget_figure(best), out / "stride_budget.png"))
