"""The running joints' defaults, measured: RBDS001's quasi-stiffness and touchdown moments.

    python problems/joint_stiffness.py

From the data set's own inverse dynamics (RBDS001processed.txt: the mean right gait cycle,
0-100 % from touchdown, sagittal angles in deg and moments in N m/kg, knee extensor and ankle
plantarflexor positive) at 2.5, 3.5 and 4.5 m/s: the quasi-stiffness (least-squares slope of
moment against angle from touchdown to peak knee flexion, with its correlation), the moment at
touchdown (the preload) and the peak stance moment. landing.RUNNING_JOINTS holds the 3.5 m/s
values; the test tests/mechanics/test_joint_moments.py checks that they are these.
Compare: sprinters' knee 17-24 and ankle 7 N m/deg (Kuitunen, Komi & Kyrolainen 2002, Med Sci
Sports Exerc 34:166), about 0.2-0.3 and 0.09 N m/(kg deg).
"""

from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parent.parent / "data" / "rbds" / "RBDS001processed.txt"
SPEEDS = ("25", "35", "45")


def measure(path=DATA) -> dict:
    """{speed: {joint: {stiffness, r, preload, peak}}}: N m/(kg deg), 1, N m/kg, N m/kg."""
    data = np.genfromtxt(path, names=True, delimiter="\t")
    result = {}
    for speed in SPEEDS:
        knee, vertical = data[f"RkneeAngZ{speed}"], data[f"RgrfY{speed}"]
        stance = int(np.argmin(np.nan_to_num(vertical, nan=0.0) > 0.5))  # first row off the ground
        loading = slice(0, int(np.argmax(knee[:stance])) + 1)  # touchdown to peak knee flexion
        result[speed] = {}
        for joint in ("knee", "ankle"):
            angle, moment = data[f"R{joint}AngZ{speed}"], data[f"R{joint}MomZ{speed}"]
            slope = np.polyfit(angle[loading], moment[loading], 1)[0]
            result[speed][joint] = {"stiffness": float(slope),
                                    "r": float(np.corrcoef(angle[loading], moment[loading])[0, 1]),
                                    "preload": float(moment[0]),
                                    "peak": float(np.nanmax(moment[:stance]))}
    return result


def main():
    print(f"{DATA.name}: quasi-stiffness from touchdown to peak knee flexion\n")
    print(f"{'speed':>6s} {'joint':>6s} {'k N m/(kg deg)':>15s} {'r':>6s} {'at touchdown N m/kg':>20s} "
          f"{'peak N m/kg':>12s}")
    for speed, joints in measure().items():
        for joint, v in joints.items():
            print(f"{int(speed) / 10:6.1f} {joint:>6s} {v['stiffness']:15.4f} {v['r']:6.3f} "
                  f"{v['preload']:20.3f} {v['peak']:12.2f}")


if __name__ == "__main__":
    main()
