"""Scene files (TOML): what is studied, validated at the boundary.

Every error is a SceneError (io.validate.ValidationError) naming the file, the key
(`touchdown.angles_deg.knee`), the value and the allowed range (mechanics.limits); nothing
invalid reaches the mechanics. Degrees at this edge, SI inside.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ..mechanics import body as bodies
from ..mechanics import limits
from ..mechanics.body import Body, Segment
from ..mechanics.contact import LAWS
from ..mechanics.dynamics import JOINT_MODELS, Joints
from ..mechanics.impact import GRAPHS, Impact
from ..mechanics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from ..mechanics.landing import RUNNING_JOINTS, LandingModel
from ..mechanics.model import MODELS, STATE, STRIKES, Model, Swing, build_model
from ..optim.objective import OBJECTIVES, STANCE_PEAK_BW
from ..optim.posture import Gait, Inadmissible, PostureProblem, Problem, admissible
from . import validate as val

if TYPE_CHECKING:  # io.stride_scene builds on this module's readers (imported where parsed)
    from .stride_scene import StrideScene

# The segments each model needs; a segment a model does not use may be given and is ignored.
# Shank + foot keeps the thigh's geometry: the touchdown state moves the knee through it.
# The swing leg is optional (no mass when not given).
MODEL_SEGMENTS = {"effective-mass": ("thigh", "shank", "foot"),
                  "shank-foot": ("thigh", "shank", "foot"),
                  "leg": ("trunk", "swing_leg", "thigh", "shank", "foot"),
                  "leg-trunk": ("trunk", "swing_leg", "thigh", "shank", "foot"),
                  "full-body": ("trunk", "thigh", "shank", "foot")}
OPTIONAL_SEGMENTS = ("swing_leg",)
ANGLES = ("trunk", "hip", "knee", "ankle")
RATES = ("trunk", "thigh", "shank", "foot")

# A scene that cannot be used: `key` names the offending entry (io.validate, one line).
SceneError = val.ValidationError


@dataclass(frozen=True)
class Numerics:
    """Speed against accuracy ([numerics]); every factory of Scene passes each option on."""

    graph: str = "SX"  # CasADi graph of the impact map: "SX" scalar or "MX" matrix expressions
    # generate C, compile (cached by content) and call it: True, False, or "auto" (where it
    # pays: the per-step functions of a sweep's many landings, not one landing, the impact map
    # or the NLP; landing_spring.toml: 1.8 ms a landing compiled against 3.2 ms interpreted,
    # but 0.1 s to generate and load the library even when it is cached, seconds to compile)
    compiled: bool | str = "auto"
    hessian: str = "auto"  # IPOPT: "exact", "limited-memory", or "auto" (exact for impacts)
    integrator: str = DEFAULT_INTEGRATOR  # the landing's integrator (mechanics.integrators)


@dataclass(frozen=True)
class Integration:
    """The landing's time grid ([landing]), SI."""

    dt: float = 1e-3  # s, the fixed integrators' step, the adaptive one's largest
    duration: float = 0.2  # s, longest landing simulated


