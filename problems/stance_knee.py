"""A runner's stance knee at its deepest (checks.CROUCH_DEG's source): RBDS001 at 2.5, 3.5 and 4.5
m/s from the data set's own processing (RBDS001processed.txt: Visual3D, knee flexion, the mean
cycle's stance: the vertical force above 0.5 N/kg), and RBDS001 at 3.5 m/s and RIC's runner
from formopt's measure (measure.stance_knee_deg: the right leg's mean cycle, the first local
maximum of its knee flexion, printed with its place in the cycle).

    python problems/stance_knee.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from formopt.io.mocap import read_c3d
from formopt.measure.pipeline import measure, stance_knee_deg

DATA = Path(__file__).resolve().parent.parent / "data"

TRIALS = {"RBDS001 3.5 m/s": ("rbds/RBDS001runT35.c3d", "rbds/RBDS001static.c3d", 1.81),
          "RIC 3.37 m/s": ("ric/20160226T120637_run.c3d", "ric/20160226T120637_static.c3d", 1.77)}


def processed() -> None:
    """The data set's own stance knee flexion peaks (deg)."""
    table = np.genfromtxt(DATA / "rbds" / "RBDS001processed.txt", names=True, delimiter="\t")
    for speed in ("25", "35", "45"):
        stance = table[f"RgrfY{speed}"] > 0.5
        print(f"RBDS001 {int(speed) / 10:.1f} m/s, Visual3D: stance knee at its deepest "
              f"{table[f'RkneeAngZ{speed}'][stance].max():.1f} deg")


def measured() -> None:
    """formopt's measure of the two trials' mean cycles: the stance knee's deepest flexion (deg)."""
    for name, (run, static, height) in TRIALS.items():
        knee, peak = stance_knee_deg(measure(read_c3d(DATA / run), read_c3d(DATA / static), height))
        print(f"{name}, formopt's measure: stance knee at its deepest {knee:.1f} deg "
              f"at {peak} % of the cycle")


if __name__ == "__main__":
    processed()
    measured()
