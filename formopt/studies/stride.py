"""The stride of a scene: one optimum per strike ("best": each solved, the best first by
optim.stride.rank: valid, converged, then the least costly), by the scene's search (`[stride]
search`: "local", optim.stride.optimum's starts, or "global", optim.stride.search); with
`[stride] mesh_check`, each strike's stride solved again on twice its nodes from itself
(optim.stride.refine.mesh_check: its record on the stride, the stride itself the N-node one).

The NLP of a body and settings is built once (`Strider`) and solved for any speed, slope,
friction and imposed cadence; a neighbouring solve is warm-started from the last optimum.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..io.stride_scene import StrideScene
from ..mechanics.errors import InputError
from ..optim.stride import Stride, global_optimum, optimum, ranges, rank
from ..optim.stride.notes import mesh_cost_pct, mesh_note, transcription_note
from ..optim.stride.problem import STRIKES
from ..optim.stride.refine import fine_nodes, mesh_check
from ..optim.stride.search import solves_planned

ROW_KEYS = ("strike", "success", "objective_value", "cadence_spm", "step_length_m", "stance_s",
            "flight_s", "duty_factor", "peak_vertical_grf_bw", "cost_of_transport",
            "mechanical_power_W", "swing_clearance_m", "stance_knee_deg", "iterations", "solve_s", "search")


@dataclass
class StrideStudy:
    """The strides of a scene, the least costly (objective per distance) first."""

    scene: str
    strides: list = field(default_factory=list)
    # how sure the optima are of their mesh: each stride's mesh check (optim.stride.refine), or
    # what was measured on RBDS001 (optim.stride.notes.mesh_note)
    mesh: str = ""
    # how the optima were found where no global search says it (its record does): the local starts
    search: str = ""
    # what the other transcription finds for the scene's cost at free cadence
    # (optim.stride.notes.transcription_note; "" with the cadence imposed)
    transcription: str = ""
    # the strikes the model cannot order: costs apart by less than their mesh moves them (`tie_note`)
    tie: str = ""
    # where the least costly stride is unlike a runner's, the least costly one that is not (`unlike_note`)
    unlike: str = ""

    @property
    def best(self) -> Stride:
        return self.strides[0]

    def to_dict(self) -> dict:
        """The best stride's JSON, with one row per strike solved (`strides`: what the table
        prints of each, its global search's and mesh check's records included)."""
        rows = [{**{k: getattr(s, k) for k in ROW_KEYS},
                 "impacts_J": s.budget["impacts_J"],
                 "impacts_valid": all(i["valid"] for i in s.impacts), "valid": s.valid,
                 "mesh_check": None if s.mesh_check is None else s.mesh_check.to_dict()}
                for s in self.strides]
        return {"scene": self.scene, **self.best.to_dict(), "strides": rows, "mesh": self.mesh,
                "search_note": self.search, "transcription_note": self.transcription, "tie_note": self.tie,
                "unlike_note": self.unlike}


def run(scene: StrideScene, speed: float | None = None, strike: str | None = None,
        simulate: bool = True, progress=None) -> StrideStudy:
    """Solve the scene's strides (`speed`, `strike`: overrides; "best" solves each), each
    mesh-checked with `scene.mesh_check`; `progress(text)`, when given, is told of each strike
    before it is solved, and of its mesh check."""
    speed = scene.speed if speed is None else speed
    ranges.point(speed, scene.cadence)
    choice = scene.strike if strike is None else strike
    if choice not in (*STRIKES, "best"):
        raise InputError(f"strike {choice!r}: expected one of {', '.join(STRIKES)} or best")
    if scene.mesh_check:
        fine_nodes(scene.settings.nodes)  # refused before any solve
    strikes = STRIKES if choice == "best" else (choice,)
    strides = []
    for k, name in enumerate(strikes, 1):
        head = f"[{k}/{len(strikes)}] {name} strike"
        say = None if progress is None else (lambda text, head=head: progress(f"{head}: {text}"))
        nlp = scene.nlp(name)
        if scene.search == "global":
            stride = global_optimum(nlp, speed, scene.slope, scene.friction, scene.cadence, scene.spend,
                                    simulate, say)
        else:
            if say:
                say(f"{scene.starts} start(s)")
            stride = optimum(nlp, speed, scene.slope, scene.friction, scene.cadence, simulate=simulate,
                             starts=scene.starts)
        if scene.mesh_check:
            if say:
                say(f"mesh check on {fine_nodes(nlp.settings.nodes)} nodes")
            stride = replace(stride, mesh_check=mesh_check(nlp, stride, simulate))
        strides.append(stride)
    strides.sort(key=rank)
    local = "" if scene.search == "global" else (
        f"the best of {scene.starts} start{'s' if scene.starts > 1 else ''} per strike: a local optimum, the cadences "
        "not searched ([stride] search = \"global\" searches them: docs/concepts/stride.md, 'One answer')")
    return StrideStudy(scene.name, strides, mesh_text(strides) if scene.mesh_check else mesh_note(scene.settings),
                       local, transcription_note(scene.settings) if scene.cadence is None else "",
                       tie_note(strides, lambda s: mesh_cost_pct(scene.for_strike(s.strike), s.speed_mps)),
                       unlike_note(strides))


def tie_note(strides: list[Stride], measured_pct: Callable[[Stride], float | None]) -> str:
    """The strikes whose cost lies within the mesh's uncertainty of the best's, in words ("" when
    none): valid, converged strides (ranked, the best first) whose objective J is above the
    best's by 100 (J - J_best) / |J_best| < u_best + u_J %, each u a stride's own mesh check's
    cost change (where it measured: MeshCheck.measured) or else `measured_pct(stride)`
    (optim.stride.notes.mesh_cost_pct); nothing is said for a stride whose u is unknown."""
    sound = _sound(strides)

    def moved(s: Stride) -> float | None:
        c = s.mesh_check
        return abs(c.objective_change_pct) if c is not None and c.measured else measured_pct(s)

    first = moved(sound[0]) if len(sound) > 1 else None
    if first is None:
        return ""
    best, tied = sound[0], []
    for s in sound[1:]:
        other = moved(s)
        if other is None:
            continue
        gap = _costlier_pct(s, best)
        if gap < first + other:
            tied.append(f"{s.strike} ({s.cadence_spm:.1f} steps/min) {gap:.2f} % costlier, less than the mesh may "
                        f"move the difference ({first + other:.2f} %: each cost up to {first:.2f} and {other:.2f} %)")
    if not tied:
        return ""
    return (f"the {best.strike} strike ({best.cadence_spm:.1f} steps/min) is the least costly, but {'; '.join(tied)}: "
            f"the model cannot tell these strikes apart, and {'either' if len(tied) == 1 else 'any'} is its answer")


def unlike_note(strides: list[Stride]) -> str:
    """Where the least costly of several valid, converged strides (ranked first) is unlike a
    runner's (Stride.unlike_a_runner: a crouched stance, a stiff landing), the least
    costly one that is not, with how much more it costs (%), in words ("" otherwise)."""
    sound = _sound(strides)
    if len(sound) < 2 or not sound[0].unlike_a_runner:  # one strike solved: its own NOTE says it
        return ""
    best, alike = sound[0], next((s for s in sound[1:] if not s.unlike_a_runner), None)
    said = f"the least costly stride, the {best.strike} strike, is unlike a runner's (its NOTE says how)"
    if alike is None:
        return said + ", and so is every other strike solved"
    return (f"{said}; the least costly stride without such a remark is the {alike.strike} strike "
            f"({alike.cadence_spm:.1f} steps/min, {_costlier_pct(alike, best):.1f} % costlier)")


def _sound(strides: list[Stride]) -> list[Stride]:
    """The valid, converged strides, in their (ranked) order: those `tie_note` and `unlike_note` compare."""
    return [s for s in strides if s.valid and s.success]


def _costlier_pct(stride: Stride, best: Stride) -> float:
    """How much costlier (%) `stride` is than `best`: 100 (J - J_best) / |J_best| (guarded at J_best = 0)."""
    return 100.0 * (stride.objective_value - best.objective_value) / max(abs(best.objective_value), 1e-12)


def mesh_text(strides: list[Stride]) -> str:
    """What the mesh checks measured, each strike's ("heel: " and optim.stride.refine.MeshCheck.text)."""
    return "; ".join(f"{s.strike}: {s.mesh_check.text()}" for s in strides if s.mesh_check is not None)


