"""Motion-capture files: a trial's markers and force as the file holds them, and the RBDS text
layout written back. Processing (units, axes, cleaning, joint centres, touchdowns) is
formopt.measure's.

Readers: C3D through ezc3d (markers, force plates with their calibration, units and rates from
the file) and the RBDS text layout (markers: Time (s) then NAMEX NAMEY NAMEZ; forces: frame,
Fx Fy Fz (N), and where the header names them COPx COPy COPz (mm), ... at the rate that spans
the marker file's duration). An empty cell, a NaN or
an exact (0, 0, 0) is a missing sample (measure.clean marks it); a column with no value at all
is a marker the lab removed (dropped, with a note); missing force samples are interpolated
(with a note), and an empty plate is dropped (touchdowns then come from the kinematics).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..mechanics.errors import InputError

UNITS = {"mm": 1e-3, "millimeters": 1e-3, "millimetres": 1e-3, "cm": 1e-2, "dm": 0.1,
         "m": 1.0, "meters": 1.0, "metres": 1.0}


# A force plate's samples beyond 100 kN are not a runner's (peak vertical forces are 2-3 body
# weights, about 2-3 kN; RBDS001: 25.2 N/kg at 4.5 m/s): the file's unit or its data is wrong.
FORCE_LIMIT_N = 1e5
# A marker coordinate beyond 1000 km (or 1000 km in mm, for a file without units) is not a
# lab's: a damaged file (1e300 overflowed the cluster sizes to inf, after numpy's warnings).
MARKER_LIMIT = 1e6


class MocapError(InputError):
    """A motion-capture file formopt cannot use, and why."""


@dataclass
class Trial:
    """Markers (m once the units are known; lab axes as recorded) and, if any, the ground
    reaction force (N) and its centre of pressure (m, the markers' lab frame)."""

    markers: dict[str, np.ndarray]  # name -> (frames, 3)
    rate: float  # Hz
    force: np.ndarray | None = None  # (samples, 3)
    force_rate: float | None = None
    source: str = ""
    units: str = "m"  # as the file declares them; "" when it does not (markers still in its unit)
    # measure.clean fills these two: long gaps (start, stop frames) and the samples not measured
    gaps: dict[str, list[tuple[int, int]]] = field(default_factory=dict)
    suspect: dict[str, np.ndarray] = field(default_factory=dict)  # name -> (frames,) bool
    notes: list[str] = field(default_factory=list)  # what the reader (and the cleaning) did
    cop: np.ndarray | None = None  # (samples, 3) m, at force_rate; None: the file has none

    @property
    def frames(self) -> int:
        return len(next(iter(self.markers.values())))

    def check(self) -> None:
        """Refuse, naming the file, a marker rate (or a force rate, with a force) that is not a
        finite number > 0 Hz (every time derivative divides by it), and a force beyond
        FORCE_LIMIT_N or a marker coordinate beyond MARKER_LIMIT."""
        rates = {"marker": self.rate, **({"force": self.force_rate} if self.force is not None else {})}
        for what, rate in rates.items():
            if isinstance(rate, bool) or not isinstance(rate, (int, float, np.number)) or not (math.isfinite(rate)
                                                                                   and rate > 0):
                raise MocapError(f"{self.source}: the {what} rate {rate!r} Hz must be a finite number > 0")
        far = [name for name, xyz in self.markers.items() if np.any(np.abs(xyz) > MARKER_LIMIT)]
        if far:
            raise MocapError(f"{self.source}: marker {far[0]} lies beyond {MARKER_LIMIT:g} (in the file's "
                             "unit, or m): a damaged file")
        beyond = np.abs(self.force)[np.abs(self.force) > FORCE_LIMIT_N] if self.force is not None else ()
        if len(beyond):
            top = float(np.max(beyond))
            raise MocapError(f"{self.source}: a ground force of {top:.3g} N, beyond {FORCE_LIMIT_N:g} N: "
                             "not a runner's (the force file's unit?)")

    def require(self, names, what: str) -> None:
        """Refuse, naming the file and `what` needs them, when markers `names` are missing."""
        missing = [n for n in names if n not in self.markers]
        if missing:
            raise MocapError(f"{self.source}: {what} needs markers that are missing: {', '.join(missing)}")

    def mean_positions(self) -> dict[str, np.ndarray]:
        """Each marker's mean position over the frames it was seen (3,)."""
        return {n: np.nanmean(v, axis=0) for n, v in self.markers.items()}


# -- readers ------------------------------------------------------------------------------

def read(path, forces=None) -> Trial:
    """A trial as the file holds it, from a C3D file or an RBDS marker text file (with an
    optional force file); measure.measure cleans it."""
    path = Path(path)
    if not path.exists():
        raise MocapError(f"{path}: no such file")
    if path.suffix.lower() != ".c3d":
        return read_text(path, forces)
    if forces is not None:  # not silently ignored: the C3D's own plates are what is read
        raise MocapError(f"{path}: a C3D file holds its force plates; a force file ({forces}) goes "
                         "with a text trial only")
    return read_c3d(path)


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
        plate = platforms[0]
        scale = UNITS.get(str(plate.get("unit_position", "")).strip().lower())
        _set_force(trial, np.asarray(plate["force"], float).T,
                   float(c3d["header"]["analogs"]["frame_rate"]), str(path),
                   None if scale is None else np.asarray(plate["center_of_pressure"], float).T * scale)
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
        with warnings.catch_warnings():  # numpy's warning (an empty file): the refusal's reason
            warnings.simplefilter("error")
            data = np.genfromtxt(path, skip_header=1, delimiter="\t", ndmin=2, invalid_raise=True)
    except (OSError, ValueError, UnicodeDecodeError, Warning) as err:
        reason = "no data rows" if isinstance(err, Warning) else one_reason(err)
        raise MocapError(f"{path}: not a {what} text file in the RBDS layout ({reason})") from None
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
    with np.errstate(invalid="ignore"):  # inf - inf: refused just below, without numpy's warning
        step = np.diff(time)
    if not np.all(np.isfinite(time)) or np.any(step <= 0):
        bad = int(np.flatnonzero(~(step > 0))[0]) + 2 if np.any(~(step > 0)) else 1
        raise MocapError(f"{path}: the Time column does not increase (row {bad})")
    # the column is rounded to the millisecond: the span over the whole trial gives the rate
    # to about 0.003 Hz, so it is rounded to 0.01 Hz
    rate = round((len(time) - 1) / float(time[-1] - time[0]), 2)
    if not rate > 0:
        raise MocapError(f"{path}: the Time column spans {time[-1] - time[0]:.4g} s for {len(time)} "
                         f"rows: a marker rate of {rate:g} Hz (Time in s?)")
    markers = {header[k][:-1]: data[:, k:k + 3] * 1e-3 for k in range(1, len(header), 3)}
    trial = Trial(markers, rate, source=str(path), units="mm")
    if forces is not None:
        fpath = Path(forces)
        fheader, fdata = _table(fpath, "force")
        if fdata.shape[1] < 4 or len(fdata) < 2:
            raise MocapError(f"{fpath}: expected frame, Fx, Fy, Fz columns")
        cop = [fheader.index(f"COP{a}") for a in "xyz" if f"COP{a}" in fheader]
        _set_force(trial, fdata[:, 1:4], round(len(fdata) / (len(time) / rate), 2), str(fpath),
                   fdata[:, cop] * 1e-3 if len(cop) == 3 else None)
    return _drop_empty(trial)


def _set_force(trial: Trial, force, rate: float, name: str, cop=None):
    """The plate's force and its centre of pressure (m; None: not in the file), unless the
    force is empty (then touchdowns come from the kinematics); `name`, the file, names it in
    the notes and refusals."""
    finite = np.abs(force[np.isfinite(force)])
    if finite.size and finite.max() > 50.0:
        trial.cop = cop if cop is not None and cop.shape == force.shape else None
        good = np.all(np.isfinite(force), axis=1)
        if not good.any():
            raise MocapError(f"{name}: no force sample has finite Fx, Fy and Fz")
        if not good.all():
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
    """Write a trial in the RBDS text layout (mm; forces in N, the centre of pressure in mm),
    each file renamed into place."""
    names = list(trial.markers)
    table = np.column_stack([np.arange(trial.frames) / trial.rate] +
                            [trial.markers[n] * 1e3 for n in names])
    header = "\t".join(["Time"] + [f"{n}{a}" for n in names for a in "XYZ"])
    _save(markers_path, table, header)
    if forces_path is not None and trial.force is not None:
        rows = np.column_stack([np.arange(1, len(trial.force) + 1), trial.force]
                               + ([trial.cop * 1e3] if trial.cop is not None else []))
        _save(forces_path, rows, "Time\tFx\tFy\tFz" + ("\tCOPx\tCOPy\tCOPz" if trial.cop is not None else ""))


def _save(path, table, header):
    from .files import atomic

    with atomic(path) as fh:
        np.savetxt(fh, table, delimiter="\t", header=header, comments="", fmt="%.10g")