@dataclass(frozen=True)
class Scene:
    """A validated scene in SI units: the body, the model level, the touchdown, the ground.

    The factories (`model`, `impact`, `landing`, `posture_problem`) are the one path from a
    scene to a computation: each honours every [numerics] option.
    """

    name: str
    kind: str  # the model level (model.MODELS)
    body: Body
    strike: str
    state: np.ndarray  # model.STATE, SI
    friction: float
    slope: float  # rad, positive uphill
    path: str = ""
    notes: tuple[str, ...] = field(default=())  # what the loader did that a user should know
    problem: Problem | None = None  # the [optimize] table, when there is one
    joints: Joints = Joints()  # the [joints] table: the joint model of the landing
    integration: Integration = Integration()  # the [landing] table
    swing: Swing | None = None  # the swing leg's posture (model "full-body")
    numerics: Numerics = Numerics()  # the [numerics] table
    contact: str = "no-slip"  # [ground].contact: the contact law at the impact (contact.LAWS)

    def model(self) -> Model:
        """The model the scene asks for (only its segments, contacts and swing posture)."""
        return build_model(self.body, self.kind, self.strike, self.swing)

    def impact(self) -> Impact:
        """The impact map of the scene's touchdown (graph and compilation from [numerics])."""
        return Impact(self.model(), self.strike, self.slope, self.friction,
                      compiled=self.numerics.compiled is True, graph=self.numerics.graph,
                      law=self.contact)

    def landing(self, many: bool = False) -> LandingModel:
        """The landing equations (joints, ground, integrator and compilation from the scene);
        `many`: for many landings (a sweep), where compiling pays under numerics.compiled
        "auto" (Numerics)."""
        compiled = self.numerics.compiled is True or (self.numerics.compiled == "auto" and many)
        return LandingModel(self.model(), self.joints, self.slope, compiled,
                            self.numerics.integrator, self.contact)

    def posture_problem(self, **overrides) -> PostureProblem:
        """The posture NLP of the [optimize] table; `overrides` replace Problem fields."""
        if self.problem is None:
            raise SceneError("optimize", "missing: the scene has nothing to optimise")
        problem = replace(self.problem, **{k: v for k, v in overrides.items() if v is not None})
        n = self.numerics
        return PostureProblem(self.model(), self.strike, self.state, problem, self.slope,
                              self.friction, joints=self.joints, duration=self.integration.duration,
                              graph=n.graph, compiled=n.compiled is True, hessian=n.hessian,
                              integrator=n.integrator, law=self.contact)

    @property
    def touchdown(self) -> dict:
        """The touchdown in the scene file's schema (degrees)."""
        return touchdown_table(self.strike, self.state)


def touchdown_table(strike: str, state) -> dict:
    """A touchdown state (model.STATE, SI) in the scene file's [touchdown] schema."""
    s = dict(zip(STATE, (float(v) for v in state)))
    return {"strike": strike,
            "hip_velocity": [s["hip_vx"], s["hip_vz"]],
            "angles_deg": {k: math.degrees(s[k]) for k in ANGLES},
            "angular_velocity_dps": {k: math.degrees(s["omega_" + k]) for k in RATES}}


def load(path) -> Scene | StrideScene:
    """Read and validate a scene file; an error names the file and the key."""
    data = val.read_toml(path, "a scene")
    try:
        return parse(data, str(path))
    except SceneError as err:
        raise err.in_file(path) from None


def landing_scene(scene: Scene | StrideScene, command: str) -> Scene:
    """`scene` if it has a [touchdown] (impact, simulate, solve, sweep, bench need one); a
    stride scene is refused in one line naming the command that takes it."""
    if isinstance(scene, Scene):
        return scene
    raise SceneError("stride", f"a stride scene ({scene.path or scene.name}): `{command}` needs a "
                               "[touchdown]; run `formopt stride` on it")