def stages(scene: StrideScene, speed: float | None = None, strike: str | None = None) -> int:
    """How many times `run` tells its progress: per strike once, or once per solve of the global
    search (optim.stride.search.solves_planned), and once more for its mesh check."""
    strikes = len(STRIKES) if (strike or scene.strike) == "best" else 1
    solves = 1 if scene.search != "global" else \
        solves_planned(scene.speed if speed is None else speed, scene.spend, scene.cadence)
    return strikes * (solves + scene.mesh_check)


# RBDS001's mean gait cycle (Fukuchi et al. 2017; the data set's Visual3D processing): 101
# rows from right touchdown; Z columns sagittal (hip and knee flexion, ankle dorsiflexion, deg;
# moments N m/kg, extensor / plantarflexor positive), grfY vertical (N/kg)
RBDS_SPEEDS = {2.5: "25", 3.5: "35", 4.5: "45"}
CYCLE_JOINTS = ("hip", "knee", "ankle")
# The data set's hip moment is flexor positive (-1.1 N m/kg in early stance, where the hip
# extensors work, +0.8 at toe-off at 3.5 m/s), its knee and ankle moments extensor and
# plantarflexor positive: the hip's sign turned to formopt's (extensor positive).
HIP_SIGN = {"hip": -1.0}


