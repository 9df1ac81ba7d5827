"""RBDS001's touchdown angles three ways: formopt, a second method of its own, and the data set's
processing (Visual3D, RBDS001processed.txt, row 0 of the mean gait cycle: right touchdown).

    python problems/rbds_angles.py

formopt: CAST joint centres carried by each cluster, force-plate touchdowns, lab vertical from
the mean force. The second method shares none of those steps: each segment's angle is its
standing angle (the joint-centre line in the standing trial) plus its cluster's sagittal pitch
since standing (the rotation of a Kabsch fit, no joint centre carried), the lab's own Y axis as
vertical, touchdowns from the foot's speed (no force plate).

Visual3D's conventions differ from formopt's, so its numbers are not expected to match: its
hip is the thigh relative to the pelvis's anatomical frame (ASIS-PSIS plane: anteriorly tilted
when standing), where formopt's is relative to the standing posture; its knee and ankle are
relative to anatomical frames whose standing angles are not zero. The script prints the
difference and the standing offsets formopt measures, which account for most of it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from formopt.io import mocap
from formopt.measure import Measurement, measure
from formopt.measure.axes import Axes
from formopt.measure.clean import clean
from formopt.measure.filters import lowpass
from formopt.measure.kinematics import kabsch, kinematics
from formopt.measure.kinematics import pitch as cluster_pitch
from formopt.measure.touchdowns import touchdowns

DATA = Path(__file__).resolve().parents[1] / "data" / "rbds"
HEIGHT = 1.81
KINEMATIC = False
UP = np.array([0.0, 1.0, 0.0])  # the lab's vertical


def second_method(m: Measurement, up=UP):
    """Right-side (hip, knee, ankle) at the foot-speed touchdowns: standing angle + cluster pitch."""
    cal, trial = m.calibration, m.trial
    forward = cal.axes.forward - (cal.axes.forward @ up) * up
    forward /= np.linalg.norm(forward)
    axes = Axes(forward, np.cross(up, forward), up)
    ms = cal.markerset
    ref = {n: np.nanmean(v, axis=0) for n, v in clean(mocap.read(DATA / "RBDS001static.c3d")).markers.items()}

    def pitch(names):
        filtered = np.stack([lowpass(trial.markers[n], trial.rate, 10.0) for n in names], axis=1)
        R, _ = kabsch(np.array([ref[n] for n in names]), filtered)
        return cluster_pitch(R, axes)

    def standing(a, b):  # the a->b line's angle from the downward vertical (rad)
        v = axes.sagittal(b - a)
        return math.atan2(v[0], -v[1])
    hip = cal.points["R.hip"][2]
    knee = np.mean([ref[n] for n in ms.landmarks("R", "knee")], axis=0)
    ankle = np.mean([ref[n] for n in ms.landmarks("R", "ankle")], axis=0)
    trunk = pitch(ms.pelvis)
    thigh = standing(hip, knee) - pitch(ms.cluster("R", "thigh"))
    shank = standing(knee, ankle) - pitch(ms.cluster("R", "shank"))
    foot = -pitch(ms.cluster("R", "foot"))
    no_plate = mocap.Trial(dict(trial.markers), trial.rate, source=trial.source)
    kin = kinematics(no_plate, cal)
    frames = [td.frame for td in (touchdowns(no_plate, kin, cal) if KINEMATIC else m.steps).touchdowns if td.side == "R"]
    joints = np.degrees(np.column_stack([thigh + trunk, thigh - shank, foot - shank])[frames])
    return joints.mean(axis=0)


def main():
    processed = np.genfromtxt(DATA / "RBDS001processed.txt", names=True, delimiter="\t")
    static = mocap.read(DATA / "RBDS001static.c3d")
    print(f"{'':10s} {'method':34s} {'hip':>7s} {'knee':>7s} {'ankle':>7s}")
    for speed, files in (("35", ("RBDS001runT35.c3d",)), ("25", ("RBDS001runT25markers.txt", "RBDS001runT25forces.txt"))):
        m = measure(mocap.read(*(DATA / f for f in files)), static, HEIGHT)
        right = [td for td in m.steps.valid if td.side == "R"]
        ours = np.degrees([[td.angles[k] for k in ("hip", "knee", "ankle")] for td in right]).mean(axis=0)
        second = second_method(m)
        v3d = np.array([processed[f"R{j}AngZ{speed}"][0] for j in ("hip", "knee", "ankle")])
        label = f"{speed[0]}.{speed[1]} m/s"
        print(f"{label:10s} {'formopt (' + str(len(right)) + ' right touchdowns)':34s} " + " ".join(f"{v:7.1f}" for v in ours))
        print(f"{'':10s} {'second method (cluster pitch)':34s} " + " ".join(f"{v:7.1f}" for v in second)
              + "   difference " + " ".join(f"{v:+.1f}" for v in second - ours))
        print(f"{'':10s} {'Visual3D, processed row 0':34s} " + " ".join(f"{v:7.1f}" for v in v3d)
              + "   difference " + " ".join(f"{v:+.1f}" for v in v3d - ours))
    cal = m.calibration
    ref = {n: np.nanmean(v, axis=0) for n, v in static.markers.items()}
    line = cal.axes.sagittal((ref["R.ASIS"] + ref["L.ASIS"]) / 2 - (ref["R.PSIS"] + ref["L.PSIS"]) / 2)
    print(f"\nstanding: the pelvis's ASIS-PSIS line tilts {math.degrees(math.atan2(-line[1], line[0])):.1f} deg "
          f"anteriorly (Visual3D's hip counts it, formopt's does not)")


if __name__ == "__main__":
    main()
