"""Measured touchdowns against the optimum: the runner's own posture, indicators and the gap.

For each touchdown of a trial (formopt.mocap), the indicators of that landing on the paper's
leg scaled to the runner (de Leva); and the gait-anchored optimum of the mean touchdown of the
dominant strike: the measured hip placement over the strike point, hip velocity, segment
rates and cadence held, hip, knee and ankle free within BOUNDS_DEG (settable), the objective
T_c + support weight * support (optim.objective); then per-joint differences, the saving in J
per step and in W at the measured cadence, and the spread across steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..io import mocap
from ..mechanics.body import Body, scaled_body
from ..mechanics.contact import LAWS
from ..mechanics.impact import Impact, ImpactResult
from ..mechanics.model import STATE, build_model
from ..optim.posture import Gait, PostureProblem, Problem
from ..optim.solution import Optimum
from ..optim.variables import RANGE_OF_MOTION_DEG

JOINTS = ("trunk", "hip", "knee", "ankle")
VARIABLES = ("hip", "knee", "ankle")
# The optimum searches hip, knee and ankle within these bounds (deg; default the joints'
# ranges of motion), the runner's trunk lean, speed and segment rates held at their means.
BOUNDS_DEG = {k: RANGE_OF_MOTION_DEG[k] for k in VARIABLES}
SUPPORT = 0.0  # the support term's weight: T_c alone (README, "What the optimum weighs")


@dataclass
class Comparison:
    steps: mocap.Steps
    axes: str
    results: list[ImpactResult]  # one per touchdown, on the scaled model
    strikes: list[str]  # the impact's strike point per touchdown (heel or forefoot)
    reference: np.ndarray  # mean measured touchdown state of the dominant pattern
    strike: str  # the dominant strike point
    optimum: Optimum
    body: Body
    law: str  # the contact law of `results` and of the optimum (contact.LAWS)
    problem: Problem  # the optimum's: bounds (rad), objective, gait

def impact_strike(td: mocap.Touchdown, kin: mocap.Kinematics) -> str:
    """The foot point that meets the ground first: heel or forefoot (midfoot: the lower)."""
    if td.strike in ("heel", "forefoot"):
        return td.strike
    heel = kin.points[f"{td.side}.heel"][td.frame, 1]
    fore = kin.points[f"{td.side}.forefoot"][td.frame, 1]
    return "heel" if heel <= fore else "forefoot"


def compare(trial: mocap.Trial, static: mocap.Trial, mass: float, height: float,
            sex: str = "male", friction: float = 0.8, starts: int = 4, seed: int = 0,
            law: str = "no-slip", bounds_deg: dict | None = None,
            support: float = SUPPORT) -> Comparison:
    """Every touchdown of `trial` through the impact under `law` (each result also carries
    the other laws, ImpactResult.contact_laws), and the gait-anchored optimum under `law`
    within `bounds_deg` ({joint: (lo, hi)}, deg; missing joints keep BOUNDS_DEG)."""
    cal = mocap.calibrate(static)
    kin = mocap.kinematics(trial, cal)
    steps = mocap.touchdowns(trial, kin, cal)
    if not steps.touchdowns:
        raise mocap.MocapError(f"{trial.source}: no usable touchdown ({'; '.join(steps.left_out)})")
    body = scaled_body(mass, height, sex)
    model = build_model(body, "leg")
    impacts = {s: Impact(model, s, 0.0, friction, law=law) for s in ("heel", "forefoot")}
    strikes = [impact_strike(td, kin) for td in steps.touchdowns]
    results = [impacts[s](td.state()) for s, td in zip(strikes, steps.touchdowns)]
    patterns = [td.strike for td in steps.touchdowns]  # the runner's pattern decides the optimum's
    strike = "heel" if patterns.count("heel") > len(patterns) / 2 else "forefoot"
    chosen = [td for s, td in zip(strikes, steps.touchdowns) if s == strike] or steps.touchdowns
    reference = np.mean([td.state() for td in chosen], axis=0)
    bounds = {**BOUNDS_DEG, **(bounds_deg or {})}
    lower, upper = zip(*(map(math.radians, bounds[v]) for v in VARIABLES))
    objective = {"T_c": 1.0, "support": support} if support else {"T_c": 1.0}
    problem = Problem(VARIABLES, lower, upper, objective, starts=starts, seed=seed,
                      gait=Gait(cadence_spm=steps.cadence_spm))
    optimum = PostureProblem(model, strike, reference, problem, 0.0, friction, law=law).solve()
    return Comparison(steps, cal.axes.describe(), results, strikes, reference, strike, optimum,
                      body, law, problem)


def report(c: Comparison) -> dict:
    """The JSON report (the CLI's --json)."""
    def deg(state):
        return {k: math.degrees(state[STATE.index(k)]) for k in JOINTS}

    touchdowns = [{"time": td.time, "side": td.side, "strike": td.strike, "impact_at": s,
                   "angles_deg": {k: math.degrees(v) for k, v in td.angles.items()},
                   "foot_angle_deg": math.degrees(td.foot_strike_angle),
                   "rates_dps": {k: math.degrees(v) for k, v in td.rates.items()},
                   "hip_velocity": list(td.hip_velocity), "hip_height": td.hip_height,
                   "T_c": r.T_c, "mu_c": r.mu_c, "valid": r.valid,
                   "contact_laws": {law: {k: v[k] for k in ("T_c", "valid", "mode", "slip_velocity")}
                                    for law, v in r.contact_laws.items()}}
                  for td, s, r in zip(c.steps.touchdowns, c.strikes, c.results)]
    opt = c.optimum
    return {
        "law": c.law, "cadence_spm": c.steps.cadence_spm, "belt_speed": c.steps.belt_speed,
        "touchdown_method": c.steps.method, "axes": c.axes, "body": c.body.source,
        "left_out": c.steps.left_out, "notes": c.steps.notes, "touchdowns": touchdowns,
        "summary": summary(c),
        "optimum": {"success": opt.success, "status": opt.status, "verdict": opt.verdict,
                    "strike": c.strike, "law": c.law,
                    "bounds_deg": {v: [math.degrees(lo), math.degrees(hi)] for v, lo, hi in
                                   zip(c.problem.variables, c.problem.lower, c.problem.upper)},
                    "objective_terms": c.problem.objective, "gait": gait(c),
                    "touchdown": {"angles_deg": deg(opt.state), "hip_velocity": list(opt.state[4:6])},
                    "T_c": opt.impact.T_c, "terms": opt.terms, "objective": opt.objective,
                    "held_by": [a.name for a in opt.held_by],
                    "active": [a.name for a in opt.active],
                    "saving_J_per_step": opt.saving, "saving_W": opt.power},
        "reference": {"angles_deg": deg(c.reference), "T_c": opt.reference.T_c,
                      "terms": opt.reference_terms, "objective": opt.reference_objective},
        "difference_deg": {k: v for k, v in zip(JOINTS, np.subtract(
            [deg(opt.state)[k] for k in JOINTS], [deg(c.reference)[k] for k in JOINTS]))},
    }


def gait(c: Comparison) -> dict:
    """What the optimum holds from the measured gait: hip placement (m), velocity, cadence."""
    held = {a.name: a.bound for a in c.optimum.active if a.equality}
    return {"hip_from_strike_m": [held.get("hip_from_strike_x"), held.get("hip_from_strike_z")],
            "hip_velocity": list(c.reference[4:6]), "cadence_spm": c.steps.cadence_spm}


def summary(c: Comparison) -> dict:
    """Mean and standard deviation per side: joint angles, foot strike angle, T_c; and per
    contact law the mean T_c and how many touchdowns are valid under it."""
    out = {}
    for side in mocap.SIDES:
        rows = [(td, r) for td, r in zip(c.steps.touchdowns, c.results) if td.side == side]
        if not rows:
            continue
        angles = np.array([[math.degrees(td.angles[k]) for k in JOINTS] for td, _ in rows])
        T_c = np.array([r.T_c for _, r in rows])
        fsa = np.array([math.degrees(td.foot_strike_angle) for td, _ in rows])
        patterns = [td.strike for td, _ in rows]
        out[side] = {"steps": len(rows),
                     "strike": max(set(patterns), key=patterns.count),
                     "angles_deg_mean": dict(zip(JOINTS, angles.mean(axis=0))),
                     "angles_deg_sd": dict(zip(JOINTS, angles.std(axis=0, ddof=1) if len(rows) > 1
                                               else np.zeros(4))),
                     "foot_angle_deg_mean": float(fsa.mean()), "foot_angle_deg_sd": float(fsa.std(ddof=1)) if len(rows) > 1 else 0.0,
                     "T_c_mean": float(T_c.mean()), "T_c_sd": float(T_c.std(ddof=1)) if len(rows) > 1 else 0.0,
                     "laws": {law: {"T_c_mean": float(np.mean([r.contact_laws[law]["T_c"] for _, r in rows])),
                                    "valid": sum(r.contact_laws[law]["valid"] for _, r in rows)}
                              for law in LAWS}}
    return out