def parse(data: dict, path: str = "") -> Scene | StrideScene:
    """Validate a scene given as a dictionary (the parsed TOML); one with a [stride] table is
    a stride scene (io/stride_scene.py, imported here: it builds on this module's readers)."""
    if isinstance(data, dict) and "stride" in data:
        from .stride_scene import parse as parse_stride
        return parse_stride(data, path)
    val.keys(data, "", {"scene", "body", "touchdown", "ground", "optimize", "joints", "landing",
                     "numerics"}, ("scene", "touchdown", "ground"))
    scene = val.table(data, "scene", {"name", "model"}, {"name"})
    name = val.string(scene, "name", "scene")
    model = val.choice(scene.get("model", "leg"), "scene.model", MODELS)
    body, notes = _body(data.get("body", {}), model)
    touchdown = val.table(data, "touchdown", {"strike", "hip_velocity", "angles_deg", "angular_velocity_dps",
                                           "swing_angles_deg", "swing_velocity_dps"},
                       ("strike", "hip_velocity", "angles_deg", "angular_velocity_dps"))
    strike, state = _touchdown(touchdown)
    swing = _swing(touchdown) if model == "full-body" else None
    for key in ("swing_angles_deg", "swing_velocity_dps"):
        if key in touchdown and model != "full-body":
            notes += (f"touchdown.{key} is only used by model 'full-body' and was ignored",)
    ground = val.table(data, "ground", {"friction", "slope_deg", "contact"}, {"friction"})
    friction = val.number(ground, "friction", "ground", limit=limits.FRICTION)
    contact_law = val.choice(ground.get("contact", "no-slip"), "ground.contact", LAWS)
    slope = val.number(ground, "slope_deg", "ground", default=0.0, limit=limits.SLOPE_DEG)
    problem = None
    if "optimize" in data:
        problem = _optimize(data["optimize"], model, strike, contact_law)
    joints = _joints(data.get("joints", {}), model, body.mass)
    landing = _landing(data.get("landing", {}))
    if model == "effective-mass" and ((problem and problem.landing) or data.get("joints")):
        raise SceneError("scene.model", "'effective-mass' is an impact-only model: no [joints], "
                                        "landing or T_c_total")
    return Scene(name, model, body, strike, state, friction, math.radians(slope), path, notes,
                 problem, joints, landing, swing, _numerics(data.get("numerics", {})), contact_law)


def _numerics(data) -> Numerics:
    """Speed against accuracy: CasADi graph, compiled or not, IPOPT's Hessian, the landing's
    integrator. hessian "auto": exact for impacts, limited-memory through a landing."""
    if not isinstance(data, dict):
        raise SceneError("numerics", "must be a table")
    val.keys(data, "numerics", {"graph", "compiled", "hessian", "integrator"}, set())
    default = Numerics()
    compiled = data.get("compiled", default.compiled)
    if not isinstance(compiled, bool) and compiled != "auto":
        raise SceneError("numerics.compiled", f"must be true, false or \"auto\", not {val.short(compiled)}")
    return Numerics(val.choice(data.get("graph", default.graph), "numerics.graph", GRAPHS), compiled,
                    val.choice(data.get("hessian", default.hessian), "numerics.hessian",
                            ("auto", "exact", "limited-memory")),
                    val.choice(data.get("integrator", default.integrator), "numerics.integrator",
                            INTEGRATORS))


def _swing(data) -> Swing:
    where = "touchdown"
    angles = val.table(data, "swing_angles_deg", {"hip", "knee", "ankle"}, ("hip", "knee", "ankle"), where)
    rates = val.table(data, "swing_velocity_dps", {"thigh", "shank", "foot"}, ("thigh", "shank", "foot"), where)
    a = {k: math.radians(val.number(angles, k, f"{where}.swing_angles_deg", limit=limits.ANGLE_DEG))
         for k in ("hip", "knee", "ankle")}
    w = {k: math.radians(val.number(rates, k, f"{where}.swing_velocity_dps", limit=limits.RATE_DPS))
         for k in ("thigh", "shank", "foot")}
    return Swing(a["hip"], a["knee"], a["ankle"], w["thigh"], w["shank"], w["foot"])


# -- landing ----------------------------------------------------------------------------

MODEL_JOINTS = {"effective-mass": (), "shank-foot": ("ankle",), "leg": ("knee", "ankle"),
                "leg-trunk": ("hip", "knee", "ankle"),
                "full-body": ("hip", "knee", "ankle", "swing_hip", "swing_knee", "swing_ankle")}


JOINT_KEYS = {"model", "stiffness_nm_per_deg", "damping_nms_per_deg", "preload_nm", "locked",
              "moments"}
SPRING_KEYS = ("stiffness_nm_per_deg", "damping_nms_per_deg", "preload_nm")


