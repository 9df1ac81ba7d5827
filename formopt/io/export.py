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



# The planar body as an OpenSim 4 model (write_osim): each coordinate's axis in OpenSim's frame
# (X forward, Y up, Z right) so that its sign is formopt's, the .mot's. pelvis_tilt: the trunk's
# tilt, about +Z (anterior negative, as gait2392 and Rajagopal 2016); hip_flexion about +Z
# (flexion positive, as both); knee_angle about -Z: flexion POSITIVE, as Rajagopal 2016 and
# opposite to gait2392 (whose knee_angle is flexion negative); ankle_angle about +Z
# (dorsiflexion positive, as both; 0 with the foot perpendicular to the shank).
OSIM_AXES = {"hip": "0 0 0", "knee": "3.14159265358979 0 0", "ankle": "0 0 0"}  # frame orientation:
# a PinJoint turns about its frames' Z; rotated by pi about X that is -Z (both frames alike, so
# the body does not move at 0)
LEG_WIDTH_M = 0.09  # each hip's offset along Z: only for the view, the model is planar


def _osim_body(name: str, mass: float, com, inertia: float) -> str:
    # planar: the sagittal inertia (about Z) is formopt's; X and Y get the same (a placeholder
    # that keeps the inertia valid; nothing moves about them)
    return (f'<Body name="{name}"><mass>{mass:.6g}</mass><mass_center>{com[0]:.6g} {com[1]:.6g} 0'
            f'</mass_center><inertia>{inertia:.6g} {inertia:.6g} {inertia:.6g} 0 0 0</inertia></Body>')


def _osim_joint(kind: str, name: str, parent: str, child: str, at, coords: list[tuple[str, str, float]],
                orientation: str = "0 0 0") -> str:
    frames = (f'<PhysicalOffsetFrame name="{parent.split("/")[-1]}_offset"><socket_parent>{parent}'
              f'</socket_parent><translation>{at[0]:.6g} {at[1]:.6g} {at[2]:.6g}</translation>'
              f'<orientation>{orientation}</orientation></PhysicalOffsetFrame>'
              f'<PhysicalOffsetFrame name="{child.split("/")[-1]}_offset"><socket_parent>{child}'
              f'</socket_parent><translation>0 0 0</translation><orientation>{orientation}</orientation>'
              f'</PhysicalOffsetFrame>')
    coordinates = "".join(f'<Coordinate name="{c}"><default_value>{d:.6g}</default_value><range>{r}</range>'
                          '</Coordinate>' for c, r, d in coords)
    return (f'<{kind} name="{name}"><socket_parent_frame>{parent.split("/")[-1]}_offset</socket_parent_frame>'
            f'<socket_child_frame>{child.split("/")[-1]}_offset</socket_child_frame>'
            f'<coordinates>{coordinates}</coordinates><frames>{frames}</frames></{kind}>')


