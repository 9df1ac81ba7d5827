"""A compiled batch
================

The impact map as C code, mapped over many touchdown states at once
(the absorbed energy of 10,000 random forefoot strikes).

    python examples/compiled_batch.py [OUT]
"""

import sys
import time
from pathlib import Path

import casadi as ca
import numpy as np
from matplotlib.figure import Figure

from formopt.io.files import save_figure
from formopt.mechanics.body import paper_body
from formopt.mechanics.compiled import external
from formopt.mechanics.impact import impact_function, on_ground
from formopt.mechanics.model import build_model
from formopt.studies.bench import read_states

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")
SEED = 7
rng = np.random.default_rng(SEED)
base = read_states()  # the bench's forefoot strikes, resampled with small changes
states = base[rng.integers(0, len(base), 10000)] * rng.uniform(0.95, 1.05, (10000, base.shape[1]))
# no-slip T_c depends on no friction; the ground is level
f = on_ground(impact_function(build_model(paper_body(), "leg"), "forefoot", outputs=["T_c"]), 0.8, 0.0)
batch = external(f.map(len(states), "serial"))  # generated, compiled (cached), loaded
t = time.perf_counter()
T_c = np.asarray(batch(ca.DM(states.T)), float).ravel()
elapsed = time.perf_counter() - t
print(f"seed {SEED}: {len(states)} states in {elapsed * 1e3:.1f} ms ({len(states) / elapsed:,.0f} states/s); "
      f"T_c median {np.median(T_c):.2f} J")
fig = Figure(figsize=(5, 3.5))
ax = fig.subplots()
ax.hist(T_c, bins=60, color="tab:blue")
ax.set_xlabel("absorbed energy T_c (J)")
ax.set_ylabel("touchdowns")
fig.tight_layout()
print("wrote", save_figure(fig, out / "compiled_batch.png"))
