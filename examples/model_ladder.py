"""The model ladder
================

The same touchdown on each model level, from the effective mass to the
full planar body, and the absorbed energy each gives.

    python examples/model_ladder.py [OUT]
"""

import sys
from dataclasses import replace
from pathlib import Path

from matplotlib.figure import Figure

import formopt
from formopt.io.files import save_figure
from formopt.mechanics.model import MODELS

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

full = formopt.load(Path(formopt.__file__).parent / "studies" / "data" / "full_body.toml")  # package data
T_c = {kind: formopt.impact(replace(full, kind=kind)).T_c for kind in MODELS}
for kind, value in T_c.items():
    print(f"{kind:15s} T_c {value:8.3f} J")
fig = Figure(figsize=(6, 3.5))
ax = fig.subplots()
ax.bar(list(T_c), list(T_c.values()), color="tab:blue")
ax.set_ylabel("absorbed energy T_c (J)")
ax.set_title("one forefoot touchdown on each model level", fontsize=10)
ax.tick_params(axis="x", labelsize=8)
fig.tight_layout()
print("wrote", save_figure(fig, out / "model_ladder.png"))
