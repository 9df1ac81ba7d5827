"""Stride scenes: a `[stride]` table instead of a touchdown (issue 23).

    [scene]   name
    [body]    preset = "paper", or mass (kg) and height (m) (scene.py's [body])
    [ground]  friction, slope_deg, contact ("no-slip" or "coulomb": the impacts' law)
    [stride]  speed_mps, strike ("heel", "forefoot", "flat" or "best"), actuation ("torque",
              "torque+springs", the default with [stride.tendons], or "muscles":
              optim.stride.problem.ACTUATIONS), objective ("effort", "work", "metabolic",
              "joint-metabolic"; with muscles "metabolic", their default, or "activation"), nodes, impact_weight,
              torque_limit_nm_per_kg (torque rungs),
              cadence_spm (imposed; absent: free), max_iterations, search ("local", the
              default: starts, the generic guess and starts - 1 perturbations of it, the best
              kept, default 4; or "global": optim.stride.search's procedure, its spend
              `spend`, default 1),
              [stride.duration_s] heel/flat/forefoot/flight = [low, high] (s),
              [stride.tendons] hip/knee/ankle = stiffness (N m/rad per kg; the stance leg's
              springs, optim.stride.problem.TENDON_JOINTS; "torque+springs" without it takes
              RUNNER_TENDONS), transcription ("trapezoid", the
              default, or "hermite-simpson": optim.stride.collocation), clearance_m (the
              swing foot's least height while the other foot holds the ground, m; default
              optim.stride.contact.CLEARANCE), mesh_check (true: each strike's stride solved
              again on twice its nodes from itself and what that moved reported,
              optim.stride.refine; default false), force_rate_power (with muscles and
              "metabolic": 2, the default, or 1: optim.stride.problem.FORCE_RATE_POWERS),
              approach_speed_mps (each impact's points reach the ground at least this fast, m/s;
              default 0: optim.stride.problem.APPROACH_SPEED), moment_time_s (the torque rungs'
              moment dynamics' time, s; default 0, moments that jump: optim.stride.problem.MOMENT_TIME),
              torque_velocity (true: the torque rungs' limit falls with the joint's rate as its
              muscles' force does, optim.stride.actuation.Torques.rows; default false)

Every error names its key (SceneError, one line); degrees at this edge, SI inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..mechanics.body import Body
from ..mechanics.errors import InputError
from ..mechanics.muscles import Muscles
from ..optim.stride.collocation import StrideNLP, build
from ..optim.stride.contact import CLEARANCE
from ..optim.stride.problem import (
    ACTUATIONS,
    NODE_SHARE,
    OBJECTIVES,
    RUNNER_TENDONS,
    STRIKES,
    TENDON_JOINTS,
    TRANSCRIPTIONS,
    StrideSettings,
)
from ..optim.stride.ranges import RANGES, point
from ..optim.stride.refine import fine_nodes
from ..optim.stride.search import SEARCHES
from . import validate as val
from .muscle_table import body_muscles
from .scene import SceneError, _body

STRIDE_STRIKES = (*STRIKES, "best")
STRIDE_LAWS = ("no-slip", "coulomb")
STRIDE_KEYS = {"speed_mps", "strike", "objective", "nodes", "impact_weight",
               "torque_limit_nm_per_kg", "cadence_spm", "max_iterations", "duration_s", "starts", "tendons",
               "transcription", "actuation", "clearance_m", "search", "spend", "grading", "mesh_check",
               "force_rate_power", "approach_speed_mps", "moment_time_s", "torque_velocity"}


@dataclass(frozen=True)
class StrideScene:
    """A validated stride scene (SI): the body, the ground, the solve's settings."""

    name: str
    body: Body
    speed: float  # m/s
    slope: float  # rad
    friction: float
    strike: str  # a strike of optim.stride.STRIKE_PHASES, or "best"
    settings: StrideSettings  # of the first strike ("best": heel), the others by replace()
    cadence: float | None  # steps/min, imposed; None: free
    starts: int = 4  # the multi-start's solves per strike (optim.stride.optimum)
    path: str = ""
    notes: tuple[str, ...] = ()
    search: str = "local"  # optim.stride.search.SEARCHES: "local" (`starts`) or "global" (`spend`)
    spend: int = 1  # the global search's spend (optim.stride.search)
    mesh_check: bool = False  # each strike's stride solved again on 2N nodes (optim.stride.refine)

    def for_strike(self, strike: str) -> StrideSettings:
        """The settings of one strike."""
        return replace(self.settings, strike=strike)

    def nlp(self, strike: str | None = None) -> StrideNLP:
        """The stride NLP of the scene's body and settings for `strike` (default: the scene's;
        "best" is no strike, solve each): the one path from a scene to its NLP, built once
        per process (optim.stride.collocation.build)."""
        strike = self.strike if strike is None else strike
        if strike not in STRIKES:
            raise SceneError("stride.strike", f"{strike!r}: an NLP solves one strike "
                                              f"({', '.join(STRIKES)})")
        return build(self.body, self.for_strike(strike))


