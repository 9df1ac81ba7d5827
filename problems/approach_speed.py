"""RBDS001's foot points' approach speed at their touchdown (the source of the figures beside
StrideSettings.approach_speed).

    python problems/approach_speed.py

Per trial (treadmill, 2.5 and 3.5 m/s) and foot: the heel (Heel.Bottom) and the forefoot (the
mean of the MT1 and MT5 markers' heights); a point's ground is its height's 2nd percentile over
the trial, its touchdown the frame where it comes down within TOUCH_M of it, its approach speed
minus its vertical velocity (central differences) averaged over the APPROACH_FRAMES before. Prints
per point the median, least and greatest over the touchdowns (m/s) and their number.
"""

from __future__ import annotations

import numpy as np
from swing_clearance import DATA, TRIALS, UP

from formopt.io.mocap import read

TOUCH_M = 0.005  # a point this close above its ground (m) touches it
APPROACH_FRAMES = 3  # frames before the touchdown whose velocity is averaged (20 ms at 150 Hz)
POINTS = {"heel": ("Heel.Bottom",), "forefoot": ("MT1", "MT5")}


def approach_speeds(trial, side: str, markers: tuple[str, ...]) -> list[float]:
    """The point's approach speed (m/s, > 0 moving down) at each of its touchdowns in `trial`."""
    h = np.mean([trial.markers[f"{side}.{m}"][:, UP] for m in markers], axis=0)
    h = h - np.nanpercentile(h, 2)
    v = np.gradient(h) * trial.rate
    down = np.flatnonzero((h[1:] <= TOUCH_M) & (h[:-1] > TOUCH_M)) + 1
    return [float(-np.mean(v[k - APPROACH_FRAMES:k])) for k in down
            if k >= APPROACH_FRAMES and np.all(np.isfinite(v[k - APPROACH_FRAMES:k]))]


def main() -> int:
    for markers, forces in TRIALS:
        trial = read(DATA / markers, DATA / forces) if forces else read(DATA / markers)
        for point, names in POINTS.items():
            s = [a for side in "RL" for a in approach_speeds(trial, side, names)]
            print(f"{markers} {point}: {len(s)} touchdowns, approach speed (m/s): median {np.median(s):.3f}, "
                  f"least {min(s):.3f}, greatest {max(s):.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
