"""The fixed touchdown states of formopt bench (formopt.bench.read_states reads them back):
forefoot strikes like RBDS subject 001's.

    python problems/bench/make_states.py      # writes problems/bench/states.csv (seed printed)

Uniform in: trunk 0..10, hip 15..30, knee 5..25 deg, and the foot 3..20 deg toe-down (so that
the forefoot strikes: ankle = foot - shank); hip velocity 2.5..5 m/s forward, -0.9..-0.4 m/s
down; thigh -100..60, shank -400..-150, foot -300..-80 deg/s.
"""

import csv
from pathlib import Path

import numpy as np

SEED = 20261122
N = 200
RANGES = {"trunk_deg": (0, 10), "hip_deg": (15, 30), "knee_deg": (5, 25), "ankle_deg": (-20, -3),
          "hip_vx": (2.5, 5.0), "hip_vz": (-0.9, -0.4), "omega_thigh_dps": (-100, 60),
          "omega_shank_dps": (-400, -150), "omega_foot_dps": (-300, -80)}


def main():
    rng = np.random.default_rng(SEED)
    path = Path(__file__).with_name("states.csv")
    with path.open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(RANGES)
        for _ in range(N):
            row = dict(zip(RANGES, (rng.uniform(*r) for r in RANGES.values())))
            shank = row["hip_deg"] - row["trunk_deg"] - row["knee_deg"]
            row["ankle_deg"] -= shank  # the draw was the foot angle: ankle = foot - shank
            writer.writerow([f"{v:.6f}" for v in row.values()])
    print(f"seed {SEED}: wrote {N} states to {path}")


if __name__ == "__main__":
    main()