def _joints(data, model, mass) -> Joints:
    """[joints]: the landing's joint model. Spring-damper values not given take the running
    defaults scaled to the body's mass (landing.RUNNING_JOINTS), within limits.JOINT_LIMITS."""
    if not isinstance(data, dict):
        raise SceneError("joints", "must be a table")
    val.keys(data, "joints", JOINT_KEYS, set())
    kind = val.choice(data.get("model", "spring-damper"), "joints.model", JOINT_MODELS)
    names = MODEL_JOINTS[model]
    for key in (*SPRING_KEYS, "locked", "moments"):
        wanted = "locked" if key == "locked" else "torque" if key == "moments" else "spring-damper"
        if key in data and kind != wanted:
            raise SceneError(f"joints.{key}", f"only for joints.model = \"{wanted}\", not {kind!r}")
    if not names:
        return Joints(kind)
    if kind == "spring-damper":
        values = {}
        for key, what in zip(SPRING_KEYS, ("stiffness", "damping", "preload")):
            table = val.table(data, key, set(names), set(), "joints") if key in data else {}
            high = limits.JOINT_LIMITS[what] * mass
            values[key] = {j: val.number(table, j, f"joints.{key}", low=-high if what == "preload" else 0.0,
                                      high=high, default=RUNNING_JOINTS[what].get(j, 0.0) * mass)
                           for j in names}
        per_deg = math.degrees(1.0)  # N m/deg -> N m/rad
        return Joints(kind, {j: v * per_deg for j, v in values["stiffness_nm_per_deg"].items()},
                      {j: v * per_deg for j, v in values["damping_nms_per_deg"].items()},
                      preload=values["preload_nm"])
    if kind == "torque":
        return _torque_joints(data, names)
    if kind == "locked":
        locked = data.get("locked", list(names))
        if not isinstance(locked, list) or not locked:
            raise SceneError("joints.locked", f"must be a non-empty list of {', '.join(names)}")
        for j in locked:
            val.choice(j, "joints.locked", names)
        return Joints(kind, locked=tuple(locked))
    return Joints(kind)


TIME_MS = limits.Range(-1e4, 1e4, "ms")  # a prescribed moment's time: a landing lasts < 2 s


def _torque_joints(data, names) -> Joints:
    """[joints.moments]: time_ms (increasing, from 0) and <joint>_nm columns of the same
    length, extensor / plantarflexor positive, linear between samples."""
    allowed = {"time_ms"} | {f"{j}_nm" for j in names}
    table = val.table(data, "moments", allowed, {"time_ms"}, "joints")
    columns = {}
    for key in sorted(table):
        column = table[key]
        if not isinstance(column, list) or len(column) < 2:
            raise SceneError(f"joints.moments.{key}", "must be a list of at least two numbers")
        r = TIME_MS if key == "time_ms" else limits.JOINT_MOMENT_NM
        columns[key] = [val.value(v, f"joints.moments.{key}[{i}]", r.low, r.high, unit=r.unit)
                        for i, v in enumerate(column)]
    times = columns.pop("time_ms")
    if times[0] != 0.0 or any(b <= a for a, b in itertools.pairwise(times)):
        raise SceneError("joints.moments.time_ms", "must start at 0 (the touchdown) and increase")
    if not columns:
        raise SceneError("joints.moments", f"missing: give a moment column ({', '.join(sorted(allowed - {'time_ms'}))})")
    for key, column in columns.items():
        if len(column) != len(times):
            raise SceneError(f"joints.moments.{key}", f"has {len(column)} values for "
                                                      f"{len(times)} times")
    return Joints("torque", times=tuple(t * 1e-3 for t in times),
                  moments={key[:-3]: tuple(column) for key, column in columns.items()})


