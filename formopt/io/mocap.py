"""Measured postures: motion capture import, checks, lab axes, joint centres, touchdowns.

Readers: C3D through ezc3d (markers, force plates with their calibration, units and rates from
the file) and the RBDS text layout (markers: Time (s) then NAMEX NAMEY NAMEZ; forces: frame,
Fx Fy Fz (N), ... at the rate that spans the marker file's duration). An empty cell, a NaN or
an exact (0, 0, 0) is a missing sample; a column with no value at all is a marker the lab
removed (dropped, with a note).

The method (a calibrated anatomical system, CAST), for any marker map (markerset.py):
- Units: as the file declares them, checked against the stature (the standing markers span
  0.35 to 1.1 statures); when the file does not say, inferred from that span, with a note.
- Lab axes from physics, never from the lab's names: up is the force plate's mean force
  (body weight) when there is one; else the standing body (pelvis above feet), pitched so
  that the stance foot moves level (a level belt or floor). Forward: the pelvis moves
  forward relative to the stance foot (treadmill or overground). Left: from the L and R
  markers; a left-handed file frame (a mirrored lab) is said and does no harm.
- Labels: each running cluster is fitted to its standing shape; a permutation that fits
  three times better (MT1 and MT5 swapped, say) or the other side's cluster is swapped back
  with a note.
- Joint centres in the standing trial: hip by Harrington et al. (2007, J Biomech 40:595-602)
  from the pelvis markers, or at a landmark (the greater trochanter's sagittal projection);
  knee and ankle at the midpoints of their landmarks; heel and forefoot at their markers or
  from the foot's geometry. Each is carried into the run by a least-squares rigid fit (Kabsch)
  of its segment's cluster, frame by frame; the fit's residual says whether the cluster stayed
  rigid.
- Markers: spikes (a sample 25 mm off the 5-sample median) and frozen stretches (5 identical
  samples) are missing samples; gaps up to 10 frames are interpolated. Then a 4th-order
  zero-lag Butterworth low-pass (default 10 Hz: Winter 2009).
- Touchdowns from the vertical force (default 50 N, rising) where there is a force plate: a
  single treadmill plate sees both feet, the side is the foot that is lower then; from the
  foot's height otherwise (its lowest point within 1 cm of its stance level). The cadence they
  give is checked against the feet's own rhythm (and the force's): a force file that does not
  span the marker file is refused. Strike pattern from the foot strike angle (foot angle at
  touchdown relative to standing; Altman & Davis 2012, Gait Posture 35:298-300): rearfoot
  > 8 deg, forefoot < -1.6 deg, midfoot between.
- A touchdown whose markers around it (+-30 ms) were missing, spiked, frozen, or whose
  clusters were not rigid (residual > 12 mm) is listed with valid_data False and left out of
  the means.
- No trunk markers in the shipped maps: the trunk angle is the pelvis's tilt relative to
  standing.
"""

from __future__ import annotations

import copy
import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..mechanics.errors import InputError
from . import markerset as msets

SIDES = ("R", "L")
MAX_GAP = 10  # frames interpolated; longer gaps leave their steps out
SPIKE = 0.025  # m off the 5-sample median
FROZEN = 5  # identical samples in a row
RIGID = 0.012  # m: a cluster's rms residual beyond this is not a rigid body at that frame
STEP_WINDOW = 0.03  # s each side of a touchdown whose markers must be sound
SPEED_RANGE = (0.5, 12.0)  # m/s: running
CADENCE_TOLERANCE = 0.1  # relative: touchdowns against the feet's rhythm
STATIC_DRIFT = 0.05  # m: the pelvis of a standing trial moves less
SPAN_PER_HEIGHT = (0.35, 1.1)  # the standing markers' span, statures
REARFOOT_DEG, FOREFOOT_DEG = 8.0, -1.6  # Altman & Davis (2012) foot strike angle thresholds
UNITS = {"mm": 1e-3, "millimeters": 1e-3, "millimetres": 1e-3, "cm": 1e-2, "dm": 0.1,
         "m": 1.0, "meters": 1.0, "metres": 1.0}


class MocapError(InputError):
    """A motion-capture file formopt cannot use, and why."""


@dataclass(frozen=True)
class Options:
    """What compare lets a user set about the measurement."""

    markers: str | None = None  # marker map: shipped name or TOML file; None: recognised
    cutoff_hz: float = 10.0  # low-pass of the markers (Winter 2009)
    force_threshold_n: float = 50.0  # vertical force at touchdown
    foot_speed_fraction: float = 0.5  # without a plate: touchdown when the foot's speed over
    #                                   the ground falls below this fraction of the running speed


@dataclass
class Trial:
    """Markers (m once the units are known; lab axes as recorded) and, if any, the ground
    reaction force (N)."""

    markers: dict[str, np.ndarray]  # name -> (frames, 3)
    rate: float  # Hz
    force: np.ndarray | None = None  # (samples, 3)
    force_rate: float | None = None
    source: str = ""
    units: str = "m"  # as the file declares them; "" when it does not (markers still in its unit)
    gaps: dict[str, list[tuple[int, int]]] = field(default_factory=dict)  # long gaps (start, stop)
    suspect: dict[str, np.ndarray] = field(default_factory=dict)  # name -> samples not measured
    notes: list[str] = field(default_factory=list)  # what the reader did that a user should know

    @property
    def frames(self) -> int:
        return len(next(iter(self.markers.values())))


# -- readers ------------------------------------------------------------------------------

