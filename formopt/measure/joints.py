"""Joint centres and foot points in the standing trial (a calibrated anatomical system, CAST),
each expressed on the cluster that carries it into the run (kinematics.py).

Hip by Harrington et al. (2007, J Biomech 40:595-602) from the pelvis markers, or at a
landmark (the greater trochanter's sagittal projection); knee and ankle at the midpoints of
their landmarks; heel and forefoot at their markers or from the foot's geometry
(markerset.FOOT_GEOMETRY). Positions are lab points (3,) in m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..io import markerset as msets
from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from .axes import Axes, find_axes

# Segment lengths over stature (Winter 2009, fig. 4.1: thigh 0.245, leg 0.246), accepted
# between half and one and a half times these
LENGTH_PER_HEIGHT = {"thigh": 0.245, "shank": 0.246}


@dataclass(frozen=True)
class Calibration:
    """Anatomical points in the standing trial and the clusters that carry them."""

    markerset: msets.MarkerSet
    axes: Axes
    # point -> (cluster: marker labels or carried points "R.hip", cluster0 (k, 3), point0 (3,)),
    # in the order they are carried (pelvis, thigh, shank, foot)
    points: dict[str, tuple[tuple[str, ...], np.ndarray, np.ndarray]]
    foot_offset: dict[str, float]  # rad: the heel-to-forefoot line's angle when standing
    lengths: dict[str, float]  # m: "R.thigh" (hip-knee), "R.shank" (knee-ankle), "R.foot"
    notes: list[str] = field(default_factory=list)


def harrington_hip(ref: dict, ms: msets.MarkerSet, side: str, up) -> np.ndarray:
    """Hip joint centre (3,; m, lab) from the pelvis markers: Harrington et al. (2007).

    Pelvis frame at the mid-ASIS: x anterior, y superior, z right; PW the ASIS distance,
    PD the mid-ASIS to mid-PSIS distance; HJC = (-0.24 PD - 9.9, -0.30 PW - 10.9,
    +-(0.33 PW + 7.3)) mm (+ right, - left). y is taken upward along the lab's up, so a
    mirrored file frame does not flip it. `ref`: label -> standing position (3,), m.
    """
    assert ms.asis is not None and ms.psis is not None  # io.markerset: a "harrington" hip has them
    m = {n: ref[n] * 1e3 for n in (*ms.asis, *ms.psis)}
    mid_asis = (m[ms.asis[0]] + m[ms.asis[1]]) / 2
    mid_psis = (m[ms.psis[0]] + m[ms.psis[1]]) / 2
    z = m[ms.asis[0]] - m[ms.asis[1]]
    pw = np.linalg.norm(z)
    z /= pw
    x = mid_asis - mid_psis
    pd = np.linalg.norm(x)
    x -= (x @ z) * z
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    y *= 1.0 if y @ up > 0 else -1.0
    sign = 1.0 if side == "R" else -1.0
    local = np.array([-0.24 * pd - 9.9, -0.30 * pw - 10.9, sign * (0.33 * pw + 7.3)])
    return (mid_asis + local[0] * x + local[1] * y + local[2] * z) * 1e-3


def foot_geometry(ref: dict, ms: msets.MarkerSet, side: str, ankle, axes: Axes, height: float):
    """Heel and forefoot points (3,) from the ankle centre and the foot length
    (markerset.FOOT_GEOMETRY), at the height of the foot's lowest standing marker."""
    g = msets.FOOT_GEOMETRY
    length = g["foot_length_per_height"] * height
    markers = [ref[n] for n in ms.cluster(side, "foot") if not n.startswith("@")]
    floor = min(m @ axes.up for m in markers)
    heel = ankle - g["heel_behind_ankle"] * length * axes.forward
    heel = heel + (floor - heel @ axes.up) * axes.up
    return heel, heel + g["forefoot_from_heel"] * length * axes.forward


def joint_centres(ref: dict, ms: msets.MarkerSet, side: str, axes: Axes, height: float) -> dict:
    """Hip, knee, ankle, heel and forefoot of one leg in the standing trial (module docstring)."""
    centre = {}
    if ms.hip == "harrington":
        centre["hip"] = harrington_hip(ref, ms, side, axes.up)
    else:
        centre["hip"] = np.mean([ref[n] for n in ms.landmarks(side, "hip")], axis=0)
    for key in ("knee", "ankle"):
        centre[key] = np.mean([ref[n] for n in ms.landmarks(side, key)], axis=0)
    if "heel" in ms.leg:
        centre["heel"] = np.mean([ref[n] for n in ms.landmarks(side, "heel")], axis=0)
        centre["forefoot"] = np.mean([ref[n] for n in ms.landmarks(side, "forefoot")], axis=0)
    else:
        centre["heel"], centre["forefoot"] = foot_geometry(ref, ms, side, centre["ankle"], axes, height)
    return centre


def calibrate(static: Trial, trial: Trial, ms: msets.MarkerSet, height: float) -> Calibration:
    """Joint centres and heel/forefoot points of both legs, expressed on their clusters; the
    thigh and shank lengths checked against the stature."""
    axes, notes = find_axes(static, trial, ms)
    ref = static.mean_positions()
    points, foot_offset, lengths = {}, {}, {}
    for s in SIDES:
        centre = joint_centres(ref, ms, s, axes, height)
        for point, names in (("hip", ms.pelvis), ("knee", ms.cluster(s, "thigh")),
                             ("ankle", ms.cluster(s, "shank")), ("heel", ms.cluster(s, "foot")),
                             ("forefoot", ms.cluster(s, "foot"))):
            points[f"{s}.{point}"] = (*_cluster(names, s, centre, ref), centre[point])
        line = axes.sagittal(centre["forefoot"] - centre["heel"])
        foot_offset[s] = math.atan2(line[1], line[0])
        lengths[f"{s}.thigh"] = float(np.linalg.norm(centre["hip"] - centre["knee"]))
        lengths[f"{s}.shank"] = float(np.linalg.norm(centre["knee"] - centre["ankle"]))
        lengths[f"{s}.foot"] = float(np.linalg.norm(centre["forefoot"] - centre["heel"]))
    _check_lengths(static, lengths, height)
    return Calibration(ms, axes, points, foot_offset, lengths, notes)


def _cluster(names, side: str, centre: dict, ref: dict) -> tuple[tuple[str, ...], np.ndarray]:
    """A cluster's members and their standing positions (k, 3): markers, or "@knee" for the
    point "R.knee" carried by the segment above, standing at centre["knee"]."""
    cluster = tuple(f"{side}.{n[1:]}" if n.startswith("@") else n for n in names)
    return cluster, np.array([centre[n[1:]] if n.startswith("@") else ref[n] for n in names])


def _check_lengths(static: Trial, lengths: dict, height: float) -> None:
    """Thigh and shank between half and one and a half times LENGTH_PER_HEIGHT statures."""
    for s in SIDES:
        for seg, per in LENGTH_PER_HEIGHT.items():
            length = lengths[f"{s}.{seg}"]
            if not 0.5 * per * height < length < 1.5 * per * height:
                raise MocapError(f"{static.source}: the {'right' if s == 'R' else 'left'} {seg} is "
                                 f"{length:.3g} m long, not a {height:g} m runner's (about "
                                 f"{per * height:.2f} m): wrong units, landmarks or stature")
