"""Files other tools read: OpenSim marker (.trc) and motion (.mot) files of a measured run.

OpenSim's ground frame: X forward, Y up, Z right. The markers are written after formopt's axes
and filter (mm, with the lab origin kept); the motion file holds formopt's sagittal angles per
frame in deg, named as in OpenSim's gait models (Rajagopal et al. 2016): pelvis_tilt (the
pelvis's tilt relative to standing; anterior tilt negative, OpenSim's sign), hip_flexion,
knee_angle (flexion positive) and ankle_angle (dorsiflexion positive), _r and _l.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..mechanics.model import joint_angles
from .files import atomic
from .markerset import SIDES

# kin and cal below are a measured run's measure.kinematics.Kinematics and
# measure.joints.Calibration (not imported: io sits below measure in the layers)

def write_trc(path, kin, cal, names=None):
    """The filtered markers (and carried joint centres, as R.hip ...) in OpenSim's frame."""
    names = list(names or kin.markers)
    ax = cal.axes
    R = np.array([ax.forward, ax.up, -ax.left])  # rows: OpenSim X, Y, Z in the file's frame
    frames = len(kin.t)
    with atomic(path) as fh:
        fh.write(f"PathFileType\t4\t(X/Y/Z)\t{path}\n")
        fh.write("DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\t"
                 "OrigDataStartFrame\tOrigNumFrames\n")
        fh.write(f"{kin.rate:g}\t{kin.rate:g}\t{frames}\t{len(names)}\tmm\t{kin.rate:g}\t1\t{frames}\n")
        fh.write("Frame#\tTime\t" + "\t".join(f"{n}\t\t" for n in names).rstrip("\t") + "\n")
        fh.write("\t\t" + "\t".join(f"X{k}\tY{k}\tZ{k}" for k in range(1, len(names) + 1)) + "\n")
        data = np.concatenate([kin.markers[n] @ R.T * 1e3 for n in names], axis=1)
        for f in range(frames):
            fh.write(f"{f + 1}\t{kin.t[f]:.6f}\t" + "\t".join(f"{v:.4f}" for v in data[f]) + "\n")
    return Path(path)

MOT_COLUMNS = ("pelvis_tilt", *[f"{j}_{s.lower()}" for s in SIDES
                                for j in ("hip_flexion", "knee_angle", "ankle_angle")])

def motion(kin) -> np.ndarray:
    """(frames, 7) sagittal angles in deg, MOT_COLUMNS."""
    trunk = kin.angles["trunk"]
    cols = [-trunk]
    for s in SIDES:
        j = joint_angles({"trunk": trunk, **{k: kin.angles[f"{s}.{k}"] for k in ("thigh", "shank", "foot")}})
        cols += [j["hip"], j["knee"], j["ankle"]]
    return np.degrees(np.column_stack(cols))

def write_mot(path, kin):
    return write_storage(path, kin.t, MOT_COLUMNS, motion(kin))


def write_storage(path, t, columns, values, degrees: bool = True):
    """An OpenSim storage file (.mot or .sto): time and named columns (values: rows, cols)."""
    with atomic(path) as fh:
        fh.write(f"{path}\nversion=1\nnRows={len(t)}\nnColumns={len(columns) + 1}\n"
                 f"inDegrees={'yes' if degrees else 'no'}\nendheader\n")
        fh.write("time\t" + "\t".join(columns) + "\n")
        for time, row in zip(t, values):
            fh.write(f"{time:.6f}\t" + "\t".join(f"{v:.5f}" for v in row) + "\n")
    return Path(path)