def read(path, forces=None) -> Trial:
    """A trial from a C3D file or an RBDS marker text file (with an optional force file);
    cleaned (clean()) when its units are known."""
    path = Path(path)
    if not path.exists():
        raise MocapError(f"{path}: no such file")
    trial = read_c3d(path) if path.suffix.lower() == ".c3d" else read_text(path, forces)
    return clean(trial) if trial.units else trial


def read_c3d(path) -> Trial:
    import ezc3d

    try:
        c3d = ezc3d.c3d(str(path), extract_forceplat_data=True)
    except (RuntimeError, ValueError, OSError) as err:
        raise MocapError(f"{path}: not a readable C3D file ({err})") from None
    point = c3d["parameters"]["POINT"]
    labels = point["LABELS"]["value"]
    rate = float(point["RATE"]["value"][0])
    unit = (point.get("UNITS", {}).get("value") or [""])[0].strip().lower()
    if unit and unit not in UNITS:
        raise MocapError(f"{path}: marker units {unit!r} not understood ({', '.join(UNITS)})")
    points = c3d["data"]["points"][:3] * (UNITS[unit] if unit else 1.0)
    if points.shape[2] < 1 or not rate > 0:
        raise MocapError(f"{path}: no marker frames (truncated or empty)")
    declared = _declared_frames(path)
    if declared is not None and points.shape[2] < declared:
        raise MocapError(f"{path}: truncated: the file declares {declared} frames but holds "
                         f"{points.shape[2]}")
    markers = {name: points[:, k, :].T.copy() for k, name in enumerate(labels)}
    trial = Trial(markers, rate, source=str(path), units=unit)
    platforms = c3d["data"].get("platform", [])
    if platforms:
        _set_force(trial, np.asarray(platforms[0]["force"], float).T,
                   float(c3d["header"]["analogs"]["frame_rate"]), Path(path).name)
    return _drop_empty(trial)


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


def _table(path, what: str) -> tuple[list[str], np.ndarray]:
    """Header and values of a tab-separated file; empty cells are NaN."""
    try:
        with path.open() as fh:
            header = fh.readline().rstrip("\r\n").split("\t")
        data = np.genfromtxt(path, skip_header=1, delimiter="\t", ndmin=2, invalid_raise=True)
    except (OSError, ValueError, UnicodeDecodeError) as err:
        raise MocapError(f"{path}: not a {what} text file in the RBDS layout ({one_reason(err)})") from None
    return header, data


def one_reason(err) -> str:
    return str(err).strip().splitlines()[-1][:100] if str(err).strip() else type(err).__name__


def read_text(path, forces=None) -> Trial:
    """The RBDS text layout: a marker file (mm) and, optionally, a force file."""
    path = Path(path)
    header, data = _table(path, "marker")
    if header[0] != "Time" or (len(header) - 1) % 3 or data.shape[1] != len(header) or len(data) < 2:
        raise MocapError(f"{path}: expected 'Time' then NAMEX NAMEY NAMEZ columns and at least 2 rows")
    time = data[:, 0]
    step = np.diff(time)
    if not np.all(np.isfinite(time)) or np.any(step <= 0):
        bad = int(np.flatnonzero(~(step > 0))[0]) + 2 if np.any(~(step > 0)) else 1
        raise MocapError(f"{path}: the Time column does not increase (row {bad})")
    # the column is rounded to the millisecond: the span over the whole trial gives the rate
    # to about 0.003 Hz, so it is rounded to 0.01 Hz
    rate = round((len(time) - 1) / float(time[-1] - time[0]), 2)
    markers = {header[k][:-1]: data[:, k:k + 3] * 1e-3 for k in range(1, len(header), 3)}
    trial = Trial(markers, rate, source=str(path), units="mm")
    if forces is not None:
        fpath = Path(forces)
        _, fdata = _table(fpath, "force")
        if fdata.shape[1] < 4 or len(fdata) < 2:
            raise MocapError(f"{fpath}: expected frame, Fx, Fy, Fz columns")
        _set_force(trial, fdata[:, 1:4], round(len(fdata) / (len(time) / rate), 2), fpath.name)
    return _drop_empty(trial)


def _set_force(trial: Trial, force, rate: float, name: str):
    """The plate's force, unless it is empty (then touchdowns come from the kinematics)."""
    if force.size and np.nanmax(np.abs(force)) > 50.0:
        if not np.all(np.isfinite(force)):
            good = np.all(np.isfinite(force), axis=1)
            for axis in range(3):
                force[~good, axis] = np.interp(np.flatnonzero(~good), np.flatnonzero(good), force[good, axis])
            trial.notes.append(f"{name}: {int((~good).sum())} missing force samples interpolated")
        trial.force, trial.force_rate = force, rate
    else:
        trial.notes.append(f"{name}: the force plate is empty: touchdowns from the kinematics")


def _drop_empty(trial: Trial) -> Trial:
    """Markers with no sample at all (removed after the standing trial) are dropped."""
    empty = [n for n, xyz in trial.markers.items()
             if not np.any(np.all(np.isfinite(xyz), axis=1) & ~np.all(xyz == 0.0, axis=1))]
    for n in empty:
        del trial.markers[n]
    if empty:
        trial.notes.append(f"no data for {', '.join(empty)}: left out")
    if not trial.markers:
        raise MocapError(f"{trial.source}: no marker holds any data")
    return trial