def _landing(data) -> Integration:
    if not isinstance(data, dict):
        raise SceneError("landing", "must be a table")
    val.keys(data, "landing", {"dt_ms", "duration_ms"}, set())
    default = Integration()
    return Integration(
        val.number(data, "dt_ms", "landing", default=default.dt * 1e3,
                   limit=limits.LANDING_DT_S.scaled(1e3, "ms")) * 1e-3,
        val.number(data, "duration_ms", "landing", default=default.duration * 1e3,
                   limit=limits.LANDING_DURATION_S.scaled(1e3, "ms")) * 1e-3)


# -- optimize ---------------------------------------------------------------------------

OPTIMIZE_KEYS = {"variables", "objective", "bounds_deg", "bounds_dps", "starts", "seed",
                 "tolerance", "max_overstride_m", "hip_height_m", "contact_friction",
                 "max_iterations", "max_slip_mps", "gait", "around", "radius_deg", "stance_peak_bw"}
GAIT_KEYS = {"hip_from_strike_m", "foot_velocity_mps", "cadence_spm"}
HIP_MODELS = ("leg", "leg-trunk", "full-body")  # models with a thigh: a hip to place
RATE_VARIABLES = tuple("omega_" + r for r in RATES)


def _optimize(data, model, strike, law) -> Problem:
    """[optimize]: the posture problem (variables and bounds, objective, multi-start, limits,
    gait, local mode), with what the model, strike and contact law admit."""
    if not isinstance(data, dict):
        raise SceneError("optimize", "must be a table")
    val.keys(data, "optimize", OPTIMIZE_KEYS, ("variables", "objective"))
    variables, lower, upper = _variables(data, model, strike)
    objective = _objective(data["objective"])
    starts = val.integer(data, "starts", "optimize", 8, int(limits.STARTS.low), int(limits.STARTS.high))
    seed = val.integer(data, "seed", "optimize", 0, int(limits.SEED.low), int(limits.SEED.high))
    tolerance = val.number(data, "tolerance", "optimize", default=1e-8, limit=limits.TOLERANCE)
    overstride = (val.number(data, "max_overstride_m", "optimize", low=-2.0, high=2.0)
                  if "max_overstride_m" in data else None)
    hip_height = None
    if "hip_height_m" in data:
        hip_height = val.pair(data, "hip_height_m", "optimize", limit=3.0)
        if hip_height[0] >= hip_height[1]:
            raise SceneError("optimize.hip_height_m", "the lower height must be below the upper")
    contact_friction = val.flag(data, "contact_friction", "optimize", False)
    max_iterations = val.integer(data, "max_iterations", "optimize", 200,
                                 int(limits.MAX_ITERATIONS.low), int(limits.MAX_ITERATIONS.high))
    max_slip = None
    if "max_slip_mps" in data:
        max_slip = val.number(data, "max_slip_mps", "optimize", low=0.0, high=100.0)
    gait = _gait(data["gait"], model) if "gait" in data else None
    radius = None
    if "around" in data or "radius_deg" in data:
        if data.get("around", "reference") != "reference":
            raise SceneError("optimize.around", f"must be \"reference\" (the scene's touchdown), "
                                                f"not {val.short(data['around'])}")
        radius = math.radians(val.number(data, "radius_deg", "optimize", default=5.0, low=0.0,
                                         high=90.0, low_open=True))
    if "support" in objective and model not in HIP_MODELS:
        raise SceneError("optimize.objective.support", f"the stance's support needs a knee and a "
                                                       f"hip: scene.model {', '.join(HIP_MODELS)}")
    peak = val.number(data, "stance_peak_bw", "optimize", default=STANCE_PEAK_BW, low=0.5, high=10.0)
    problem = Problem(variables, lower, upper, objective, overstride, hip_height,
                      starts, seed, tolerance, contact_friction, max_iterations, max_slip, gait,
                      radius, peak)
    try:
        admissible(law, strike, problem)
    except Inadmissible as err:
        raise SceneError(err.key, err.reason) from None
    return problem