def _whole(key: str) -> tuple[int, int]:
    """(low, high) of an integer key's range (optim.stride.ranges)."""
    return int(RANGES[key].low), int(RANGES[key].high)


def _actuation(stride: dict, actuation: str, body: Body) -> tuple[dict, Muscles | None]:
    """(tendons, muscles) of the [stride] table's rung (optim.stride.problem.ACTUATIONS):
    "torque+springs" takes [stride.tendons] (default RUNNER_TENDONS), "muscles" gait2d's muscles
    scaled to the body (io.muscle_table.body_muscles)."""
    if "tendons" in stride and actuation != "torque+springs":
        raise SceneError("stride.tendons", f"springs in parallel need actuation 'torque+springs', not {actuation!r}")
    if actuation == "muscles":
        if "torque_limit_nm_per_kg" in stride:
            raise SceneError("stride.torque_limit_nm_per_kg", "the muscles' strength is their own "
                                                              "(io/data/gait2d_muscles.csv): remove the key")
        if "moment_time_s" in stride:
            raise SceneError("stride.moment_time_s", "the torque rungs' moment dynamics: the muscles' moments "
                                                     "rise with their activations: remove the key")
        if "torque_velocity" in stride:
            raise SceneError("stride.torque_velocity", "the torque rungs' torque-velocity limit: the muscles' "
                                                       "force-velocity is their own: remove the key")
        return {}, body_muscles(body)
    if actuation == "torque":
        return {}, None
    given = val.table(stride, "tendons", set(TENDON_JOINTS), set(), "stride") if "tendons" in stride \
        else dict(RUNNER_TENDONS)
    return {j: val.number(given, j, "stride.tendons", limit=RANGES["tendon_nm_per_rad_kg"]) for j in given}, None


