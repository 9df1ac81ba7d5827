"""The measurement without a force plate, checked on the trials that have one (issue 24, item 5).

    python problems/no_plate.py

For RBDS001 at 3.5 and 2.5 m/s: the vertical found without the plate (the standing body
pitched to the resting feet's level marker paths, formopt/measure/stance.py) against the
plate's mean force, in degrees (pitch: about the lateral axis, roll: about the running axis),
with the bootstrap spread and each side's path; the touchdowns by the foot's speed against the
plate's (ms, and how many within one frame). Then the foot-at-rest rule at higher cadences:
each run without its plate, and the RIC runner, declared at 1.2-1.4 times their rate (the same
samples, played faster; the markers' cut-off scaled alike), must land in the same frames; and
the same runs at a rate 10 times too high must be refused.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np

from formopt.io import mocap
from formopt.measure import Options, measure
from formopt.measure.filters import CUTOFF_HZ

DATA = Path(__file__).resolve().parents[1] / "data"
RBDS = DATA / "rbds"
RIC = DATA / "ric"


def without_plate(trial: mocap.Trial) -> mocap.Trial:
    out = copy.copy(trial)
    out.force, out.force_rate = None, None
    return out


def vertical(name: str, run: mocap.Trial, static: mocap.Trial, height: float):
    """The vertical and the touchdowns with and without the plate."""
    plate, free = measure(run, static, height), measure(without_plate(run), static, height)
    lab, up = plate.calibration.axes, free.calibration.axes.up
    off = math.degrees(math.acos(min(1.0, float(up @ lab.up))))
    print(f"{name}: vertical without the plate {off:.2f} deg from the plate's (pitch "
          f"{math.degrees((up - lab.up) @ lab.forward):+.2f}, roll {math.degrees((up - lab.up) @ lab.left):+.2f})")
    print(f"  without the plate: {next(n for n in free.steps.notes if 'resting feet' in n)}")
    print(f"  with the plate:    {next(n for n in plate.steps.notes if 'resting feet' in n)}")
    times = np.array([td.time for td in plate.steps.touchdowns])
    frame = 1.0 / plate.kinematics.rate
    for side in ("R", "L"):
        gaps = np.array([td.time - times[np.argmin(np.abs(times - td.time))]
                         for td in free.steps.touchdowns if td.side == side]) * 1e3
        print(f"  touchdowns {side} by the foot's speed: {np.mean(gaps):+.1f} +- {np.std(gaps):.1f} ms from "
              f"the plate's, {np.sum(np.abs(gaps) <= frame * 1e3 + 1e-6)} of {len(gaps)} within one frame")


def faster(name: str, run: mocap.Trial, static: mocap.Trial, height: float):
    """The run declared at higher rates: the same touchdown frames, a 10x rate refused."""
    base = measure(run, static, height).steps
    frames = [(td.frame, td.side) for td in base.touchdowns]
    for factor in (1.2, 1.3, 1.4):
        fast = copy.deepcopy(run)
        fast.rate *= factor
        steps = measure(fast, static, height, Options(cutoff_hz=CUTOFF_HZ * factor)).steps
        found = [(td.frame, td.side) for td in steps.touchdowns]
        same = len(set(frames) & set(found))
        near = sum(any(abs(f - g) <= 1 and s == t for g, t in found) for f, s in frames)
        print(f"{name} x{factor:g}: {steps.cadence_spm:.0f} steps/min, {same} of {len(frames)} "
              f"touchdowns in the same frame, {near} within one, belt {steps.belt_speed / base.belt_speed:.3f} times")
    wrong = copy.deepcopy(run)
    wrong.rate *= 10
    try:
        measure(wrong, static, height)
        print(f"{name} x10: NOT refused")
    except mocap.MocapError as err:
        print(f"{name} x10: refused: {err}")


def main():
    static = mocap.read(RBDS / "RBDS001static.c3d")
    runs = {"RBDS001 T35": mocap.read(RBDS / "RBDS001runT35.c3d"),
            "RBDS001 T25": mocap.read(RBDS / "RBDS001runT25markers.txt", RBDS / "RBDS001runT25forces.txt")}
    for name, run in runs.items():
        vertical(name, run, static, 1.81)
    for name, run in runs.items():
        faster(f"{name} (no plate)", without_plate(run), static, 1.81)
    faster("RIC", mocap.read(RIC / "20160226T120637_run.c3d"), mocap.read(RIC / "20160226T120637_static.c3d"), 1.77)


if __name__ == "__main__":
    main()
