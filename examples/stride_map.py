"""A stride map: what speed and cadence cost
===========================================

The half stride of formopt/scenes/stride.toml (the paper's body, heel strike) solved on a 3 x 3
grid of running speed and imposed cadence, each stride warm-started from its neighbour on the
grid, the rows written to a CSV file as they come (rerun the same command and it resumes). The
figure: the objective, the mechanical power W+/T and the impact loss over the grid, a star at
each speed's least objective.

To stay within seconds this map runs at 18 collocation nodes (the heel strike's fewest) and one
start; the cadence and cost move with the mesh (the scene's 40 nodes are what `formopt stride`
reports), so read it for its shape, not its numbers. On the command line, with the scene's own
nodes and a progress bar: ``formopt sweep stride --param speed_mps=3:4:3 --param cadence_spm=160:180:3``.

    python examples/stride_map.py [OUT] [--quick]    (about 20 s of CPU; ``--quick``, the tests' run:
                                                      3.5 m/s at 160 and 180 steps/min alone, about half)
"""

import sys
from pathlib import Path

import numpy as np

import formopt
from formopt.io.files import save_figure
from formopt.report.stride_sweep import map_figure
from formopt.studies.stride_map import for_nodes

out = Path(sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "out/examples")

scene = for_nodes(formopt.load("stride"), 18, starts=1)
quick = "--quick" in sys.argv  # one speed, the cadences' ends: a chain's cold start and one warm start
speeds = [3.5] if quick else np.linspace(3.0, 4.0, 3)
grid = [("speed_mps", np.asarray(speeds)), ("cadence_spm", np.linspace(160.0, 180.0, 2 if quick else 3))]
rows = formopt.sweep(scene, grid, out / "stride_map.csv", progress=False, workers=1)
valid = [r for r in rows if r["valid"] == "True"]
print(f"{len(valid)} valid of {len(rows)} strides (18 nodes, one start)")
for r in rows:
    print(f"  {float(r['speed_mps']):.1f} m/s, {float(r['cadence_spm']):.0f} steps/min: "
          f"{float(r['mechanical_power_W']):.0f} W, impact loss {float(r['impact_loss_W']):.1f} W"
          + ("" if r["valid"] == "True" else f"  INVALID ({r['status'] or r['error']})"))
print("wrote", save_figure(map_figure(rows, "speed_mps", "cadence_spm"), out / "stride_map.png"))