def measured_cycle(path, speed: float) -> dict | None:
    """RBDS001's right-leg mean cycle at `speed` (m/s; None unless 2.5, 3.5 or 4.5): percent
    (101), angles (deg), moments (N m/kg) and powers (W/kg, generation positive) per joint,
    vertical force (N/kg)."""
    suffix = RBDS_SPEEDS.get(round(speed, 2))
    if suffix is None:
        return None
    data = np.genfromtxt(path, names=True, delimiter="\t")
    return {"percent": data["PercGcycle"],
            "angles": {j: data[f"R{j}AngZ{suffix}"] for j in CYCLE_JOINTS},
            "moments": {j: HIP_SIGN.get(j, 1.0) * data[f"R{j}MomZ{suffix}"] for j in CYCLE_JOINTS},
            "powers": {j: data[f"R{j}Pow{suffix}"] for j in CYCLE_JOINTS},
            "vertical": np.nan_to_num(data[f"RgrfY{suffix}"], nan=0.0)}


def predicted_cycle(stride: Stride) -> dict:
    """The right leg over a whole gait cycle from the half stride (its left leg gives the second
    half, by symmetry): percent, angles (deg), the thigh from the downward vertical (deg, knee
    ahead positive: thigh = hip - trunk, mechanics.model.segment_angles), net moments (N m/kg: the
    active moments and the tendons'), their powers (W/kg, P = -tau theta': generation positive),
    vertical force (N/kg)."""
    T = stride.half_period_s
    percent = np.r_[stride.t / T * 50.0, 50.0 + stride.t / T * 50.0]
    m = stride.mass_kg
    angles = {j: np.degrees(np.r_[stride.theta[:, 3 + k], stride.theta[:, 6 + k]])
              for k, j in enumerate(CYCLE_JOINTS)}
    thigh = angles["hip"] - np.degrees(np.r_[stride.theta[:, 2], stride.theta[:, 2]])
    net = stride.tau + (0.0 if stride.tau_spring is None else stride.tau_spring)
    moments = {j: np.r_[net[:, k], net[:, 3 + k]] / m for k, j in enumerate(CYCLE_JOINTS)}
    rates = {j: np.r_[stride.thetad[:, 3 + k], stride.thetad[:, 6 + k]] for k, j in enumerate(CYCLE_JOINTS)}
    powers = {j: -moments[j] * rates[j] for j in CYCLE_JOINTS}
    vertical = np.r_[stride.force[:, :, 1].sum(axis=1), np.zeros(len(stride.t))] / m
    return {"percent": percent, "angles": angles, "thigh": thigh, "moments": moments, "powers": powers,
            "vertical": vertical}


def cycle_angles(stride: Stride, percent) -> dict:
    """The predicted right-leg joint angles and the thigh's (deg; predicted_cycle) at the cycle's
    `percent`."""
    predicted = predicted_cycle(stride)
    order = np.argsort(predicted["percent"], kind="stable")
    curves = {**predicted["angles"], "thigh": predicted["thigh"]}
    return {j: np.interp(percent, predicted["percent"][order], curve[order]) for j, curve in curves.items()}


def compare_cycle(stride: Stride, measured: dict) -> dict:
    """Predicted against measured: joint angles over the cycle (deg): the RMS of the difference
    d = predicted - measured, its mean (`angle_offset_deg`) and its RMS with the mean removed
    (`angle_rms_shape_deg`; rms^2 = offset^2 + shape^2): the data set's hip is the thigh against
    the pelvis's ASIS-PSIS frame (tilted about 18 deg forward in RBDS001's running: problems/stride_angles.py --markers), formopt's
    the thigh against the trunk, so the hip's offset is part definition; stance time (s, the
    measured from the vertical force above 0.5 N/kg over a cycle of 120 / cadence), peak
    vertical force (N/kg)."""
    predicted = predicted_cycle(stride)
    curves = cycle_angles(stride, measured["percent"])
    diff = {j: curves[j] - measured["angles"][j] for j in CYCLE_JOINTS}
    offset = {j: float(np.mean(d)) for j, d in diff.items()}
    stance_share = float(np.mean(measured["vertical"][:-1] > 0.5))
    return {"angle_rms_deg": {j: float(np.sqrt(np.mean(d ** 2))) for j, d in diff.items()},
            "angle_offset_deg": offset,
            "angle_rms_shape_deg": {j: float(np.sqrt(np.mean((d - offset[j]) ** 2))) for j, d in diff.items()},
            "stance_share_measured": stance_share,
            "stance_share_predicted": stride.duty_factor,
            "peak_vertical_n_per_kg": {"predicted": float(np.max(predicted["vertical"])),
                                       "measured": float(np.max(measured["vertical"]))}}
