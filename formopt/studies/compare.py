"""Measured touchdowns against the optimum: the runner's own posture, indicators and the gap.

For each touchdown of a trial (measure.measure), the indicators of that landing on the
paper's leg scaled to the runner (de Leva); the gait-anchored optimum of the mean touchdown of
the dominant strike (the measured hip placement over the strike point, hip velocity, segment
rates and cadence held; hip, knee and ankle free within `bounds_deg`, default the ranges of
motion; objective T_c + support weight * support, optim.objective); and the same optimum for
every step of that strike, each anchored at its own placement (one NLP: the reference
touchdown is a parameter). Only touchdowns with sound markers (valid_data) enter the means.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..io import mocap
from ..io.markerset import SIDES
from ..measure import Measurement, Options, Steps, Touchdown, measure
from ..measure.filters import effective_cutoff
from ..mechanics.body import Body, scaled_body
from ..mechanics.contact import LAWS
from ..mechanics.impact import Impact, ImpactResult
from ..mechanics.model import STATE, build_model
from ..optim.posture import Gait, PostureProblem, Problem
from ..optim.solution import CONVERGED, Optimum
from ..optim.variables import RANGE_OF_MOTION_DEG

JOINTS = ("trunk", "hip", "knee", "ankle")
SEGMENTS = ("trunk", "thigh", "shank", "foot")
VARIABLES = ("hip", "knee", "ankle")
# The optimum searches hip, knee and ankle within these bounds (deg; default the joints'
# ranges of motion), the runner's trunk lean, speed and segment rates held at their means.
BOUNDS_DEG = {k: RANGE_OF_MOTION_DEG[k] for k in VARIABLES}
SUPPORT = 0.0  # the support term's weight: T_c alone (README, "What the optimum weighs")


@dataclass(frozen=True)
class StepOptimum:
    """The optimum of one measured step, its gait held (J per step)."""

    success: bool
    status: str
    state: np.ndarray  # touchdown state (model.STATE, SI)
    objective: float  # at the optimum
    measured: float  # the objective at the step's own posture

    @property
    def saving(self) -> float:
        return self.measured - self.objective


@dataclass
class Comparison:
    measurement: Measurement
    results: list[ImpactResult]  # one per touchdown, on the scaled model
    strikes: list[str]  # the impact's strike point per touchdown (heel or forefoot)
    reference: np.ndarray  # mean measured touchdown state of the dominant pattern (valid steps)
    strike: str  # the dominant strike point
    optimum: Optimum
    body: Body
    law: str  # the contact law of `results` and of the optima (contact.LAWS)
    problem: Problem  # the optimum's: bounds (rad), objective, gait
    settings: dict  # every setting that made this comparison (to_dict()["settings"])
    per_step: dict[int, StepOptimum] = field(default_factory=dict)  # touchdown index -> optimum
    hip_from_strike: tuple[float, float] = (0.0, 0.0)  # m, the mean touchdown's placement

    @property
    def steps(self) -> Steps:
        return self.measurement.steps

    def to_dict(self) -> dict:
        """JSON-ready dictionary (README, "Measured touchdowns"): the settings, the measurement,
        every touchdown, the per-side summary, the optimum of the mean touchdown against it,
        the per-step optima."""
        opt, cal, st = self.optimum, self.measurement.calibration, self.steps
        optimum, reference = _angles_deg(opt.state), _angles_deg(self.reference)
        return {
            "settings": self.settings, "source": self.measurement.trial.source,
            "law": self.law, "cadence_spm": st.cadence_spm, "belt_speed": st.belt_speed,
            "speed": st.speed, "touchdown_method": st.method, "axes": cal.axes.describe(),
            "segment_lengths_m": cal.lengths, "body": self.body.source,
            "touchdowns_total": len(st.touchdowns), "touchdowns_valid_data": len(st.valid),
            "left_out": st.left_out, "notes": st.notes,
            "touchdowns": [touchdown_row(self, k) for k in range(len(st.touchdowns))],
            "summary": summary(self),
            "optimum": {"success": opt.success, "status": opt.status, "verdict": opt.verdict,
                        "strike": self.strike, "law": self.law,
                        "bounds_deg": {v: [math.degrees(lo), math.degrees(hi)] for v, lo, hi in
                                       zip(self.problem.variables, self.problem.lower, self.problem.upper)},
                        "objective_terms": self.problem.objective, "gait": gait(self),
                        "touchdown": {"angles_deg": optimum, "hip_velocity": list(opt.state[4:6])},
                        "T_c": opt.impact.T_c, "terms": opt.terms, "objective": opt.objective,
                        "held_by": [a.name for a in opt.held_by],
                        "active": [a.name for a in opt.active],
                        "saving_J_per_step": opt.saving, "saving_W": opt.power},
            "per_step": per_step_summary(self),
            "reference": {"angles_deg": reference, "T_c": opt.reference.T_c,
                          "terms": opt.reference_terms, "objective": opt.reference_objective},
            "difference_deg": {k: optimum[k] - reference[k] for k in JOINTS},
        }


def impact_strike(td: Touchdown) -> str:
    """The foot point that meets the ground first: heel or forefoot (midfoot: the lower)."""
    if td.strike in ("heel", "forefoot"):
        return td.strike
    heel, fore = td.hip_from_point["heel"][1], td.hip_from_point["forefoot"][1]
    return "heel" if heel >= fore else "forefoot"  # the hip higher above it: the lower point


def compare(trial: mocap.Trial, static: mocap.Trial, mass: float, height: float,
            sex: str = "male", friction: float = 0.8, starts: int = 4, seed: int = 0,
            law: str = "no-slip", bounds_deg: dict | None = None, support: float = SUPPORT,
            options: Options = Options(), per_step: bool = True) -> Comparison:
    """Every touchdown of `trial` through the impact under `law` (each result also carries
    the other laws, ImpactResult.contact_laws), the gait-anchored optimum under `law` within
    `bounds_deg` ({joint: (lo, hi)}, deg; missing joints keep BOUNDS_DEG), and with
    `per_step` the optimum of each valid step of the dominant strike."""
    m = measure(trial, static, height, options)
    steps = m.steps
    if not steps.valid:
        raise mocap.MocapError(f"{trial.source}: no touchdown with sound markers "
                               f"({'; '.join(steps.left_out[:3])})")
    body = scaled_body(mass, height, sex)
    model = build_model(body, "leg")
    impacts = {s: Impact(model, s, 0.0, friction, law=law) for s in ("heel", "forefoot")}
    strikes = [impact_strike(td) for td in steps.touchdowns]
    results = [impacts[s](td.state()) for s, td in zip(strikes, steps.touchdowns)]
    patterns = [td.strike for td in steps.valid]  # the runner's pattern decides the optimum's
    strike = "heel" if patterns.count("heel") > len(patterns) / 2 else "forefoot"
    chosen = [k for k, (s, td) in enumerate(zip(strikes, steps.touchdowns))
              if s == strike and td.valid_data] or [k for k, td in enumerate(steps.touchdowns) if td.valid_data]
    reference = np.mean([steps.touchdowns[k].state() for k in chosen], axis=0)
    bounds = {**BOUNDS_DEG, **(bounds_deg or {})}
    lower, upper = zip(*(map(math.radians, bounds[v]) for v in VARIABLES))
    objective = {"T_c": 1.0, "support": support} if support else {"T_c": 1.0}
    problem = Problem(VARIABLES, lower, upper, objective, starts=starts, seed=seed,
                      gait=Gait(cadence_spm=steps.cadence_spm))
    pp = PostureProblem(model, strike, reference, problem, 0.0, friction, law=law)
    optimum = pp.solve()
    settings = {"markers": m.calibration.markerset.name, "cutoff_hz": options.cutoff_hz,
                "effective_cutoff_hz": round(effective_cutoff(m.trial.rate, options.cutoff_hz), 2),
                "force_threshold_n": options.force_threshold_n,
                "foot_speed_fraction": options.foot_speed_fraction, "contact": law,
                "friction": friction, "bounds_deg": {k: list(v) for k, v in bounds.items()},
                "support": support, "starts": starts, "seed": seed,
                "body": {"mass_kg": mass, "height_m": height, "sex": sex}}
    c = Comparison(m, results, strikes, reference, strike, optimum, body, law, problem, settings,
                   hip_from_strike=pp.hip_from_strike(reference))
    if per_step and optimum.success:
        c.per_step = {k: step_optimum(pp, steps.touchdowns[k].state(), optimum.state, friction)
                      for k in chosen}
    return c


def step_optimum(pp: PostureProblem, state, start, friction: float) -> StepOptimum:
    """The optimum of one measured touchdown `state`, its placement held, from `start` (the
    mean step's optimum): one IPOPT run of the same NLP, the step in its parameters."""
    p = pp.posture.parameters(friction=friction, reference=state)
    sol, stats, _ = pp.solve_from(pp.start(start), p)
    w, x, _impact, ok = pp.accept(sol, stats, p)
    post = pp.posture
    own = (np.asarray(state)[post.index] - post.lower) / (post.upper - post.lower)  # unclipped
    return StepOptimum(ok, stats["return_status"] if stats["return_status"] not in CONVERGED or ok
                       else "rejected: a constraint or the checked impact fails",
                       x, float(pp.objective_function(w, p)), float(pp.objective_function(own, p)))


def _deg(values: dict) -> dict:
    return {k: math.degrees(v) for k, v in values.items()}


def _angles_deg(state) -> dict:
    """The trunk and joint angles (deg) of a touchdown state (model.STATE, SI)."""
    return {k: math.degrees(state[STATE.index(k)]) for k in JOINTS}


def touchdown_row(c: Comparison, k: int) -> dict:
    """One touchdown in the JSON report (README, "Measured touchdowns")."""
    td, s, r = c.steps.touchdowns[k], c.strikes[k], c.results[k]
    row = {"time": td.time, "side": td.side, "frame": td.frame, "method": c.steps.method,
           "strike": td.strike, "foot_strike_angle_deg": math.degrees(td.foot_strike_angle),
           "segment_angles_deg": _deg(td.segments), "angles_deg": _deg(td.angles),
           "rates_dps": _deg(td.rates), "hip_velocity_mps": list(td.hip_velocity),
           "hip_height_m": td.hip_height,
           "strike_point": {"point": s, "hip_from_point_m": list(td.hip_from_point[s])},
           "valid_data": td.valid_data, "data_problems": list(td.problems),
           "T_c": r.T_c, "mu_c": r.mu_c, "valid": r.valid,
           "contact_laws": {law: {key: getattr(v, key) for key in ("T_c", "valid", "mode", "slip_velocity")}
                            for law, v in r.contact_laws.items()}}
    if k in c.per_step:
        o = c.per_step[k]
        row["optimum"] = {"success": o.success, "status": o.status,
                          "angles_deg": _angles_deg(o.state),
                          "objective": o.objective, "measured_objective": o.measured,
                          "saving_J": o.saving}
    return row


def gait(c: Comparison) -> dict:
    """What the optimum holds from the measured gait: hip placement (m), velocity, cadence."""
    return {"hip_from_strike_m": list(c.hip_from_strike), "hip_velocity": list(c.reference[4:6]),
            "cadence_spm": c.steps.cadence_spm}


def per_step_summary(c: Comparison) -> dict:
    """The per-step optima: how many converged, and their angles and savings (mean, sd)."""
    done = [o for o in c.per_step.values() if o.success]
    if not done:
        return {"steps": len(c.per_step), "converged": 0}
    angles = np.degrees([[o.state[STATE.index(j)] for j in VARIABLES] for o in done])
    saving = np.array([o.saving for o in done])
    return {"steps": len(c.per_step), "converged": len(done),
            "angles_deg_mean": dict(zip(VARIABLES, angles.mean(axis=0))),
            "angles_deg_sd": dict(zip(VARIABLES, angles.std(axis=0, ddof=1) if len(done) > 1 else np.zeros(3))),
            "saving_J_mean": float(saving.mean()),
            "saving_J_sd": float(saving.std(ddof=1)) if len(done) > 1 else 0.0}


def summary(c: Comparison) -> dict:
    """Per side, over the touchdowns with sound markers: mean and standard deviation of the
    joint and segment angles, foot strike angle and T_c; per contact law the mean T_c and how
    many touchdowns are valid under it."""
    out = {}
    for side in SIDES:
        rows = [(td, r) for td, r in zip(c.steps.touchdowns, c.results) if td.side == side and td.valid_data]
        if not rows:
            continue

        def stats(values):
            values = np.asarray(values, float)
            return values.mean(axis=0), (values.std(axis=0, ddof=1) if len(values) > 1 else np.zeros(values.shape[1:]))
        angles = stats([[math.degrees(td.angles[k]) for k in JOINTS] for td, _ in rows])
        segments = stats([[math.degrees(td.segments[k]) for k in SEGMENTS] for td, _ in rows])
        fsa = stats([math.degrees(td.foot_strike_angle) for td, _ in rows])
        T_c = stats([r.T_c for _, r in rows])
        patterns = [td.strike for td, _ in rows]
        out[side] = {"steps": len(rows),
                     "left_out": sum(td.side == side and not td.valid_data for td in c.steps.touchdowns),
                     "strike": max(set(patterns), key=patterns.count),
                     "patterns": {p: patterns.count(p) for p in ("heel", "midfoot", "forefoot")},
                     "angles_deg_mean": dict(zip(JOINTS, angles[0])),
                     "angles_deg_sd": dict(zip(JOINTS, angles[1])),
                     "segment_angles_deg_mean": dict(zip(SEGMENTS, segments[0])),
                     "segment_angles_deg_sd": dict(zip(SEGMENTS, segments[1])),
                     "foot_strike_angle_deg_mean": float(fsa[0]), "foot_strike_angle_deg_sd": float(fsa[1]),
                     "T_c_mean": float(T_c[0]), "T_c_sd": float(T_c[1]),
                     "laws": {law: {"T_c_mean": float(np.mean([r.contact_laws[law].T_c for _, r in rows])),
                                    "valid": sum(r.contact_laws[law].valid for _, r in rows)}
                              for law in LAWS}}
    return out
