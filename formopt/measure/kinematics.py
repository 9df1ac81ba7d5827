"""Segment kinematics: each calibrated point carried into the run by a least-squares rigid fit
(Kabsch) of its segment's cluster, frame by frame; sagittal segment angles (design.md section 2)
from the carried points.

The fit's residual says whether the cluster stayed rigid. The contact points' heights (`soles`)
are each of the map's heel and forefoot markers on its own (a forefoot lands on one edge first:
RBDS001's lateral metatarsal 20-40 mm below the medial one at touchdown, so the two markers'
mean lands 20-30 ms after the first of them), or the carried point where the map has none. Segment angles: thigh and shank from
the downward vertical, positive when the distal end is ahead; foot: the heel-to-forefoot line
relative to standing, toe up positive; trunk: the pelvis's forward tilt relative to standing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from .axes import Axes
from .filters import CUTOFF_HZ, lowpass
from .joints import Calibration
from .rigid import fit_residual, kabsch


@dataclass
class Kinematics:
    """Sagittal kinematics of both legs at the marker rate (SI, formopt's conventions)."""

    t: np.ndarray  # (frames,) s
    points: dict[str, np.ndarray]  # "R.knee" -> (frames, 2) forward, up (m)
    angles: dict[str, np.ndarray]  # "R.thigh", "R.shank", "R.foot", "trunk" -> (frames,) rad
    rate: float  # Hz
    residual: dict[tuple[str, ...], np.ndarray]  # cluster -> rms fit residual per frame (m)
    markers: dict[str, np.ndarray]  # filtered markers (frames, 3), lab frame (for exports)
    soles: dict[str, np.ndarray]  # "R.heel", "R.forefoot" -> (k, frames) m: the heights of the
    #                              point's own markers, or of the carried point (module docstring)


def kinematics(trial: Trial, cal: Calibration, cutoff_hz: float = CUTOFF_HZ) -> Kinematics:
    """The markers that carry `cal`'s points, low-passed at `cutoff_hz` (filters.lowpass);
    every point carried by its cluster's fit (module docstring); segment angles."""
    needed = sorted({n for cluster, _, _ in cal.points.values() for n in cluster
                     if n not in cal.points})
    trial.require(needed, "the running trial")
    if trial.frames < 10:
        raise MocapError(f"{trial.source}: {trial.frames} frames: too short for a run")
    filtered = {n: lowpass(trial.markers[n], trial.rate, cutoff_hz, trial.source) for n in needed}
    carried: dict[str, np.ndarray] = {}  # label -> (frames, 3), m
    fits, residual = {}, {}
    for name, (cluster, ref, p0) in cal.points.items():
        if cluster not in fits:  # one fit per cluster and frame (the pelvis carries both hips)
            current = np.stack([filtered[n] if n in filtered else carried[n] for n in cluster], axis=1)
            fits[cluster] = kabsch(ref, current)
            residual[cluster] = fit_residual(ref, current, *fits[cluster])
        R, t = fits[cluster]
        carried[name] = np.einsum("fij,j->fi", R, p0) + t
    points = {k: cal.axes.sagittal(v) for k, v in carried.items()}
    angles = segment_angles(points, cal.foot_offset)
    angles["trunk"] = pitch(fits[cal.points["R.hip"][0]][0], cal.axes)
    markers = {**filtered, **carried}
    soles = {}
    for key in (f"{s}.{p}" for s in SIDES for p in ("heel", "forefoot")):
        own = [n for n in cal.markerset.landmarks(*key.split(".")) if n in markers]
        soles[key] = (np.array([cal.axes.sagittal(markers[n])[:, 1] for n in own]) if own
                      else points[key][:, 1][None, :])
    return Kinematics(np.arange(trial.frames) / trial.rate, points, angles, trial.rate, residual,
                      markers, soles)


def segment_angles(points: dict, foot_offset: dict) -> dict[str, np.ndarray]:
    """Thigh, shank and foot angles (rad) of both legs from the sagittal points ("R.hip" ->
    (frames, 2)); `foot_offset`: side -> the heel-to-forefoot line's standing angle (rad)."""
    angles = {}
    for s in SIDES:
        p = {k: points[f"{s}.{k}"] for k in ("hip", "knee", "ankle", "heel", "forefoot")}
        angles[f"{s}.thigh"] = _from_down(p["knee"] - p["hip"])
        angles[f"{s}.shank"] = _from_down(p["ankle"] - p["knee"])
        line = p["forefoot"] - p["heel"]
        angles[f"{s}.foot"] = np.arctan2(line[:, 1], line[:, 0]) - foot_offset[s]
    return angles


def pitch(R, axes: Axes) -> np.ndarray:
    """Forward tilt (rad, nose down positive) of rotations R (frames, 3, 3) from standing."""
    f = R @ axes.forward
    return np.arctan2(-(f @ axes.up), f @ axes.forward)


def _from_down(v) -> np.ndarray:
    """Angle of v (frames, 2) from the downward vertical, positive when its end is ahead (rad)."""
    return np.arctan2(v[:, 0], -v[:, 1])