def _variables(data, model, strike) -> tuple[tuple, tuple, tuple]:
    """optimize.variables and their bounds: (names, lower, upper), SI. Angles default to the
    joint's range of motion and may not leave it; rates need their bounds_dps."""
    variables = data["variables"]
    allowed = ANGLES + RATE_VARIABLES
    if not isinstance(variables, list) or not variables:
        raise SceneError("optimize.variables", f"must be a non-empty list of {', '.join(allowed)}")
    for v in variables:
        val.choice(v, "optimize.variables", allowed)
    if len(set(variables)) != len(variables):
        raise SceneError("optimize.variables", "lists a variable twice")
    if "trunk" in variables and model != "leg-trunk":
        raise SceneError("optimize.variables", "'trunk' needs scene.model = \"leg-trunk\": the "
                                               "paper's leg has a point-mass trunk whose angle does not matter")
    bounds_deg = val.table(data, "bounds_deg", set(ANGLES), set(), "optimize") if "bounds_deg" in data else {}
    bounds_dps = val.table(data, "bounds_dps", set(RATES), set(), "optimize") if "bounds_dps" in data else {}
    lower, upper = [], []
    for v in variables:
        if v in ANGLES:
            lo, hi = (val.joint_bounds(bounds_deg[v], f"optimize.bounds_deg.{v}", v)
                      if v in bounds_deg else limits.RANGE_OF_MOTION_DEG[v])
        else:
            rate = v.removeprefix("omega_")
            if rate not in bounds_dps:
                raise SceneError(f"optimize.bounds_dps.{rate}", f"missing (variable {v!r} needs bounds)")
            lo, hi = val.pair(bounds_dps, rate, "optimize.bounds_dps", limit=limits.RATE_DPS.high)
            if lo >= hi:
                raise SceneError(f"optimize.bounds_dps.{rate}", f"lower bound {lo:g} must be below the upper {hi:g}")
        lower.append(math.radians(lo))
        upper.append(math.radians(hi))
    return tuple(variables), tuple(lower), tuple(upper)


def _objective(objective) -> dict:
    """optimize.objective: a name (weight 1) or a table of weights, at least one non-zero."""
    if isinstance(objective, str):
        objective = {val.choice(objective, "optimize.objective", OBJECTIVES): 1.0}
    elif isinstance(objective, dict):
        val.keys(objective, "optimize.objective", set(OBJECTIVES), set())
        objective = {k: val.number(objective, k, "optimize.objective", limit=limits.OBJECTIVE_WEIGHT)
                     for k in objective}
        if not any(objective.values()):
            raise SceneError("optimize.objective", "needs at least one non-zero weight")
    else:
        raise SceneError("optimize.objective", f"must be one of {', '.join(OBJECTIVES)} or a table "
                                               "of weights, e.g. { T_c = 1.0, dv_trunk_x = 20.0 }")
    return objective


def _gait(data, model) -> Gait:
    """[optimize.gait]: the hip's place over the strike point (absent: the touchdown's), the
    foot's speed along the ground, the cadence."""
    if not isinstance(data, dict):
        raise SceneError("optimize.gait", "must be a table")
    val.keys(data, "optimize.gait", GAIT_KEYS, set())
    if model not in HIP_MODELS:
        raise SceneError("optimize.gait", f"places the hip over the strike point: scene.model "
                                          f"{', '.join(HIP_MODELS)}, not {model!r}")
    place = None
    if "hip_from_strike_m" in data:
        value = data["hip_from_strike_m"]
        key = "optimize.gait.hip_from_strike_m"
        if not (isinstance(value, list) and len(value) == 2):
            raise SceneError(key, "must be [x, z] in m: x forward along the ground (a foot landing "
                                  "ahead of the hip gives x < 0), z normal to it")
        place = (val.value(value[0], key, -1.5, 1.5), val.value(value[1], key, 0.1, 2.0))
    velocity = (val.number(data, "foot_velocity_mps", "optimize.gait", low=-20.0, high=20.0)
                if "foot_velocity_mps" in data else None)
    cadence = (val.number(data, "cadence_spm", "optimize.gait", limit=limits.CADENCE_SPM)
               if "cadence_spm" in data else None)
    return Gait(place, velocity, cadence)