def parse(data: dict, path: str = "") -> StrideScene:
    """Validate a stride scene given as a dictionary (the parsed TOML)."""
    val.keys(data, "", {"scene", "body", "ground", "stride"}, ("scene", "ground", "stride"))
    scene = val.table(data, "scene", {"name", "model"}, {"name"})
    name = val.string(scene, "name", "scene")
    body, notes = _body(data.get("body", {"preset": "paper"}), "full-body")
    ground = val.table(data, "ground", {"friction", "slope_deg", "contact"}, {"friction"})
    friction = val.number(ground, "friction", "ground", limit=RANGES["friction"])
    law = val.choice(ground.get("contact", "no-slip"), "ground.contact", STRIDE_LAWS)
    slope = val.number(ground, "slope_deg", "ground", default=0.0, limit=RANGES["slope_deg"])
    stride = val.table(data, "stride", STRIDE_KEYS, {"speed_mps"})
    speed = val.number(stride, "speed_mps", "stride", limit=RANGES["speed_mps"])
    strike = val.choice(stride.get("strike", "heel"), "stride.strike", STRIDE_STRIKES)
    actuation = val.choice(stride.get("actuation", "torque+springs" if "tendons" in stride else "torque"),
                           "stride.actuation", ACTUATIONS)
    objective = val.choice(stride.get("objective", "metabolic" if actuation == "muscles" else "effort"),
                           "stride.objective", OBJECTIVES)
    transcription = val.choice(stride.get("transcription", "trapezoid"), "stride.transcription", TRANSCRIPTIONS)
    nodes = val.integer(stride, "nodes", "stride", 40, *_whole("nodes"))
    grading = val.number(stride, "grading", "stride", default=0.0, limit=RANGES["grading"])
    weight = val.number(stride, "impact_weight", "stride", default=0.0, limit=RANGES["impact_weight"])
    approach = val.number(stride, "approach_speed_mps", "stride", default=0.0, limit=RANGES["approach_speed_mps"])
    moment_time = val.number(stride, "moment_time_s", "stride", default=0.0, limit=RANGES["moment_time_s"])
    velocity = val.flag(stride, "torque_velocity", "stride", default=False)
    torque = val.number(stride, "torque_limit_nm_per_kg", "stride", default=4.0,
                         limit=RANGES["torque_limit_nm_per_kg"])
    cadence = val.number(stride, "cadence_spm", "stride", limit=RANGES["cadence_spm"]) \
        if "cadence_spm" in stride else None
    if cadence is not None:
        try:
            point(speed, cadence)
        except InputError as err:
            raise SceneError("stride.cadence_spm", str(err)) from None
    clearance = val.number(stride, "clearance_m", "stride", default=CLEARANCE, limit=RANGES["clearance_m"])
    max_iter = val.integer(stride, "max_iterations", "stride", 1000, *_whole("max_iterations"))
    search, spend, starts = _search(stride)
    mesh_check = _mesh_check(stride, nodes)
    duration = dict(StrideSettings().duration)
    if "duration_s" in stride:
        given = val.table(stride, "duration_s", set(NODE_SHARE), set(), "stride")
        for phase in given:
            low, high = val.pair(given, phase, "stride.duration_s", limit=RANGES["duration_s"].high)
            if not 0 < low < high:
                raise SceneError(f"stride.duration_s.{phase}", f"must be 0 < low < high, not "
                                                               f"[{low:g}, {high:g}]")
            duration[phase] = (low, high)
    tendons, muscles = _actuation(stride, actuation, body)
    try:
        settings = StrideSettings(strike="heel" if strike == "best" else strike, objective=objective,
                                  nodes=nodes, law=law, impact_weight=weight, torque_limit=torque,
                                  duration=duration, max_iter=max_iter, tendons=tendons,
                                  transcription=transcription, muscles=muscles, clearance=clearance,
                                  grading=grading, force_rate_power=_force_rate_power(stride, objective, muscles),
                                  approach_speed=approach, moment_time=moment_time, torque_velocity=velocity)
    except InputError as err:  # what only the settings check (e.g. a strike's least nodes)
        raise SceneError("stride", str(err)) from None
    return StrideScene(name, body, speed, math.radians(slope), friction, strike, settings,
                       cadence, starts, path, notes, search, spend, mesh_check)


def _search(stride: dict) -> tuple[str, int, int]:
    """(search, spend, starts) of the [stride] table: each search's own key only."""
    search = val.choice(stride.get("search", "local"), "stride.search", SEARCHES)
    if search == "global" and "starts" in stride:
        raise SceneError("stride.starts", "the local search's starts: search = 'global' takes spend instead")
    if search == "local" and "spend" in stride:
        raise SceneError("stride.spend", "the global search's spend: set search = 'global' (the local "
                                         "search takes starts)")
    return (search, val.integer(stride, "spend", "stride", 1, *_whole("spend")),
            val.integer(stride, "starts", "stride", 4, *_whole("starts")))


def _force_rate_power(stride: dict, objective: str, muscles: Muscles | None) -> int:
    """The [stride] table's force_rate_power (optim.stride.problem.FORCE_RATE_POWERS: 2, the
    squared tendon-force rates, or 1, their absolute values), for the muscles' metabolic objective."""
    if "force_rate_power" in stride and (muscles is None or objective != "metabolic"):
        raise SceneError("stride.force_rate_power", "the force-rate term is the muscles' metabolic "
                                                    "objective's: needs actuation 'muscles', objective 'metabolic'")
    return val.integer(stride, "force_rate_power", "stride", 2, 1, 2)


def _mesh_check(stride: dict, nodes: int) -> bool:
    """The [stride] table's mesh_check (true or false); true only where twice the nodes is
    within their range (optim.stride.refine.fine_nodes)."""
    mesh_check = val.flag(stride, "mesh_check", "stride", False)
    if mesh_check:
        try:
            fine_nodes(nodes)
        except InputError as err:
            raise SceneError("stride.mesh_check", str(err)) from None
    return mesh_check