def write_osim(path, body, name: str = "formopt_planar_body"):
    """The planar body (mechanics.body.Body with trunk, thigh, shank and foot; two legs alike) as
    an OpenSim 4 model: a trunk on a planar joint to the ground (pelvis_tilt, pelvis_tx,
    pelvis_ty), hips, knees and ankles as pin joints named as the .mot's columns (MOT_COLUMNS),
    each with formopt's sign (OSIM_AXES); masses, centres of mass and sagittal inertias are the
    body's, the segment frames formopt's (origin at the proximal joint, x forward, y up); the
    heel and forefoot contact points are markers (heel_r, forefoot_r, ...); pelvis_ty's default
    stands the heels on the ground (y = 0)."""
    trunk, thigh, shank, foot = (body[k] for k in ("trunk", "thigh", "shank", "foot"))
    bodies = [_osim_body("torso", trunk.mass, trunk.com, trunk.inertia_com)]
    standing = -(thigh.landmarks["knee"][1] + shank.landmarks["ankle"][1] + foot.landmarks["heel"][1])
    joints = [_osim_joint("PlanarJoint", "ground_pelvis", "/ground", "/bodyset/torso", (0.0, 0.0, 0.0),
                          [("pelvis_tilt", "-1.5708 1.5708", 0.0), ("pelvis_tx", "-100 100", 0.0),
                           ("pelvis_ty", "-1 3", standing)])]  # the hip's height, m: standing at 0
    markers = []
    for side, z in (("r", LEG_WIDTH_M), ("l", -LEG_WIDTH_M)):
        knee, ankle = thigh.landmarks["knee"], shank.landmarks["ankle"]
        for seg in (thigh, shank, foot):
            bodies.append(_osim_body(f"{seg.name}_{side}", seg.mass, seg.com, seg.inertia_com))
        joints += [
            _osim_joint("PinJoint", f"hip_{side}", "/bodyset/torso", f"/bodyset/thigh_{side}", (0.0, 0.0, z),
                        [(f"hip_flexion_{side}", "-2.0944 2.0944", 0.0)], OSIM_AXES["hip"]),
            _osim_joint("PinJoint", f"knee_{side}", f"/bodyset/thigh_{side}", f"/bodyset/shank_{side}",
                        (knee[0], knee[1], 0.0), [(f"knee_angle_{side}", "-0.1745 2.0944", 0.0)], OSIM_AXES["knee"]),
            _osim_joint("PinJoint", f"ankle_{side}", f"/bodyset/shank_{side}", f"/bodyset/foot_{side}",
                        (ankle[0], ankle[1], 0.0), [(f"ankle_angle_{side}", "-1.0472 0.8727", 0.0)], OSIM_AXES["ankle"])]
        markers += [f'<Marker name="{p}_{side}"><socket_parent_frame>/bodyset/foot_{side}</socket_parent_frame>'
                    f'<location>{foot.landmarks[p][0]:.6g} {foot.landmarks[p][1]:.6g} 0</location></Marker>'
                    for p in ("heel", "forefoot")]
    text = ('<?xml version="1.0" encoding="UTF-8" ?>\n<OpenSimDocument Version="40000">'
            f'<Model name="{name}"><credits>formopt: {body.source}</credits>'
            '<gravity>0 -9.80665 0</gravity><Ground name="ground"/>'
            f'<BodySet name="bodyset"><objects>{"".join(bodies)}</objects></BodySet>'
            f'<JointSet name="jointset"><objects>{"".join(joints)}</objects></JointSet>'
            f'<MarkerSet name="markerset"><objects>{"".join(markers)}</objects></MarkerSet>'
            '</Model></OpenSimDocument>\n')
    with atomic(path) as fh:
        fh.write(text)
    return Path(path)


def write_grf(path, t, force, points, side: str = "r"):
    """The ground force on one foot as OpenSim external loads (.sto, SI): `force` (N, 2 points,
    x and z, N) on the heel and forefoot at `points` (N, 2 points, x and z, m, formopt's axes),
    one resultant per row applied at the centre of pressure (the points weighted by their
    normal force; the heel when no force), no free moment (both points on the ground). Columns
    `{side}_ground_force_v{x,y,z}`, `_p{x,y,z}`, `{side}_ground_torque_{x,y,z}` in OpenSim's
    frame (Y up, Z right: z is 0 in the plane), for an ExternalLoads file to apply to the foot."""
    force, points = np.asarray(force, float), np.asarray(points, float)
    total = force.sum(axis=1)  # (N, 2)
    normal = force[:, :, 1]
    share = np.divide(normal, normal.sum(axis=1, keepdims=True), out=np.zeros_like(normal),
                      where=normal.sum(axis=1, keepdims=True) > 0)
    share[share.sum(axis=1) == 0, 0] = 1.0  # no force: the heel
    cop = np.einsum("np,npk->nk", share, points)
    zero = np.zeros(len(total))
    values = np.column_stack([total[:, 0], total[:, 1], zero, cop[:, 0], cop[:, 1], zero, zero, zero, zero])
    columns = [f"{side}_ground_force_v{a}" for a in "xyz"] + [f"{side}_ground_force_p{a}" for a in "xyz"] \
        + [f"{side}_ground_torque_{a}" for a in "xyz"]
    return write_storage(path, t, columns, values, degrees=False)