# -- body -------------------------------------------------------------------------------

SEGMENT_KEYS = {
    "trunk": {"mass", "length", "com", "inertia_proximal", "inertia_com"},
    "swing_leg": {"mass"},
    "thigh": {"mass", "length", "com", "inertia_proximal", "inertia_com"},
    "shank": {"mass", "length", "com", "inertia_proximal", "inertia_com"},
    "foot": {"mass", "com", "inertia_com", "inertia_proximal", "heel", "forefoot"},
}


def _body(data, model) -> tuple[Body, tuple[str, ...]]:
    if not isinstance(data, dict):
        raise SceneError("body", "must be a table")
    val.keys(data, "body", {"preset", "mass", "height", "sex", *bodies.SEGMENTS}, set())
    notes = []
    if "preset" in data:
        for key in ("mass", "height", "sex"):
            if key in data:
                raise SceneError(f"body.{key}", "give either body.preset or body.mass/height, not both")
        val.choice(data["preset"], "body.preset", ("paper",))
        base = bodies.paper_body()
    elif "mass" in data or "height" in data:
        mass = val.number(data, "mass", "body", limit=limits.BODY_MASS_KG)
        height = val.number(data, "height", "body", limit=limits.BODY_HEIGHT_M)
        sex = val.choice(data.get("sex", "male"), "body.sex", tuple(bodies.DE_LEVA))
        base = bodies.scaled_body(mass, height, sex)
    else:
        base = None
    segments = {}
    for name in bodies.SEGMENTS:
        given = data.get(name)
        if given is not None and not isinstance(given, dict):
            raise SceneError(f"body.{name}", "must be a table")
        if name not in MODEL_SEGMENTS[model]:
            if given is not None:
                notes.append(f"body.{name} is not part of model {model!r} and was ignored")
            continue
        if given is None and base is None:
            if name in OPTIONAL_SEGMENTS:
                continue
            raise SceneError(f"body.{name}", f"missing (model {model!r} needs it; or give body.preset "
                                             "or body.mass and body.height)")
        segments[name] = _segment(name, given or {}, base[name] if base else None)
    if model in ("leg-trunk", "full-body") and segments["trunk"].inertia_com <= 0:
        raise SceneError("body.trunk.length", f"model {model!r} needs a rigid trunk: give its "
                                              "length, com and inertia (or a body preset or scaling)")
    source = base.source if base else "scene file"
    if base and any(name in data for name in bodies.SEGMENTS):
        source += ", with segments from the scene file"
    return Body(segments, source), tuple(notes)