def write_text(trial: Trial, markers_path, forces_path=None):
    """Write a trial in the RBDS text layout (mm; forces in N), each file renamed into place."""
    names = list(trial.markers)
    table = np.column_stack([np.arange(trial.frames) / trial.rate] +
                            [trial.markers[n] * 1e3 for n in names])
    header = "\t".join(["Time"] + [f"{n}{a}" for n in names for a in "XYZ"])
    _save(markers_path, table, header)
    if forces_path is not None and trial.force is not None:
        rows = np.column_stack([np.arange(1, len(trial.force) + 1), trial.force])
        _save(forces_path, rows, "Time\tFx\tFy\tFz")


def _save(path, table, header):
    from .files import atomic

    with atomic(path) as fh:
        np.savetxt(fh, table, delimiter="\t", header=header, comments="", fmt="%.10g")


# -- cleaning -----------------------------------------------------------------------------

def clean(trial: Trial) -> Trial:
    """Missing samples (NaN, exact zeros), spikes and frozen stretches are marked in
    `suspect`; gaps up to MAX_GAP frames are interpolated, longer ones recorded in `gaps`."""
    from scipy.ndimage import median_filter

    spikes, frozen = 0, []
    for name, xyz in trial.markers.items():
        missing = np.any(~np.isfinite(xyz), axis=1) | np.all(xyz == 0.0, axis=1)
        if missing.all():
            raise MocapError(f"{trial.source}: marker {name} has no valid frame")
        still = np.concatenate([[False], np.all(np.diff(xyz, axis=0) == 0.0, axis=1)])
        stuck = np.zeros_like(missing)
        for a, b in _runs(still):
            if b - a >= FROZEN - 1:
                stuck[a - 1:b] = True
        if stuck.any():
            frozen.append(name)
        missing |= stuck
        if len(xyz) >= 5:
            filled = _interpolated(xyz, missing)
            off = np.linalg.norm(filled - median_filter(filled, size=(5, 1), mode="nearest"), axis=1)
            spiked = (off > SPIKE) & ~missing
            spikes += int(spiked.sum())
            missing |= spiked
        if not missing.any():
            continue
        trial.suspect[name] = missing
        trial.markers[name] = _interpolated(xyz, missing)
        long = [(a, b) for a, b in _runs(missing) if b - a > MAX_GAP]
        if long:
            trial.gaps[name] = long
            trial.notes.append(f"{name}: {len(long)} gaps longer than {MAX_GAP} frames "
                               f"({', '.join(f'{a / trial.rate:.2f}-{b / trial.rate:.2f} s' for a, b in long)})")
    if spikes:
        trial.notes.append(f"{spikes} spike samples (over {SPIKE * 1e3:g} mm off their neighbours) "
                           f"treated as missing")
    if frozen:
        trial.notes.append(f"frozen stretches (the same position {FROZEN}+ frames running) "
                           f"treated as missing in {', '.join(frozen)}")
    gaps = sum(int(m.sum()) for m in trial.suspect.values())
    if gaps:
        trial.notes.append(f"{gaps} missing marker samples in {len(trial.suspect)} markers, "
                           f"gaps up to {MAX_GAP} frames interpolated")
    return trial


def _interpolated(xyz, missing):
    out = np.array(xyz, float)
    good = np.flatnonzero(~missing)
    for axis in range(3):
        out[missing, axis] = np.interp(np.flatnonzero(missing), good, out[good, axis])
    return out


