"""formopt stride SCENE: the periodic running half stride (figures, CSV, JSON, OpenSim files)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from .. import api
from ..io.export import write_grf, write_osim, write_storage
from ..io.files import save_figure, write_csv
from ..io.progress import Stages
from ..io.scene import load
from ..io.stride_scene import STRIDE_STRIKES, StrideScene
from ..mechanics.errors import InputError
from ..mechanics.joint_space import JOINTS, JointSpace
from ..optim.stride.result import FOOT_POINTS
from ..report.stride import stride_figures, stride_table
from ..studies.stride import measured_cycle, stages
from .common import add_format, emit, out_folder

# RBDS001's measured mean cycle, drawn beside the prediction when the repository's data are there
RBDS = Path(__file__).resolve().parents[2] / "data" / "rbds" / "RBDS001processed.txt"
MOT_NAMES = ("pelvis_tilt", "hip_flexion_r", "knee_angle_r", "ankle_angle_r", "hip_flexion_l",
             "knee_angle_l", "ankle_angle_l")


def add_parser(commands):
    cmd = commands.add_parser("stride", help="the periodic running half stride optimum")
    add_format(cmd)
    cmd.add_argument("scene", help="stride scene: a file or a shipped name, e.g. stride (`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--speed", type=float, help="running speed (m/s) instead of the scene's")
    cmd.add_argument("--strike", choices=STRIDE_STRIKES, help="strike instead of the scene's")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for figures, CSV, JSON and OpenSim files")
    cmd.add_argument("--mesh-check", action="store_true",
                     help="solve each strike's stride again on twice its nodes from itself and report what "
                          "that moved (the scene's [stride] mesh_check = true); the outputs stay the N-node stride's")


def stride_rows(stride):
    """stride.csv: time, phase, joint angles (deg) and moments (N m) of both legs, the ground
    force (N, x and z) of each foot point of the leading leg."""
    yield ["t_s", "phase", *[f"{j}_deg" for j in JOINTS], *[f"{j}_Nm" for j in JOINTS],
           *[f"{p}_{a}_N" for p in FOOT_POINTS for a in ("x", "z")]]
    for k, t in enumerate(stride.t):
        yield [t, stride.phase[k], *np.degrees(stride.theta[k, 3:]), *stride.tau[k],
               *stride.force[k].ravel()]


def muscle_rows(stride):
    """stride_muscles.csv: time, phase, each muscle's activation (0-1) and tendon force (N),
    both legs."""
    names = stride.muscles["names"]
    yield ["t_s", "phase", *[f"{m}_activation" for m in names], *[f"{m}_force_N" for m in names]]
    for k, t in enumerate(stride.t):
        yield [t, stride.phase[k], *stride.muscles["activation"][k], *stride.muscles["tendon_force_N"][k]]


def foot_points(stride, js: JointSpace) -> np.ndarray:
    """The leading leg's heel and forefoot (n, 2, x and z, m) at each node (OpenSim's points of
    application of the ground force)."""
    return np.array([[np.asarray(js.points[p](th, np.zeros(9), stride.slope)[0], float).ravel()[:2]
                      for p in FOOT_POINTS] for th in stride.theta])


def run(args) -> int:
    scene = load(args.scene)
    if not isinstance(scene, StrideScene):
        raise InputError(f"{args.scene}: not a stride scene (it has no [stride] table)")
    if args.mesh_check:
        scene = replace(scene, mesh_check=True)
    out = out_folder(args, scene.path or scene.name)
    with Stages(None if args.json else stages(scene, args.speed, args.strike), "stride") as say:
        study = api.stride(scene, args.speed, args.strike, progress=say)
    best = study.best
    measured = measured_cycle(RBDS, best.speed_mps) if RBDS.exists() else None
    files = [save_figure(fig, out / f"stride_{name}.{args.format}")
             for name, fig in stride_figures(best, JointSpace(scene.body), measured).items()]
    files.append(write_csv(out / "stride.csv", stride_rows(best)))
    if best.muscles is not None:
        files.append(write_csv(out / "stride_muscles.csv", muscle_rows(best)))
    angles = np.degrees(np.column_stack([-best.theta[:, 2], best.theta[:, 3:]]))
    files.append(write_storage(out / "stride.mot", best.t, MOT_NAMES, angles))
    files.append(write_osim(out / "stride.osim", scene.body))
    files.append(write_grf(out / "stride_grf.sto", best.t, best.force, foot_points(best, JointSpace(scene.body))))
    report = {**study.to_dict(), "files": [str(f) for f in files]}
    emit(args, report, stride_table(study), out / "stride.json", files)
    return 0 if best.valid else 1
