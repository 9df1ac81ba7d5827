"""Measured postures: motion capture import, lab axes, joint centres, touchdowns, strike pattern.

Readers: C3D through ezc3d (markers, force plates with their calibration, units and rates from
the file) and the RBDS text layout (markers: Time (s) then NAMEX NAMEY NAMEZ in mm; forces:
frame, Fx Fy Fz (N), ... at the rate that spans the marker file's duration).

The method (a calibrated anatomical system, CAST):
- Lab axes from the data: up is the normal of the floor plane through the static trial's
  foot markers (heel bottoms, first and fifth metatarsal heads), forward the mean heel-to-toe
  direction in that plane. Nothing about the lab's own axes is assumed.
- Joint centres in the static trial: hip by Harrington et al. (2007, J Biomech 40:595-602)
  from the pelvis markers; knee and ankle at the midpoints of the epicondyle and malleolus
  markers. Each is carried into the running trial by a least-squares rigid fit (Kabsch) of
  its segment's marker cluster, frame by frame.
- Markers low-pass filtered (4th-order zero-lag Butterworth, 10 Hz: Winter 2009), velocities
  by central differences. Short gaps (<= 10 frames) are interpolated; longer ones are
  reported and the steps they touch are left out.
- Touchdowns from the vertical force (50 N, rising) where there is a force plate: a single
  treadmill plate sees both feet, the side is the foot that is lower then; from the foot's
  height otherwise (its lowest point within 1 cm of its stance level). Strike pattern from the foot strike angle (foot angle at touchdown
  relative to standing; Altman & Davis 2012, Gait Posture 35:298-300): rearfoot > 8 deg,
  forefoot < -1.6 deg, midfoot between.
- Treadmill: the belt speed is measured as the stance foot's backward speed; hip velocities
  are given in the ground's frame (the belt's).
- RBDS has no trunk markers: the trunk angle is the pelvis's tilt relative to standing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..mechanics.errors import InputError

SIDES = ("R", "L")
PELVIS = ("R.ASIS", "L.ASIS", "R.PSIS", "L.PSIS")
CLUSTER = {"thigh": ("Thigh.Top.Lateral", "Thigh.Bottom.Lateral", "Thigh.Top.Medial", "Thigh.Bottom.Medial"),
           "shank": ("Shank.Top.Lateral", "Shank.Bottom.Lateral", "Shank.Top.Medial", "Shank.Bottom.Medial"),
           "foot": ("Heel.Top", "Heel.Bottom", "Heel.Lateral", "MT1", "MT5")}
ANATOMICAL = ("Knee", "Knee.Medial", "Ankle", "Ankle.Medial")
CUTOFF_HZ = 10.0
MAX_GAP = 10  # frames interpolated; longer gaps leave their steps out
FORCE_THRESHOLD = 50.0  # N
# Without a force plate: touchdown when the foot's lowest point comes within 1 cm of its stance
# level (RBDS 2.5 m/s: a median 3 ms, at most 27 ms, from the force plate's touchdowns)
KINEMATIC_LEVEL = 0.01  # m
REARFOOT_DEG, FOREFOOT_DEG = 8.0, -1.6  # Altman & Davis (2012) foot strike angle thresholds


class MocapError(InputError):
    """A motion-capture file formopt cannot use, and why."""


@dataclass
class Trial:
    """Markers (m, lab axes as recorded) and, if any, the ground reaction force (N)."""

    markers: dict[str, np.ndarray]  # name -> (frames, 3)
    rate: float  # Hz
    force: np.ndarray | None = None  # (samples, 3)
    force_rate: float | None = None
    source: str = ""
    gaps: dict[str, list[tuple[int, int]]] = field(default_factory=dict)  # long gaps (start, stop)
    notes: list[str] = field(default_factory=list)  # what the reader did that a user should know


# -- readers ------------------------------------------------------------------------------

def read(path, forces=None) -> Trial:
    """A trial from a C3D file or an RBDS marker text file (with an optional force file)."""
    path = Path(path)
    if not path.exists():
        raise MocapError(f"{path}: no such file")
    if path.suffix.lower() == ".c3d":
        return read_c3d(path)
    return read_text(path, forces)


def read_c3d(path) -> Trial:
    import ezc3d

    try:
        c3d = ezc3d.c3d(str(path), extract_forceplat_data=True)
    except (RuntimeError, ValueError, OSError) as err:
        raise MocapError(f"{path}: not a readable C3D file ({err})") from None
    point = c3d["parameters"]["POINT"]
    labels = point["LABELS"]["value"]
    rate = float(point["RATE"]["value"][0])
    unit = point["UNITS"]["value"][0].strip().lower() if point["UNITS"]["value"] else "mm"
    scale = {"mm": 1e-3, "cm": 1e-2, "m": 1.0}.get(unit)
    if scale is None:
        raise MocapError(f"{path}: marker units {unit!r} not understood (mm, cm or m)")
    points = c3d["data"]["points"][:3] * scale
    if points.shape[2] < 2 or rate <= 0:
        raise MocapError(f"{path}: no marker frames (truncated or empty)")
    declared = _declared_frames(path)
    if declared is not None and points.shape[2] < declared:
        raise MocapError(f"{path}: truncated: the file declares {declared} frames but holds "
                         f"{points.shape[2]}")
    markers = {name: points[:, k, :].T.copy() for k, name in enumerate(labels)}
    force, force_rate, notes = None, None, []
    platforms = c3d["data"].get("platform", [])
    if platforms:
        f = np.asarray(platforms[0]["force"], float).T
        if f.size and np.nanmax(np.abs(f)) > FORCE_THRESHOLD:
            force = f
            force_rate = float(c3d["header"]["analogs"]["frame_rate"])
        else:
            notes.append("the force plate is empty: touchdowns from the kinematics")
    return fill_gaps(Trial(markers, rate, force, force_rate, str(path), notes=notes))


def _declared_frames(path) -> int | None:
    """Frames the C3D header declares (first and last frame, 16-bit words at bytes 6-9).

    ezc3d reads what a truncated file still holds and rewrites its parameters to match; the
    raw header keeps the original count. None where the header cannot say (over 65535 frames,
    or a big-endian file).
    """
    import struct

    with open(path, "rb") as fh:
        head = fh.read(10)
    if len(head) < 10 or head[1] != 0x50:
        return None
    first, last = struct.unpack("<HH", head[6:10])
    return last - first + 1 if 0 < first <= last < 65535 else None


def read_text(path, forces=None) -> Trial:
    """The RBDS text layout: a marker file (and a force file)."""
    path = Path(path)
    try:
        with path.open() as fh:
            header = fh.readline().rstrip("\n").split("\t")
        data = np.loadtxt(path, skiprows=1, delimiter="\t", ndmin=2)
    except (OSError, ValueError) as err:
        raise MocapError(f"{path}: not a marker text file in the RBDS layout ({err})") from None
    if header[0] != "Time" or (len(header) - 1) % 3 or data.shape[1] != len(header) or len(data) < 2:
        raise MocapError(f"{path}: expected 'Time' then NAMEX NAMEY NAMEZ columns and at least 2 rows")
    time = data[:, 0]
    # the column is rounded to the millisecond: the span over the whole trial gives the rate
    # to about 0.003 Hz, so it is rounded to 0.01 Hz
    rate = round((len(time) - 1) / float(time[-1] - time[0]), 2)
    markers = {header[k][:-1]: data[:, k:k + 3] * 1e-3 for k in range(1, len(header), 3)}
    trial = Trial(markers, round(rate, 6), source=str(path))
    if forces is not None:
        fpath = Path(forces)
        try:
            fdata = np.loadtxt(fpath, skiprows=1, delimiter="\t", ndmin=2)
        except (OSError, ValueError) as err:
            raise MocapError(f"{fpath}: not a force text file in the RBDS layout ({err})") from None
        if fdata.shape[1] < 4 or len(fdata) < 2:
            raise MocapError(f"{fpath}: expected frame, Fx, Fy, Fz columns")
        duration = len(time) / rate
        trial.force = fdata[:, 1:4]
        trial.force_rate = round(len(fdata) / duration, 2)
        if not np.any(np.abs(trial.force) > FORCE_THRESHOLD):  # an empty plate: kinematics instead
            trial.force, trial.force_rate = None, None
            trial.notes.append(f"{fpath.name}: the force plate is empty: touchdowns from the kinematics")
    return fill_gaps(trial)


def write_text(trial: Trial, markers_path, forces_path=None):
    """Write a trial in the RBDS text layout (mm; forces in N), each file renamed into place."""
    names = list(trial.markers)
    frames = len(trial.markers[names[0]])
    table = np.column_stack([np.arange(frames) / trial.rate] +
                            [trial.markers[n] * 1e3 for n in names])
    header = "\t".join(["Time"] + [f"{n}{a}" for n in names for a in "XYZ"])
    _save(markers_path, table, header)
    if forces_path is not None and trial.force is not None:
        rows = np.column_stack([np.arange(1, len(trial.force) + 1), trial.force])
        _save(forces_path, rows, "Time\tFx\tFy\tFz")


def _save(path, table, header):
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp")
    np.savetxt(tmp, table, delimiter="\t", header=header, comments="", fmt="%.10g")
    tmp.replace(path)


def fill_gaps(trial: Trial) -> Trial:
    """Mark missing samples (NaN or exact zeros), interpolate short gaps, record long ones."""
    for name, xyz in trial.markers.items():
        missing = np.any(~np.isfinite(xyz), axis=1) | np.all(xyz == 0.0, axis=1)
        if missing.all():
            raise MocapError(f"{trial.source}: marker {name} has no valid frame")
        if not missing.any():
            continue
        xyz[missing] = np.nan
        good = np.flatnonzero(~missing)
        for axis in range(3):
            xyz[missing, axis] = np.interp(np.flatnonzero(missing), good, xyz[good, axis])
        long = [(a, b) for a, b in _runs(missing) if b - a > MAX_GAP]
        if long:
            trial.gaps[name] = long
        filled = int(missing.sum()) - sum(b - a for a, b in long)
        if filled:
            trial.notes.append(f"{name}: {filled} missing frames interpolated")
        if long:
            trial.notes.append(f"{name}: {len(long)} gaps longer than {MAX_GAP} frames "
                               f"({', '.join(f'{a / trial.rate:.2f}-{b / trial.rate:.2f} s' for a, b in long)})")
    return trial


def _runs(mask):
    """(start, stop) of each run of True."""
    edges = np.diff(np.concatenate([[0], mask.astype(int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def require(trial: Trial, names, what: str):
    missing = [n for n in names if n not in trial.markers]
    if missing:
        raise MocapError(f"{trial.source}: {what} needs markers that are missing: {', '.join(missing)}")


# -- geometry ----------------------------------------------------------------------------

@dataclass(frozen=True)
class Axes:
    """Lab axes found from the data: forward, left, up (unit vectors in the file's frame)."""

    forward: np.ndarray
    left: np.ndarray
    up: np.ndarray

    def sagittal(self, p) -> np.ndarray:
        """(..., 3) lab points -> (..., 2) forward and up coordinates (m)."""
        return np.stack([p @ self.forward, p @ self.up], axis=-1)

    def describe(self) -> str:
        names = "XYZ"

        def name(v):
            k = int(np.argmax(np.abs(v)))
            return f"{'+' if v[k] > 0 else '-'}{names[k]} ({abs(v[k]):.3f})"
        return f"forward {name(self.forward)}, up {name(self.up)}, left {name(self.left)}"


def find_axes(static: Trial) -> Axes:
    """Up: normal of the floor plane through the foot markers; forward: heel to toes."""
    feet = [f"{s}.{m}" for s in SIDES for m in ("Heel.Bottom", "MT1", "MT5")]
    require(static, feet + list(PELVIS), "finding the lab axes")
    points = np.array([np.nanmean(static.markers[n], axis=0) for n in feet])
    centre = points.mean(axis=0)
    up = np.linalg.svd(points - centre)[2][-1]
    pelvis = np.mean([np.nanmean(static.markers[n], axis=0) for n in PELVIS], axis=0)
    if (pelvis - centre) @ up < 0:
        up = -up
    toes = [np.nanmean(static.markers[f"{s}.MT1"] + static.markers[f"{s}.MT5"], axis=0) / 2
            - np.nanmean(static.markers[f"{s}.Heel.Bottom"], axis=0) for s in SIDES]
    forward = np.mean(toes, axis=0)
    forward -= (forward @ up) * up
    forward /= np.linalg.norm(forward)
    return Axes(forward, np.cross(up, forward), up)


def kabsch(reference, current):
    """Rotations R and translations t with current ~ reference @ R.T + t (rows are markers).

    reference: (k, 3); current: (k, 3) or a stack (..., k, 3), one fit per frame.
    """
    a0, b0 = reference.mean(axis=0), current.mean(axis=-2)
    H = np.swapaxes(current - b0[..., None, :], -1, -2) @ (reference - a0)  # = ((ref)^T cur)^T
    u, _, vt = np.linalg.svd(np.swapaxes(H, -1, -2))
    v, ut = np.swapaxes(vt, -1, -2), np.swapaxes(u, -1, -2)
    d = np.sign(np.linalg.det(v @ ut))
    D = np.zeros(d.shape + (3, 3))
    D[..., 0, 0] = D[..., 1, 1] = 1.0
    D[..., 2, 2] = d
    R = v @ D @ ut
    return R, b0 - a0 @ np.swapaxes(R, -1, -2)


def harrington_hip(static: Trial, side: str) -> np.ndarray:
    """Hip joint centre (m, lab) from the pelvis markers: Harrington et al. (2007).

    Pelvis frame at the mid-ASIS: x anterior, y superior, z right; PW the ASIS distance,
    PD the mid-ASIS to mid-PSIS distance; HJC = (-0.24 PD - 9.9, -0.30 PW - 10.9,
    +-(0.33 PW + 7.3)) mm (+ right, - left).
    """
    m = {n: np.nanmean(static.markers[n], axis=0) * 1e3 for n in PELVIS}
    mid_asis = (m["R.ASIS"] + m["L.ASIS"]) / 2
    mid_psis = (m["R.PSIS"] + m["L.PSIS"]) / 2
    z = m["R.ASIS"] - m["L.ASIS"]
    pw = np.linalg.norm(z)
    z /= pw
    x = mid_asis - mid_psis
    pd = np.linalg.norm(x)
    x -= (x @ z) * z
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    sign = 1.0 if side == "R" else -1.0
    local = np.array([-0.24 * pd - 9.9, -0.30 * pw - 10.9, sign * (0.33 * pw + 7.3)])
    return (mid_asis + local[0] * x + local[1] * y + local[2] * z) * 1e-3


@dataclass(frozen=True)
class Calibration:
    """Anatomical points in the static trial and the clusters that carry them."""

    axes: Axes
    points: dict[str, tuple[tuple[str, ...], np.ndarray, np.ndarray]]  # name -> (cluster, cluster0, point0)
    foot_offset: dict[str, float]  # rad: the heel-to-toe marker line's angle when standing
    pelvis_offset: float  # rad: the pelvis line's tilt when standing


def calibrate(static: Trial) -> Calibration:
    """Joint centres and heel/forefoot points of both legs, expressed on their clusters."""
    axes = find_axes(static)
    mean = {n: np.nanmean(v, axis=0) for n, v in static.markers.items()}
    points, foot_offset = {}, {}
    for s in SIDES:
        names = {seg: tuple(f"{s}.{m}" for m in ms) for seg, ms in CLUSTER.items()}
        require(static, [f"{s}.{m}" for m in ANATOMICAL] + [n for ns in names.values() for n in ns],
                f"calibrating the {'right' if s == 'R' else 'left'} leg")
        hip = harrington_hip(static, s)
        knee = (mean[f"{s}.Knee"] + mean[f"{s}.Knee.Medial"]) / 2
        ankle = (mean[f"{s}.Ankle"] + mean[f"{s}.Ankle.Medial"]) / 2
        heel = mean[f"{s}.Heel.Bottom"]
        fore = (mean[f"{s}.MT1"] + mean[f"{s}.MT5"]) / 2

        def on(cluster, point):
            return (cluster, np.array([mean[n] for n in cluster]), point)
        points[f"{s}.hip"] = on(PELVIS, hip)
        points[f"{s}.knee"] = on(names["thigh"], knee)
        points[f"{s}.ankle"] = on(names["shank"], ankle)
        points[f"{s}.heel"] = on(names["foot"], heel)
        points[f"{s}.forefoot"] = on(names["foot"], fore)
        line = axes.sagittal(fore - heel)
        foot_offset[s] = math.atan2(line[1], line[0])
    return Calibration(axes, points, foot_offset, _pelvis_tilt(axes, mean))


def _pelvis_tilt(axes: Axes, m) -> float:
    """Angle of the mid-PSIS -> mid-ASIS line in the sagittal plane (rad)."""
    line = axes.sagittal((m["R.ASIS"] + m["L.ASIS"]) / 2 - (m["R.PSIS"] + m["L.PSIS"]) / 2)
    return math.atan2(-line[1], line[0])  # forward tilt (ASIS down) positive


def lowpass(x, rate: float, cutoff: float = CUTOFF_HZ):
    """4th-order zero-lag Butterworth along axis 0."""
    from scipy.signal import butter, filtfilt

    b, a = butter(2, cutoff / (rate / 2))  # second order, run forward and back: fourth order
    return filtfilt(b, a, x, axis=0)


# -- kinematics --------------------------------------------------------------------------

@dataclass
class Kinematics:
    """Sagittal kinematics of both legs at the marker rate (SI, formopt's conventions)."""

    t: np.ndarray
    points: dict[str, np.ndarray]  # "R.knee" -> (frames, 2) forward, up (m)
    angles: dict[str, np.ndarray]  # "R.thigh", "R.shank", "R.foot", "trunk" -> rad
    rate: float


def kinematics(trial: Trial, cal: Calibration) -> Kinematics:
    needed = sorted({n for cluster, _, _ in cal.points.values() for n in cluster})
    require(trial, needed, "the running trial")
    frames = len(next(iter(trial.markers.values())))
    filtered = {n: lowpass(trial.markers[n], trial.rate) for n in needed}
    points, fits = {}, {}
    for name, (cluster, ref, p0) in cal.points.items():
        if cluster not in fits:  # one fit per cluster and frame (the pelvis carries both hips)
            fits[cluster] = kabsch(ref, np.stack([filtered[n] for n in cluster], axis=1))
        R, t = fits[cluster]
        points[name] = cal.axes.sagittal(np.einsum("fij,j->fi", R, p0) + t)
    angles = {}
    for s in SIDES:
        p = {k: points[f"{s}.{k}"] for k in ("hip", "knee", "ankle", "heel", "forefoot")}
        angles[f"{s}.thigh"] = _from_down(p["knee"] - p["hip"])
        angles[f"{s}.shank"] = _from_down(p["ankle"] - p["knee"])
        line = p["forefoot"] - p["heel"]
        angles[f"{s}.foot"] = np.arctan2(line[:, 1], line[:, 0]) - cal.foot_offset[s]
    pelvis = {n: filtered[n] for n in PELVIS}
    angles["trunk"] = np.array([_pelvis_tilt(cal.axes, {n: pelvis[n][f] for n in PELVIS})
                                for f in range(frames)]) - cal.pelvis_offset
    return Kinematics(np.arange(frames) / trial.rate, points, angles, trial.rate)


def _from_down(v):
    """Angle of v from the downward vertical, positive when its end is ahead (rad)."""
    return np.arctan2(v[:, 0], -v[:, 1])


# -- touchdowns --------------------------------------------------------------------------

@dataclass(frozen=True)
class Touchdown:
    time: float  # s
    side: str  # "R" or "L"
    frame: int  # marker frame just before the contact
    strike: str  # "heel", "midfoot", "forefoot"
    foot_strike_angle: float  # rad, foot angle relative to standing
    angles: dict[str, float]  # rad: trunk, hip, knee, ankle (formopt's joint angles)
    rates: dict[str, float]  # rad/s: thigh, shank, foot (absolute)
    hip_velocity: tuple[float, float]  # m/s, ground frame (belt added)
    hip_height: float  # m above the lower foot point

    def state(self) -> np.ndarray:
        """formopt's touchdown state vector (model.STATE)."""
        a, w = self.angles, self.rates
        return np.array([a["trunk"], a["hip"], a["knee"], a["ankle"], *self.hip_velocity, 0.0,
                         w["thigh"], w["shank"], w["foot"]])


@dataclass
class Steps:
    touchdowns: list[Touchdown]
    cadence_spm: float
    belt_speed: float  # m/s
    method: str  # "force plate" or "kinematics"
    left_out: list[str]  # steps not used, and why
    notes: list[str] = field(default_factory=list)  # from the reader


def touchdowns(trial: Trial, kin: Kinematics, cal: Calibration) -> Steps:
    """Touchdowns of both feet, their side, strike pattern and touchdown state."""
    foot_low = {s: np.minimum(kin.points[f"{s}.heel"][:, 1], kin.points[f"{s}.forefoot"][:, 1])
                for s in SIDES}
    floor = min(np.percentile(foot_low[s], 2) for s in SIDES)
    if trial.force is not None:
        vertical = lowpass(trial.force, trial.force_rate, 50.0) @ cal.axes.up
        on = np.flatnonzero((vertical[1:] >= FORCE_THRESHOLD) & (vertical[:-1] < FORCE_THRESHOLD)) + 1
        times = _separated(on / trial.force_rate, 0.15)
        method = "force plate"
    else:
        level = floor + KINEMATIC_LEVEL
        both = np.minimum(foot_low["R"], foot_low["L"])
        on = np.flatnonzero((both[1:] <= level) & (both[:-1] > level)) + 1
        times = _separated(on / kin.rate, 0.15)
        method = "kinematics"
    belt = _belt_speed(kin, foot_low, floor)
    steps, left_out = [], []
    for t in times:
        frame = int(math.floor(t * kin.rate)) - 1
        if frame < 2 or frame >= len(kin.t) - 2:
            continue
        side = min(SIDES, key=lambda s: foot_low[s][frame])
        touched = [n for n, g in trial.gaps.items()
                   if (n.startswith(side + ".") or n in PELVIS)
                   and any(a - MAX_GAP <= frame <= b + MAX_GAP for a, b in g)]
        if touched:
            left_out.append(f"{t:.3f} s ({side}): gap in {', '.join(touched)}")
            continue
        steps.append(_touchdown(kin, cal, side, frame, t, belt, foot_low[side][frame]))
    if len(times) < 2:
        raise MocapError(f"{trial.source}: fewer than two touchdowns found ({method})")
    cadence = 60.0 / float(np.median(np.diff(times)))
    return Steps(steps, cadence, belt, method, left_out, list(trial.notes))


def _separated(times, gap):
    out = []
    for t in times:
        if not out or t - out[-1] > gap:
            out.append(float(t))
    return np.array(out)


def _belt_speed(kin: Kinematics, foot_low, floor) -> float:
    """The treadmill belt's speed: the stance foot's backward speed (m/s, 0 overground)."""
    speeds = []
    for s in SIDES:
        heel = kin.points[f"{s}.heel"][:, 0]
        vx = np.gradient(heel, 1.0 / kin.rate)
        stance = foot_low[s] < floor + 0.01
        if stance.sum() > 10:
            speeds.append(-np.median(vx[stance]))
    return float(np.median(speeds)) if speeds else 0.0


def _touchdown(kin, cal, side, frame, time, belt, low) -> Touchdown:
    dt = 1.0 / kin.rate

    def rate(key):
        return float((kin.angles[key][frame + 1] - kin.angles[key][frame - 1]) / (2 * dt))

    a = {k: float(kin.angles[f"{side}.{k}"][frame]) for k in ("thigh", "shank", "foot")}
    trunk = float(kin.angles["trunk"][frame])
    hip_p = kin.points[f"{side}.hip"]
    v = (hip_p[frame + 1] - hip_p[frame - 1]) / (2 * dt)
    fsa = a["foot"]
    strike = "heel" if math.degrees(fsa) > REARFOOT_DEG else \
        "forefoot" if math.degrees(fsa) < FOREFOOT_DEG else "midfoot"
    return Touchdown(time=time, side=side, frame=frame, strike=strike, foot_strike_angle=fsa,
                     angles={"trunk": trunk, "hip": a["thigh"] + trunk, "knee": a["thigh"] - a["shank"],
                             "ankle": a["foot"] - a["shank"]},
                     rates={k: rate(f"{side}.{k}") for k in ("thigh", "shank", "foot")},
                     hip_velocity=(float(v[0] + belt), float(v[1])),
                     hip_height=float(hip_p[frame][1] - low))