def _runs(mask):
    """(start, stop) of each run of True."""
    edges = np.diff(np.concatenate([[0], np.asarray(mask, int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def require(trial: Trial, names, what: str):
    missing = [n for n in names if n not in trial.markers]
    if missing:
        raise MocapError(f"{trial.source}: {what} needs markers that are missing: {', '.join(missing)}")


def _mean(trial: Trial) -> dict[str, np.ndarray]:
    return {n: np.nanmean(v, axis=0) for n, v in trial.markers.items()}


# -- checks before any geometry -----------------------------------------------------------

def resolve_units(static: Trial, trial: Trial, height: float, ms) -> None:
    """Check the declared units against the stature (or infer them), then the run's against
    the standing trial's cluster sizes; both trials are cleaned once their units are known."""
    span = _span(static)
    lo, hi = (f * height for f in SPAN_PER_HEIGHT)
    if static.units:
        if not lo <= span <= hi:
            raise MocapError(f"{static.source}: the standing markers span {span:.3g} m, not a "
                             f"{height:g} m runner's {lo:.2f}-{hi:.2f} m: are the units "
                             f"({static.units}) right?")
    else:
        scale = next((s for s in (1e-3, 1e-2, 1.0) if lo <= span * s <= hi), None)
        if scale is None:
            raise MocapError(f"{static.source}: the file gives no units and its markers span "
                             f"{span:.3g} units: no unit makes that a {height:g} m runner")
        _scale(static, scale)
        static.notes.append(f"{Path(static.source).name}: no units in the file: "
                            f"{_unit_name(scale)}, from the standing body's size "
                            f"({span * scale:.2f} m for a {height:g} m runner)")
        clean(static)
    ratio = _cluster_size(trial, ms) / _cluster_size(static, ms)
    if trial.units:
        if not 0.8 < ratio < 1.25:
            raise MocapError(f"{trial.source}: its clusters are {ratio:.3g} times the standing "
                             f"trial's: are the units ({trial.units}) right?")
    else:
        scale = 10.0 ** -round(math.log10(ratio))
        if not 0.8 < ratio * scale < 1.25:
            raise MocapError(f"{trial.source}: the file gives no units and its clusters are "
                             f"{ratio:.3g} times the standing trial's")
        _scale(trial, scale)
        trial.notes.append(f"{Path(trial.source).name}: no units in the file: "
                           f"{_unit_name(scale)}, from the standing trial's cluster sizes")
        clean(trial)


def _unit_name(scale) -> str:
    return {1e-3: "millimetres", 1e-2: "centimetres", 1.0: "metres"}.get(scale, f"{scale:g} m")


def _scale(trial: Trial, scale: float):
    for name in trial.markers:
        trial.markers[name] = trial.markers[name] * scale
    trial.units = _unit_name(scale)


def _span(static: Trial) -> float:
    points = np.array([p for p in _mean(static).values() if np.all(np.isfinite(p))])
    return float(np.max(np.linalg.norm(points[:, None] - points[None], axis=-1)))


def _cluster_size(trial: Trial, ms) -> float:
    """The median distance between the markers of each cluster of the map, in the trial's
    median frame (m, or the file's unit)."""
    clusters = [ms.pelvis] + [[n for n in ms.cluster(side, seg) if not n.startswith("@")]
                              for side in SIDES for seg in msets.SEGMENTS]
    mid = {n: np.nanmedian(trial.markers[n], axis=0) for c in clusters for n in c if n in trial.markers}
    d = [np.linalg.norm(mid[a] - mid[b]) for c in clusters for a, b in itertools.combinations(c, 2)
         if a in mid and b in mid]
    d = [x for x in d if np.isfinite(x) and x > 0]
    if not d:
        raise MocapError(f"{trial.source}: no marker cluster of the {ms.name} map to measure")
    return float(np.median(d))


def check_static(static: Trial, ms) -> None:
    """A standing trial holds still: its pelvis drifts less than STATIC_DRIFT."""
    require(static, ms.pelvis, f"the standing trial ({ms.name} markers)")
    if static.frames > 1:
        centre = np.mean([static.markers[n] for n in ms.pelvis], axis=0)
        drift = float(np.max(np.linalg.norm(centre - np.nanmedian(centre, axis=0), axis=1)))
        if drift > STATIC_DRIFT:
            raise MocapError(f"{static.source}: not a standing trial: the pelvis moves "
                             f"{drift:.2f} m (a standing trial holds within {STATIC_DRIFT:g} m)")
    require(static, ms.standing(), f"the standing trial ({ms.name} markers)")


# -- labels -------------------------------------------------------------------------------

LABEL_TOLERANCE = 0.010  # m rms: a cluster fitting worse than this has its labels questioned


def _fit_residual(reference, current) -> float:
    """Median over frames of the rms residual of the rigid fit of `reference` (k, 3) to
    `current` (frames, k, 3)."""
    R, t = kabsch(reference, current)
    fitted = np.einsum("fij,kj->fki", R, reference) + t[:, None, :]
    return float(np.median(np.sqrt(np.mean(np.sum((fitted - current) ** 2, axis=-1), axis=-1))))


def check_labels(static: Trial, trial: Trial, ms) -> None:
    """Swap back labels whose order within a cluster, or whose side, differs from the
    standing trial's; each swap is noted."""
    ref = _mean(static)
    sample = np.linspace(0, trial.frames - 1, min(trial.frames, 60)).astype(int)

    def stack(names):
        return np.stack([trial.markers[n][sample] for n in names], axis=1)

    def residual(static_names, run_names):
        return _fit_residual(np.array([ref[n] for n in static_names]), stack(run_names))

    clusters = {"pelvis": {None: list(ms.pelvis)}}
    for seg in msets.SEGMENTS:
        clusters[seg] = {s: [n for n in ms.cluster(s, seg) if not n.startswith("@")] for s in SIDES}
    # sides: each leg cluster lies on its own side of the pelvis (in the standing pelvis's
    # frame); mirror-image clusters fit either side's shape, so their place decides
    R, t = kabsch(np.array([ref[n] for n in ms.pelvis]), stack(ms.pelvis))
    centre = np.mean([ref[n] for n in ms.pelvis], axis=0)
    left = _unit(_left_of_labels(ref, ms))
    for seg in msets.SEGMENTS:
        names = clusters[seg]
        lateral = {s: np.median((np.einsum("fji,fj->fi", R, stack(names[s]).mean(axis=1) - t) - centre) @ left)
                   for s in SIDES}
        if lateral["R"] > 0 > lateral["L"]:
            _relabel(trial, dict(zip(names["R"] + names["L"], names["L"] + names["R"])))
            trial.notes.append(f"the {seg} markers' sides are swapped in the run relative to "
                               f"the standing trial: swapped back")
    for seg, by_side in clusters.items():
        for names in by_side.values():
            if len(names) < 3 or len(names) > 6:
                continue
            base = residual(names, names)
            if base <= LABEL_TOLERANCE:
                continue
            best = min(itertools.permutations(names), key=lambda p: residual(names, list(p)))
            if residual(names, list(best)) < base / 3:
                moved = {a: b for a, b in zip(names, best) if a != b}
                _relabel(trial, {b: a for a, b in moved.items()})
                trial.notes.append(f"{' and '.join(sorted(moved))} are swapped in the run "
                                   f"relative to the standing trial: swapped back")


def _left_of_labels(ref: dict, ms) -> np.ndarray:
    """The mean standing offset from each R leg marker to its L namesake (points left)."""
    return np.mean([ref[ms.label("L", n)] - ref[ms.label("R", n)]
                    for seg in msets.SEGMENTS for n in ms.leg[seg] if not n.startswith("@")], axis=0)


def _relabel(trial: Trial, mapping: dict):
    """Rename markers: run label -> standing label (all at once)."""
    trial.markers.update({new: trial.markers[old].copy() for old, new in mapping.items()})
    for d in (trial.suspect, trial.gaps):
        moved = {new: d[old] for old, new in mapping.items() if old in d}
        for old in mapping:
            d.pop(old, None)
        d.update(moved)


# -- geometry ----------------------------------------------------------------------------

@dataclass(frozen=True)
class Axes:
    """Lab axes found from the data: forward, left, up (unit vectors in the file's frame)."""

    forward: np.ndarray
    left: np.ndarray
    up: np.ndarray
    vertical: str = ""  # how up was found
    mirrored: bool = False  # the file's frame is left-handed

    def sagittal(self, p) -> np.ndarray:
        """(..., 3) lab points -> (..., 2) forward and up coordinates (m)."""
        return np.stack([p @ self.forward, p @ self.up], axis=-1)

    def describe(self) -> str:
        names = "XYZ"

        def name(v):
            k = int(np.argmax(np.abs(v)))
            return f"{'+' if v[k] > 0 else '-'}{names[k]} ({abs(v[k]):.3f})"
        return (f"forward {name(self.forward)}, up {name(self.up)}, left {name(self.left)}; "
                f"up from {self.vertical}" + ("; the file's frame is left-handed (mirrored)"
                                              if self.mirrored else ""))


def _unit(v):
    return v / np.linalg.norm(v)


def find_axes(static: Trial, trial: Trial, ms) -> tuple[Axes, list[str]]:
    """Up, forward and left from physics (module docstring), with notes on what was checked."""
    ref = _mean(static)
    feet = [n for s in SIDES for n in ms.cluster(s, "foot") if not n.startswith("@")]
    body = _unit(np.mean([ref[n] for n in ms.pelvis], axis=0) - np.mean([ref[n] for n in feet], axis=0))
    notes = []
    stance = _stance_motion(trial, ms, body)
    if trial.force is not None:
        mean = np.nanmean(trial.force, axis=0)
        up = _unit(mean) * (1 if mean @ body > 0 else -1)
        vertical = "the force plate's mean force"
    elif stance is not None:  # the stance foot moves level: pitch the body's up to be normal to it
        d = _unit(stance)
        up = _unit(body - (body @ d) * d)
        vertical = "the standing body, pitched to the stance foot's level motion"
    else:
        up, vertical = body, "the standing body (pelvis above feet)"
    tilt = math.degrees(math.acos(min(1.0, abs(float(up @ body)))))
    notes.append(f"vertical: {vertical}; {tilt:.1f} deg from the standing body's")
    if tilt > 15:
        raise MocapError(f"{trial.source}: the vertical ({vertical}) is {tilt:.0f} deg from the "
                         f"standing body's: the standing trial is not upright or the files "
                         f"do not belong together")
    if stance is None:
        raise MocapError(f"{trial.source}: no stance found: the feet never rest on the ground "
                         f"(is the rate, {trial.rate:g} Hz, right?)")
    pelvis = np.mean([trial.markers[n] for n in ms.pelvis], axis=0)
    travel = np.nanmedian(np.gradient(pelvis, 1.0 / trial.rate, axis=0), axis=0) - stance
    travel -= (travel @ up) * up
    forward = _unit(travel)
    left_labels = _left_of_labels(ref, ms)
    left = np.cross(up, forward)
    mirrored = bool(left_labels @ left < 0)
    if mirrored:
        notes.append("the file's axes are left-handed (a mirrored lab frame, or left and right "
                     "labels swapped throughout): formopt uses its own axes; sagittal angles "
                     "are unaffected, sides are as labelled")
    return Axes(forward, left if not mirrored else -left, up, vertical, mirrored), notes


def _stance_motion(trial: Trial, ms, up) -> np.ndarray | None:
    """The stance foot's median velocity (m/s, lab) over the frames each foot rests lowest."""
    velocities = []
    for s in SIDES:
        names = [n for n in ms.cluster(s, "foot") if not n.startswith("@")]
        M = np.stack([trial.markers[n] for n in names], axis=1)
        low = (M @ up).min(axis=1)
        rest = low < np.percentile(low, 5) + 0.005
        if rest.sum() >= 5:
            velocities.append(np.median(np.gradient(M, 1.0 / trial.rate, axis=0)[rest].reshape(-1, 3), axis=0))
    return np.mean(velocities, axis=0) if velocities else None


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


def harrington_hip(ref: dict, ms, side: str, up) -> np.ndarray:
    """Hip joint centre (m, lab) from the pelvis markers: Harrington et al. (2007).

    Pelvis frame at the mid-ASIS: x anterior, y superior, z right; PW the ASIS distance,
    PD the mid-ASIS to mid-PSIS distance; HJC = (-0.24 PD - 9.9, -0.30 PW - 10.9,
    +-(0.33 PW + 7.3)) mm (+ right, - left). y is taken upward along the lab's up, so a
    mirrored file frame does not flip it.
    """
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


# Segment lengths over stature (Winter 2009, fig. 4.1: thigh 0.245, leg 0.246), accepted
# between half and one and a half times these
LENGTH_PER_HEIGHT = {"thigh": 0.245, "shank": 0.246}


def calibrate(static: Trial, trial: Trial, ms, height: float) -> Calibration:
    """Joint centres and heel/forefoot points of both legs, expressed on their clusters."""
    axes, notes = find_axes(static, trial, ms)
    ref = _mean(static)
    points, foot_offset, lengths = {}, {}, {}
    for s in SIDES:
        centre = {}
        if ms.hip == "harrington":
            centre["hip"] = harrington_hip(ref, ms, s, axes.up)
        else:
            centre["hip"] = np.mean([ref[n] for n in ms.landmarks(s, "hip")], axis=0)
        for key in ("knee", "ankle"):
            centre[key] = np.mean([ref[n] for n in ms.landmarks(s, key)], axis=0)
        if "heel" in ms.leg:
            heel = np.mean([ref[n] for n in ms.landmarks(s, "heel")], axis=0)
            fore = np.mean([ref[n] for n in ms.landmarks(s, "forefoot")], axis=0)
        else:
            heel, fore = _foot_geometry(ref, ms, s, centre["ankle"], axes, height)
        centre["heel"], centre["forefoot"] = heel, fore

        def on(segment_names):  # "@knee" is the carried point "R.knee", standing at centre["knee"]
            cluster = tuple(f"{s}.{n[1:]}" if n.startswith("@") else n for n in segment_names)
            return cluster, np.array([centre[n[1:]] if n.startswith("@") else ref[n]
                                      for n in segment_names])
        points[f"{s}.hip"] = (*on(ms.pelvis), centre["hip"])
        points[f"{s}.knee"] = (*on(ms.cluster(s, "thigh")), centre["knee"])
        points[f"{s}.ankle"] = (*on(ms.cluster(s, "shank")), centre["ankle"])
        points[f"{s}.heel"] = (*on(ms.cluster(s, "foot")), heel)
        points[f"{s}.forefoot"] = (*on(ms.cluster(s, "foot")), fore)
        line = axes.sagittal(fore - heel)
        foot_offset[s] = math.atan2(line[1], line[0])
        lengths[f"{s}.thigh"] = float(np.linalg.norm(centre["hip"] - centre["knee"]))
        lengths[f"{s}.shank"] = float(np.linalg.norm(centre["knee"] - centre["ankle"]))
        lengths[f"{s}.foot"] = float(np.linalg.norm(fore - heel))
        for seg, per in LENGTH_PER_HEIGHT.items():
            length = lengths[f"{s}.{seg}"]
            if not 0.5 * per * height < length < 1.5 * per * height:
                raise MocapError(f"{static.source}: the {'right' if s == 'R' else 'left'} {seg} is "
                                 f"{length:.3g} m long, not a {height:g} m runner's (about "
                                 f"{per * height:.2f} m): wrong units, landmarks or stature")
    return Calibration(ms, axes, points, foot_offset, lengths, notes)


def _foot_geometry(ref, ms, side, ankle, axes: Axes, height):
    """Heel and forefoot points from the ankle centre and the foot length (FOOT_GEOMETRY)."""
    g = msets.FOOT_GEOMETRY
    length = g["foot_length_per_height"] * height
    markers = [ref[n] for n in ms.cluster(side, "foot") if not n.startswith("@")]
    floor = min(m @ axes.up for m in markers)
    heel = ankle - g["heel_behind_ankle"] * length * axes.forward
    heel = heel + (floor - heel @ axes.up) * axes.up
    return heel, heel + g["forefoot_from_heel"] * length * axes.forward


def lowpass(x, rate: float, cutoff: float, source: str = ""):
    """4th-order zero-lag Butterworth along axis 0."""
    from scipy.signal import butter, filtfilt

    if not 0 < cutoff < rate / 2:
        raise MocapError(f"{source}: the filter cutoff {cutoff:g} Hz must lie between 0 and half "
                         f"the sampling rate ({rate / 2:g} Hz)")
    b, a = butter(2, cutoff / (rate / 2))  # second order, run forward and back: fourth order
    if len(x) <= 3 * max(len(a), len(b)):
        raise MocapError(f"{source}: {len(x)} samples are too few to filter")
    return filtfilt(b, a, x, axis=0)


# -- kinematics --------------------------------------------------------------------------

@dataclass
class Kinematics:
    """Sagittal kinematics of both legs at the marker rate (SI, formopt's conventions)."""

    t: np.ndarray
    points: dict[str, np.ndarray]  # "R.knee" -> (frames, 2) forward, up (m)
    angles: dict[str, np.ndarray]  # "R.thigh", "R.shank", "R.foot", "trunk" -> rad
    rate: float
    residual: dict[tuple[str, ...], np.ndarray]  # cluster -> rms fit residual per frame (m)
    markers: dict[str, np.ndarray]  # filtered markers (frames, 3), lab frame (for exports)


def kinematics(trial: Trial, cal: Calibration, cutoff_hz: float = Options.cutoff_hz) -> Kinematics:
    needed = sorted({n for cluster, _, _ in cal.points.values() for n in cluster
                     if n not in cal.points})
    require(trial, needed, "the running trial")
    if trial.frames < 10:
        raise MocapError(f"{trial.source}: {trial.frames} frames: too short for a run")
    filtered = {n: lowpass(trial.markers[n], trial.rate, cutoff_hz, trial.source) for n in needed}
    carried, fits, residual = {}, {}, {}
    for name, (cluster, ref, p0) in cal.points.items():
        if cluster not in fits:  # one fit per cluster and frame (the pelvis carries both hips)
            current = np.stack([filtered[n] if n in filtered else carried[n] for n in cluster], axis=1)
            R, t = kabsch(ref, current)
            fits[cluster] = (R, t)
            fitted = np.einsum("fij,kj->fki", R, ref) + t[:, None, :]
            residual[cluster] = np.sqrt(np.mean(np.sum((fitted - current) ** 2, axis=-1), axis=-1))
        R, t = fits[cluster]
        carried[name] = np.einsum("fij,j->fi", R, p0) + t
    points = {k: cal.axes.sagittal(v) for k, v in carried.items()}
    angles = {}
    for s in SIDES:
        p = {k: points[f"{s}.{k}"] for k in ("hip", "knee", "ankle", "heel", "forefoot")}
        angles[f"{s}.thigh"] = _from_down(p["knee"] - p["hip"])
        angles[f"{s}.shank"] = _from_down(p["ankle"] - p["knee"])
        line = p["forefoot"] - p["heel"]
        angles[f"{s}.foot"] = np.arctan2(line[:, 1], line[:, 0]) - cal.foot_offset[s]
    pelvis = cal.points["R.hip"][0]
    angles["trunk"] = pitch(fits[pelvis][0], cal.axes)
    return Kinematics(np.arange(trial.frames) / trial.rate, points, angles, trial.rate, residual,
                      {**filtered, **carried})


def pitch(R, axes: Axes) -> np.ndarray:
    """Forward tilt (rad, nose down positive) of rotations R (frames, 3, 3) from standing."""
    f = R @ axes.forward
    return np.arctan2(-(f @ axes.up), f @ axes.forward)


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
    foot_strike_angle: float  # rad, foot angle relative to standing, toe up positive
    segments: dict[str, float]  # rad: trunk (tilt), thigh, shank (from the downward vertical,
    #                             end ahead positive), foot (relative to standing)
    angles: dict[str, float]  # rad: trunk, hip, knee, ankle (formopt's joint angles)
    rates: dict[str, float]  # rad/s: thigh, shank, foot (absolute)
    hip_velocity: tuple[float, float]  # m/s, ground frame (belt added)
    hip_height: float  # m above the lower foot point
    hip_from_point: dict[str, tuple[float, float]]  # m: the hip from the heel and the forefoot (forward, up)
    valid_data: bool = True
    problems: tuple[str, ...] = ()  # why valid_data is False

    def state(self) -> np.ndarray:
        """formopt's touchdown state vector (model.STATE)."""
        a, w = self.angles, self.rates
        return np.array([a["trunk"], a["hip"], a["knee"], a["ankle"], *self.hip_velocity, 0.0,
                         w["thigh"], w["shank"], w["foot"]])


@dataclass
class Steps:
    touchdowns: list[Touchdown]
    cadence_spm: float
    belt_speed: float  # m/s: the stance foot's backward speed (0 overground)
    speed: float  # m/s: the runner's speed over the ground
    method: str  # "force plate" or "kinematics"
    notes: list[str] = field(default_factory=list)  # from the reader and the checks

    @property
    def valid(self) -> list[Touchdown]:
        return [td for td in self.touchdowns if td.valid_data]

    @property
    def left_out(self) -> list[str]:
        """The steps not used, and why."""
        return [f"{td.time:.3f} s ({td.side}): {'; '.join(td.problems)}"
                for td in self.touchdowns if not td.valid_data]


def touchdowns(trial: Trial, kin: Kinematics, cal: Calibration, options: Options = Options()) -> Steps:
    """Touchdowns of both feet, their side, strike pattern, touchdown state and validity;
    the cadence and speed checked (module docstring)."""
    foot_low = {s: np.minimum(kin.points[f"{s}.heel"][:, 1], kin.points[f"{s}.forefoot"][:, 1])
                for s in SIDES}
    motion = {s: _foot_motion(kin, cal, s) for s in SIDES}
    belt = _belt_speed(trial, motion)
    pelvis = np.mean([kin.points[f"{s}.hip"][:, 0] for s in SIDES], axis=0)
    speed = belt + float(np.median(np.gradient(pelvis, 1.0 / kin.rate)))
    if not SPEED_RANGE[0] <= speed <= SPEED_RANGE[1]:
        raise MocapError(f"{trial.source}: a running speed of {speed:.3g} m/s is outside "
                         f"{SPEED_RANGE[0]:g}-{SPEED_RANGE[1]:g} m/s: wrong units or rate")
    if trial.force is not None:
        vertical = lowpass(trial.force, trial.force_rate, min(50.0, 0.4 * trial.force_rate),
                           trial.source) @ cal.axes.up
        threshold = options.force_threshold_n
        on = np.flatnonzero((vertical[1:] >= threshold) & (vertical[:-1] < threshold)) + 1
        times = [(t, min(SIDES, key=lambda s: foot_low[s][int(t * kin.rate)]))
                 for t in _separated(on / trial.force_rate, 0.15) if int(t * kin.rate) < len(kin.t)]
        method = "force plate"
    else:  # the foot's speed over the ground falls below a fraction of the running speed
        times = []
        for s in SIDES:
            slow = np.linalg.norm(motion[s][0] + [belt, 0.0], axis=1) < options.foot_speed_fraction * speed
            on = np.flatnonzero(slow[1:] & ~slow[:-1]) + 1
            times += [(t, s) for t in _separated(on / kin.rate, 0.25)]
        times.sort()
        method = "kinematics"
    if len(times) < 2:
        raise MocapError(f"{trial.source}: fewer than two touchdowns found ({method})")
    cadence = 60.0 / float(np.median(np.diff([t for t, _ in times])))
    notes = list(trial.notes) + list(cal.notes)
    _check_cadence(trial, kin, foot_low, cadence, notes)
    steps = []
    window = max(1, round(STEP_WINDOW * kin.rate))
    for t, side in times:
        frame = int(math.floor(t * kin.rate)) - 1
        if frame < 2 or frame >= len(kin.t) - 2:
            continue
        problems = _problems(trial, kin, cal, side, frame, window)
        steps.append(_touchdown(kin, side, frame, t, belt, foot_low[side][frame], problems))
    bad = sum(not td.valid_data for td in steps)
    if bad:
        notes.append(f"{bad} of {len(steps)} touchdowns have unsound markers around them: "
                     f"listed, left out of the means")
    return Steps(steps, cadence, belt, speed, method, notes)


def _foot_motion(kin: Kinematics, cal: Calibration, side: str):
    """The foot cluster's centre: sagittal velocity (frames, 2; m/s, lab) and height (m);
    the foot's angular velocity (rad/s)."""
    cluster = cal.points[f"{side}.heel"][0]
    centre = cal.axes.sagittal(np.mean([kin.markers[n] for n in cluster], axis=0))
    dt = 1.0 / kin.rate
    return np.gradient(centre, dt, axis=0), centre[:, 1], np.gradient(kin.angles[f"{side}.foot"], dt)


def _belt_speed(trial, motion) -> float:
    """The ground's backward speed (m/s; 0 overground): the foot cluster's while it rests flat
    (in the lowest third of its heights, turning under 0.5 rad/s, moving up or down under
    0.1 m/s)."""
    speeds = []
    for v, height, omega in motion.values():
        rest = (height < np.percentile(height, 35)) & (np.abs(omega) < 0.5) & (np.abs(v[:, 1]) < 0.1)
        if rest.sum() >= 5:
            speeds.append(-float(np.median(v[rest, 0])))
    if not speeds:
        raise MocapError(f"{trial.source}: no stance found: the feet never rest on the ground "
                         f"(is the rate, {trial.rate:g} Hz, right?)")
    return float(np.mean(speeds))


def _problems(trial, kin, cal, side, frame, window) -> tuple[str, ...]:
    """What is wrong with the markers of this leg and the pelvis around a touchdown."""
    lo, hi = max(frame - window, 0), frame + window + 1
    clusters = {c for name, (c, _, _) in cal.points.items() if name.startswith(side + ".")}
    names = sorted({n for c in clusters for n in c if n in trial.markers})
    out = []
    unsound = [n for n in names if n in trial.suspect and trial.suspect[n][lo:hi].any()]
    if unsound:
        out.append(f"missing or spiked samples in {', '.join(unsound)}")
    for c in sorted(clusters):
        worst = float(np.max(kin.residual[c][lo:hi]))
        if worst > RIGID:
            out.append(f"the cluster {', '.join(c)} is not rigid ({worst * 1e3:.0f} mm)")
    return tuple(out)


def _check_cadence(trial, kin, foot_low, cadence, notes):
    """The touchdowns' cadence against each foot's rhythm (twice its stride frequency) and the
    force's step frequency: they disagree when the force and marker files do not match."""
    def peak(signal, rate, lo, hi):
        spectrum = np.abs(np.fft.rfft(signal - signal.mean()))
        freqs = np.fft.rfftfreq(len(signal), 1.0 / rate)
        band = (freqs > lo) & (freqs < hi)
        return float(freqs[band][np.argmax(spectrum[band])]) if band.any() else float("nan")

    feet = 120.0 * np.mean([peak(foot_low[s], kin.rate, 0.5, 2.5) for s in SIDES])
    if not abs(cadence / feet - 1) < CADENCE_TOLERANCE:
        raise MocapError(f"{trial.source}: the touchdowns give a cadence of {cadence:.0f} steps/min "
                         f"but the feet move at {feet:.0f}: the force and marker data do not "
                         f"cover the same time (lengths or rates)")
    notes.append(f"cadence {cadence:.1f} steps/min; the feet's rhythm {feet:.1f}")


def _separated(times, gap):
    out = []
    for t in times:
        if not out or t - out[-1] > gap:
            out.append(float(t))
    return np.array(out)


def _touchdown(kin, side, frame, time, belt, low, problems) -> Touchdown:
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
                     segments={"trunk": trunk, **a},
                     angles={"trunk": trunk, "hip": a["thigh"] + trunk, "knee": a["thigh"] - a["shank"],
                             "ankle": a["foot"] - a["shank"]},
                     rates={k: rate(f"{side}.{k}") for k in ("thigh", "shank", "foot")},
                     hip_velocity=(float(v[0] + belt), float(v[1])),
                     hip_height=float(hip_p[frame][1] - low),
                     hip_from_point={p: tuple(map(float, hip_p[frame] - kin.points[f"{side}.{p}"][frame]))
                                     for p in ("heel", "forefoot")},
                     valid_data=not problems, problems=problems)


# -- the whole measurement ----------------------------------------------------------------

@dataclass
class Measurement:
    trial: Trial
    calibration: Calibration
    kinematics: Kinematics
    steps: Steps


def measure(trial: Trial, static: Trial, height: float, options: Options = Options()) -> Measurement:
    """Units, marker map, labels, axes, joint centres, kinematics and touchdowns of a run,
    every check on the way (module docstring); refuses with one line naming the file. The
    trials are copied: the Measurement holds the processed ones (units, labels, cleaning)."""
    trial, static = copy.deepcopy(trial), copy.deepcopy(static)
    ms = msets.load(options.markers) if options.markers else msets.recognise(trial.markers)
    resolve_units(static, trial, height, ms)
    check_static(static, ms)
    require(trial, ms.running(), f"the running trial ({ms.name} markers)")
    check_labels(static, trial, ms)
    cal = calibrate(static, trial, ms, height)
    kin = kinematics(trial, cal, options.cutoff_hz)
    steps = touchdowns(trial, kin, cal, options)
    steps.notes[:0] = [f"marker map: {ms.name} ({ms.title})"] + static.notes
    return Measurement(trial, cal, kin, steps)
