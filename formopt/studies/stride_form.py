"""Running form from a solved stride: the scene of a body, per-joint work, the touchdown placement.

Shared by compare's stride section (studies.compare_stride) and the literature checks
(problems/literature.py); strides at imposed cadences come from studies.stride_map.cadence_curve.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from ..io.stride_scene import StrideScene
from ..mechanics.body import Body
from ..mechanics.joint_space import JOINTS
from ..optim.stride import Stride, StrideSettings
from ..optim.stride.actuation import springs
from ..optim.stride.problem import (
    APPROACH_SPEED,
    MOMENT_TIME,
    RUNNER_ANKLE,
    RUNNER_IMPACT_WEIGHT,
    RUNNER_NODES,
    RUNNER_TENDONS,
    RUNNER_TRANSCRIPTION,
)

# collocation intervals of compare's quick model and the literature checks: at 24 the free optimum
# of RBDS001's body (heel, effort) jumped between local optima, 266 steps/min at 3.584 m/s and
# 142.5 at 3.58 (2 starts); at 30 it is 175.7 steps/min (objective 0.780, lower than both) with
# 1 or 2 starts, 2-3 s of CPU (2026-11-23)
NODES = 30
# the transcription of compare's quick model and the literature checks. Hermite-Simpson at 24
# intervals is mesh-converged where the trapezoid at 30 is not (compare's three shipped runners,
# each imposed stride solved again on twice the mesh: the objective moved 0.1-1.5 % against 10-18 %,
# the what-ifs' changes 0.1-5.6 W against 1.3-19.2 W), but the section then takes 24-42 s a trial
# instead of 15-18 (its warm starts take 25-50 IPOPT iterations of 12-14 ms against 9-16 of 7), and
# with compare's knee spring RIC's free optimum crouches (stance knee 70 deg); the torque scenes'
# model (no knee spring, impacts charged, moment dynamics) on it fails its forward check on RBDS001
# T25 (0.31 rad), and on their 40 intervals takes 80-164 s a section (eight of the three runners'
# twelve verdicts other than the trapezoid's). Kept: the trapezoid in the quick model, its mesh
# said in the section's notes (docs/howto/compare.md, "Hermite-Simpson under the what-ifs",
# 2026-11-28); the default is STRIDE_MODELS' scenes.
TRANSCRIPTION = "trapezoid"
MAX_ITER = 500  # IPOPT iterations: a converging stride takes 30-300 (2026-11-23, 24 nodes)
# compare's stride models (its `stride_model` setting; docs/howto/compare.md, "Two stride models"),
# each the settings its strides are built with beyond the body, speed, strike, objective and law:
# - scenes (the default): formopt stride's torque scenes' model (formopt/scenes/stride_rbds001.toml;
#   problem.RUNNER_ANKLE): Hermite-Simpson at 40 intervals, the ankle's spring alone, the impacts
#   charged, moment dynamics, the approach floor and IPOPT's 1000 iterations: mesh-converged
#   (optim.stride.notes.RUNNER_MESH, RUNNER_COULOMB_MESH), every stride of the three shipped
#   runners valid, 80-165 s a section (benchmarks/compare_speed.py --model scenes; `formopt
#   compare --scene problems/compare/runners.toml`: 89 / 113 / 104 s and 80 / 146 / 103 s,
#   then 91 / 165 / 114 s as the default, T35 / T25 / RIC, 2026-11-28). The default since 2026-11-28: design.md section 7 asks of a
#   reported optimum that N against 2N nodes move it within 1 %, and on the quick model a
#   different warm start of the band's metabolic variant turned 6 of the 12 shipped verdicts
#   (scenes: 1; docs/howto/compare.md, "Two stride models");
# - quick (`stride_model = "quick"`, a preview): the trapezoid at NODES with RUNNER_TENDONS (knee and
#   ankle springs), the impacts free, MAX_ITER: a section in 15-18 s a trial, not mesh-converged
#   (above; its notes say so).


@dataclass(frozen=True)
class StrideModel:
    """What compare's strides are built with beyond the body, speed, strike, objective and law
    (problem.StrideSettings' fields of the same names)."""

    nodes: int
    transcription: str
    tendons: dict  # N m/rad per kg, by joint (none at zero)
    max_iter: int  # IPOPT's iterations, at most
    impact_weight: float = 0.0  # 1/m
    approach_speed: float = 0.0  # m/s
    moment_time: float = 0.0  # s


STRIDE_MODELS = {
    "quick": StrideModel(NODES, TRANSCRIPTION, RUNNER_TENDONS, MAX_ITER),
    "scenes": StrideModel(RUNNER_NODES, RUNNER_TRANSCRIPTION, RUNNER_ANKLE, StrideSettings.max_iter,
                          RUNNER_IMPACT_WEIGHT, APPROACH_SPEED, MOMENT_TIME),
}
STRIDE_MODEL = "scenes"


def stride_scene(body: Body, speed: float, strike: str, objective: str = "effort",
                 friction: float = 0.8, law: str = "no-slip", nodes: int | None = None,
                 starts: int = 1, name: str = "stride", tendons: dict | None = None,
                 transcription: str | None = None, model: str = STRIDE_MODEL) -> StrideScene:
    """A level-ground stride scene of `body` at `speed` (m/s), one strike and objective, the
    cadence free (stride_map.cadence_curve imposes it), built as `model` (STRIDE_MODELS) builds
    it; `nodes` (the intervals), `transcription` and the stance leg's `tendons` ({} for none)
    over the model's where given."""
    own = STRIDE_MODELS[model]
    settings = StrideSettings(strike=strike, objective=objective, nodes=nodes or own.nodes, law=law,
                              transcription=transcription or own.transcription, max_iter=own.max_iter,
                              tendons=dict(own.tendons if tendons is None else tendons),
                              impact_weight=own.impact_weight, approach_speed=own.approach_speed,
                              moment_time=own.moment_time)
    return StrideScene(name, body, speed, 0.0, friction, strike, settings, None, starts)


def model_of(settings: StrideSettings) -> str | None:
    """The name of the STRIDE_MODELS entry whose settings these are (None: another model; a
    spring at zero is none)."""
    def own(value):
        return springs(value) if isinstance(value, dict) else value

    return next((name for name, m in STRIDE_MODELS.items()
                 if all(own(getattr(settings, f.name)) == own(getattr(m, f.name)) for f in fields(m))), None)


def with_body(scene: StrideScene, body: Body) -> StrideScene:
    """The scene with another body."""
    return replace(scene, body=body)


def joint_work(stride: Stride) -> dict[str, dict[str, float]]:
    """Positive and negative work (J) of each joint moment over the half stride, from the
    solution's moments tau_j (N m, extensor positive) and extension rates:

        P_j = -tau_j theta_j'  (W),  W+_j = int max(P_j, 0) dt,  W-_j = int max(-P_j, 0) dt

    by the trapezoidal rule on the nodes (the transcription's quadrature; a phase boundary's
    repeated time adds nothing). Keys: JOINTS (hip_R ... ankle_L), and per joint name the
    stance leg R during the stance phases ("stance_knee" ...), Heiderscheit's absorption."""
    power = -stride.tau * stride.thetad[:, 3:]
    stance = np.array([p != "flight" for p in stride.phase])

    def work(p, where=None):
        p = p if where is None else np.where(where, p, 0.0)
        return {"positive_J": float(np.trapezoid(np.maximum(p, 0), stride.t)),
                "negative_J": float(np.trapezoid(np.maximum(-p, 0), stride.t))}

    out = {j: work(power[:, k]) for k, j in enumerate(JOINTS)}
    for k, j in enumerate(JOINTS[:3]):
        out["stance_" + j[:-2]] = work(power[:, k], stance)
    return out


def placement_m(stride: Stride) -> float:
    """How far ahead of the hip the striking point lands at touchdown (m, along the ground)."""
    return -stride.touchdown["hip_from_strike_m"]["ahead"]
