"""Stride scenes: a `[stride]` table instead of a touchdown (issue 23).

    [scene]   name
    [body]    preset = "paper", or mass (kg) and height (m) (scene.py's [body])
    [ground]  friction, slope_deg, contact ("no-slip" or "coulomb": the impacts' law)
    [stride]  speed_mps, strike ("heel", "forefoot", "flat" or "best"), objective ("effort",
              "work", "metabolic"), nodes, impact_weight, torque_limit_nm_per_kg,
              cadence_spm (imposed; absent: free), max_iterations, starts (the generic guess
              and starts - 1 perturbations of it, the best kept; default 4),
              [stride.duration_s] heel/flat/forefoot/flight = [low, high] (s)

Every error names its key (SceneError, one line); degrees at this edge, SI inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..mechanics.body import Body
from ..optim.stride.problem import NODE_SHARE, OBJECTIVES, STRIKES, StrideSettings
from .scene import SceneError, _body, _choice, _integer, _keys, _number, _pair, _string, _table

STRIDE_STRIKES = (*STRIKES, "best")
STRIDE_LAWS = ("no-slip", "coulomb")
STRIDE_KEYS = {"speed_mps", "strike", "objective", "nodes", "impact_weight",
               "torque_limit_nm_per_kg", "cadence_spm", "max_iterations", "duration_s", "starts"}


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

    def for_strike(self, strike: str) -> StrideSettings:
        """The settings of one strike."""
        return replace(self.settings, strike=strike)

    def _other_command(self, *args, **kwargs):
        raise SceneError("stride", "a stride scene: run `formopt stride` (impact, simulate and "
                                   "solve need a [touchdown])")

    # the touchdown commands' factories (io.scene.Scene): a clear error, not an AttributeError
    model = impact = landing = posture_problem = _other_command


def parse(data: dict, path: str = "") -> StrideScene:
    """Validate a stride scene given as a dictionary (the parsed TOML)."""
    _keys(data, "", {"scene", "body", "ground", "stride"}, ("scene", "stride"))
    scene = _table(data, "scene", {"name", "model"}, {"name"})
    name = _string(scene, "name", "scene")
    body, notes = _body(data.get("body", {"preset": "paper"}), "full-body")
    ground = data.get("ground", {"friction": 0.8})
    ground = _table({"ground": ground}, "ground", {"friction", "slope_deg", "contact"}, {"friction"})
    friction = _number(ground, "friction", "ground", low=0.0, high=5.0, low_open=True)
    law = _choice(ground.get("contact", "no-slip"), "ground.contact", STRIDE_LAWS)
    slope = _number(ground, "slope_deg", "ground", default=0.0, low=-20.0, high=20.0)
    stride = _table(data, "stride", STRIDE_KEYS, {"speed_mps"})
    speed = _number(stride, "speed_mps", "stride", low=1.0, high=8.0)
    strike = _choice(stride.get("strike", "heel"), "stride.strike", STRIDE_STRIKES)
    objective = _choice(stride.get("objective", "effort"), "stride.objective", OBJECTIVES)
    nodes = _integer(stride, "nodes", "stride", default=40, low=20, high=400)
    weight = _number(stride, "impact_weight", "stride", default=0.0, low=0.0, high=1e3)
    torque = _number(stride, "torque_limit_nm_per_kg", "stride", default=4.0, low=0.5, high=20.0)
    cadence = _number(stride, "cadence_spm", "stride", low=60.0, high=300.0) \
        if "cadence_spm" in stride else None
    max_iter = _integer(stride, "max_iterations", "stride", default=1000, low=1, high=100000)
    starts = _integer(stride, "starts", "stride", default=4, low=1, high=100)
    duration = dict(StrideSettings().duration)
    if "duration_s" in stride:
        given = _table(stride, "duration_s", set(NODE_SHARE), set(), "stride")
        for phase in given:
            low, high = _pair(given, phase, "stride.duration_s", limit=2.0)
            if not 0 < low < high:
                raise SceneError(f"stride.duration_s.{phase}", f"must be 0 < low < high, not "
                                                               f"[{low:g}, {high:g}]")
            duration[phase] = (low, high)
    settings = StrideSettings(strike="heel" if strike == "best" else strike, objective=objective,
                              nodes=nodes, law=law, impact_weight=weight, torque_limit=torque,
                              duration=duration, max_iter=max_iter)
    return StrideScene(name, body, speed, math.radians(slope), friction, strike, settings,
                       cadence, starts, path, notes)