def _segment(name, data, base: Segment | None) -> Segment:
    where = f"body.{name}"
    val.keys(data, where, SEGMENT_KEYS[name], set())
    if "inertia_proximal" in data and "inertia_com" in data:
        raise SceneError(f"{where}.inertia_com", "give inertia_proximal or inertia_com, not both")
    values = _segment_values(base) if base else {}
    if {"inertia_proximal", "inertia_com"} & set(data):
        values.pop("inertia_com", None)
    values.update(data)
    point_mass = name == "swing_leg" or (name == "trunk" and set(values) == {"mass"})
    required = {"mass"} if point_mass else SEGMENT_KEYS[name] - {"inertia_proximal", "inertia_com"}
    for key in sorted(required):
        if key not in values:
            raise SceneError(f"{where}.{key}", "missing")
    if not point_mass and not {"inertia_proximal", "inertia_com"} & set(values):
        raise SceneError(f"{where}.inertia_com", "missing (give inertia_com or inertia_proximal)")
    mass = (val.number(values, "mass", where, low=0.0, high=limits.SEGMENT_MASS_KG.high)
            if name == "swing_leg" else val.number(values, "mass", where, limit=limits.SEGMENT_MASS_KG))
    if name == "swing_leg":
        return bodies.swing_leg(mass)
    if point_mass:
        return bodies.trunk(mass)
    if name == "foot":
        com_xy = val.pair(values, "com", where)
        heel, forefoot = val.pair(values, "heel", where), val.pair(values, "forefoot", where)
        if not heel[0] < forefoot[0]:
            raise SceneError(f"{where}.heel", "must lie behind the forefoot (smaller x in the foot frame)")
        if forefoot[0] - heel[0] not in limits.SEGMENT_LENGTH_M:
            raise SceneError(f"{where}.heel", f"heel to forefoot along the sole must be "
                                              f"{limits.SEGMENT_LENGTH_M.text()}, not "
                                              f"{forefoot[0] - heel[0]:g} m")
        proximal = float(np.dot(com_xy, com_xy))
    else:
        length = val.number(values, "length", where, limit=limits.SEGMENT_LENGTH_M)
        com = val.number(values, "com", where, low=0.0, high=length)
        proximal = com**2
    if "inertia_proximal" in values:
        inertia = val.number(values, "inertia_proximal", where, low=0.0, low_open=True) - mass * proximal
        if inertia not in limits.SEGMENT_INERTIA_KGM2:
            raise SceneError(f"{where}.inertia_proximal",
                             f"minus mass * distance^2 to the centre of mass ({mass * proximal:.4g} "
                             f"kg m^2) gives an inertia about the centre of mass of {inertia:.3g}: "
                             f"it must be {limits.SEGMENT_INERTIA_KGM2.text()}")
    else:
        inertia = val.number(values, "inertia_com", where, limit=limits.SEGMENT_INERTIA_KGM2)
    if name == "foot":
        return bodies.foot(mass, com_xy, inertia, heel, forefoot)
    if name == "trunk":
        return bodies.trunk(mass, com, inertia, length)
    return bodies.bar(name, mass, length, com, inertia)


def _segment_values(seg: Segment) -> dict:
    """A segment's data in the scene file's keys."""
    if seg.name == "swing_leg" or (seg.name == "trunk" and "shoulder" not in seg.landmarks):
        return {"mass": seg.mass}
    if seg.name == "trunk":
        return {"mass": seg.mass, "length": seg.landmarks["shoulder"][1], "com": seg.com[1],
                "inertia_com": seg.inertia_com}
    if seg.name == "foot":
        return {"mass": seg.mass, "com": list(seg.com), "inertia_com": seg.inertia_com,
                "heel": list(seg.landmarks["heel"]), "forefoot": list(seg.landmarks["forefoot"])}
    return {"mass": seg.mass, "length": seg.length, "com": -seg.com[1], "inertia_com": seg.inertia_com}


# -- touchdown --------------------------------------------------------------------------

def _touchdown(data) -> tuple[str, np.ndarray]:
    strike = val.choice(data["strike"], "touchdown.strike", tuple(STRIKES))
    velocity = val.pair(data, "hip_velocity", "touchdown", limit=limits.SPEED_LIMIT)
    angles = val.table(data, "angles_deg", set(ANGLES), set(ANGLES), "touchdown")
    rates = val.table(data, "angular_velocity_dps", set(RATES), set(RATES) - {"trunk"}, "touchdown")
    where_a, where_r = "touchdown.angles_deg", "touchdown.angular_velocity_dps"
    a = {k: math.radians(val.number(angles, k, where_a, limit=limits.ANGLE_DEG)) for k in ANGLES}
    w = {k: math.radians(val.number(rates, k, where_r, default=0.0, limit=limits.RATE_DPS))
         for k in RATES}
    values = {**a, "hip_vx": velocity[0], "hip_vz": velocity[1],
              **{"omega_" + k: v for k, v in w.items()}}
    return strike, np.array([values[k] for k in STATE])
