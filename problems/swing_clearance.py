"""RBDS001's swing foot clearance while the other foot is loaded (the source of the figures beside
optim.stride.contact.CLEARANCE and docs/concepts/muscles.md).

    python problems/swing_clearance.py

Per trial (treadmill, 2.5 and 3.5 m/s): each foot's lowest point is the least of its heel and
first and fifth metatarsal markers above that marker's own height on the ground (its 2nd
percentile over the trial); the stance foot is the lower one; over each stretch of frames with the
treadmill's vertical force above 50 N, the swing foot's least height. Prints the median, least
and greatest over the stances (m).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from formopt.io.mocap import read

DATA = Path(__file__).resolve().parents[1] / "data" / "rbds"
TRIALS = (("RBDS001runT25markers.txt", "RBDS001runT25forces.txt"), ("RBDS001runT35.c3d", None))
POINTS = ("Heel.Bottom", "MT1", "MT5")
LOADED_N = 50.0  # vertical force (N) above which a foot is on the ground
UP = 1  # the data set's vertical axis (Y up)


def least_clearances(trial) -> list[float]:
    """The swing foot's least height (m) over each loaded stretch of `trial` (module docstring)."""
    vertical = int(np.argmax(np.nanmean(np.abs(trial.force), axis=0)))
    frames = np.round(np.arange(trial.frames) * trial.force_rate / trial.rate).astype(int)
    loaded = np.abs(trial.force[:, vertical])[frames.clip(0, len(trial.force) - 1)] > LOADED_N
    heights = {s: np.vstack([trial.markers[f"{s}.{p}"][:, UP] for p in POINTS]) for s in "RL"}
    low = {s: np.nanmin(h - np.nanpercentile(h, 2, axis=1)[:, None], axis=0) for s, h in heights.items()}
    swing = np.where(low["R"] < low["L"], low["L"], low["R"])
    kept = loaded & np.isfinite(swing)
    edges = np.flatnonzero(np.diff(np.r_[0, kept.astype(int), 0]))
    return [float(np.nanmin(swing[a:b])) for a, b in zip(edges[::2], edges[1::2]) if b - a > 5]


def main() -> int:
    for markers, forces in TRIALS:
        trial = read(DATA / markers, DATA / forces) if forces else read(DATA / markers)
        m = least_clearances(trial)
        print(f"{markers}: {len(m)} stances, the swing foot's least height (m): median {np.median(m):.3f}, "
              f"least {min(m):.3f}, greatest {max(m):.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
