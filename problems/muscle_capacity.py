"""The muscle layer against a runner: RBDS001's measured joint moments beside what gait2d's
muscles, scaled to its body (62 kg, 1.81 m), can hold along its measured joint angles.

    python problems/muscle_capacity.py

For each speed and joint, over the mean right gait cycle (RBDS001processed.txt; angles in deg,
moments in N m/kg, knee extensor and ankle plantarflexor positive; its hip moment is flexor
positive: -1.0 N m/kg at touchdown, where the hip extensors work, +1.0 at toe-off, so it is
negated here to extensor positive like formopt's): the largest
extending and flexing moments measured, and the least ratio of the muscles' isometric capacity
to the measured moment over the cycle (the margin: every muscle that turns the joint the
measured way fully active, the rest off, the equilibrium at rest; where the moment is below
0.2 N m/kg the ratio is not taken). Isometric: shortening lowers the capacity, lengthening raises
it. Then the passive moment of the inactive muscles, largest over the cycle.
"""

from pathlib import Path

import casadi as ca
import numpy as np

from formopt.io.muscle_table import gait2d_muscles
from formopt.mechanics import muscles as mu

DATA = Path(__file__).resolve().parent.parent / "data" / "rbds" / "RBDS001processed.txt"
MASS, HEIGHT = 62.0, 1.81  # data/rbds/RBDSinfo.txt
JOINTS = ("hip", "knee", "ankle")
HIP_FLIP = np.array([-1.0, 1.0, 1.0])  # the data set's moments -> extensor / plantarflexor positive


def moments(leg, activation, theta) -> np.ndarray:
    """Joint moments (N m, extensor / plantarflexor positive) at rest for activations a (n)."""
    force = mu.isometric_force(leg, activation, theta)
    return np.asarray(mu.joint_moments(leg, ca.DM(force)), float).ravel()


def capacity(leg, theta, joint: int, sign: float) -> float:
    """The isometric moment at `joint` of every muscle turning it the `sign` way, fully active."""
    turning = (-leg.moment_arms[:, joint] * sign > 0).astype(float)
    force = mu.isometric_force(leg, turning, theta) * turning
    return float(-(leg.moment_arms[:, joint] @ (leg.max_force * force)) * sign)


def main() -> None:
    data = np.genfromtxt(DATA, names=True, delimiter="\t")
    leg = gait2d_muscles(MASS, HEIGHT)
    print(f"RBDS001 ({MASS:g} kg, {HEIGHT:g} m), measured moments and the muscles' margin")
    for speed in ("25", "35", "45"):
        angles = np.radians(np.column_stack([data[f"R{j}AngZ{speed}"] for j in JOINTS]))
        measured = np.column_stack([data[f"R{j}MomZ{speed}"] for j in JOINTS]) * MASS * HIP_FLIP
        passive = np.array([moments(leg, np.zeros(8), theta) for theta in angles])
        print(f"{speed[0]}.{speed[1]} m/s")
        for k, joint in enumerate(JOINTS):
            ratios = [(capacity(leg, theta, k, np.sign(m)) / abs(m), percent, m)
                      for theta, m, percent in zip(angles, measured[:, k], data["PercGcycle"])
                      if abs(m) > 0.2 * MASS]
            least, percent, moment = min(ratios)
            print(f"  {joint:5s} measured {measured[:, k].max():4.0f} / {measured[:, k].min():4.0f} N m"
                  f"  least capacity/measured {least:4.2f} ({moment:+4.0f} N m at {percent:3.0f} %)"
                  f"  passive {passive[:, k].max():4.1f} / {passive[:, k].min():5.1f} N m")


if __name__ == "__main__":
    main()
