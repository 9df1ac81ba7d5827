"""Measured touchdowns against the optimum: the runner's own posture, indicators and the gap.

For each touchdown of a trial (measure.measure), the impact on the paper's leg scaled to the
runner (de Leva) at the point where the foot first pushes (impact_point: the plate's centre of
pressure, else the markers' contact order; the model sole's lower point beside it), under the
law asked (default Coulomb; every law kept), its effective mass beside the plate's two-mass fit
(ImpactMass), with
T_c's band over the measurement's variants (the markers' cut-off across FILTER_BAND_HZ, the
touchdown TIME_SHIFTS frames off). Per side, never pooled: the gait-anchored optimum of the
mean touchdown of that side's dominant impact point (the measured hip placement over the
strike point, hip velocity, segment rates and cadence held; hip, knee and ankle free within
`bounds_deg`; objective T_c, optionally + support weight * support), its saving only against
a mean touchdown valid under the law, with its band (SideOptimum); and the same optimum for
every valid step of that point (one NLP: the reference touchdown is a parameter). Only
touchdowns with sound markers (valid_data) enter the means.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import casadi as ca
import numpy as np

from ..io import mocap
from ..io.markerset import SIDES
from ..measure import Measurement, Options, Steps, Touchdown, measure
from ..measure.filters import effective_cutoff
from ..measure.plate import PlateImpact, TwoMassFit, cop_point, plate_impact, two_mass_fit
from ..measure.touchdowns import FLAT_S, shifted
from ..mechanics.body import Body, scaled_body
from ..mechanics.contact import LAWS
from ..mechanics.errors import InputError
from ..mechanics.impact import Impact, ImpactResult
from ..mechanics.landing import Diverged, LandingModel, simulate_state
from ..mechanics.model import STATE, STRIKES, build_model, landmarks
from ..optim.posture import Gait, PostureProblem, Problem
from ..optim.solution import Optimum
from ..optim.variables import RANGE_OF_MOTION_DEG

if TYPE_CHECKING:  # a type only: the stride section loads the stride solver when asked
    from .compare_stride import StrideAnswer

G = 9.81  # m/s^2: body weights
JOINTS = ("trunk", "hip", "knee", "ankle")
SEGMENTS = ("trunk", "thigh", "shank", "foot")
VARIABLES = ("hip", "knee", "ankle")
# The optimum searches hip, knee and ankle within these bounds (deg; default the joints'
# ranges of motion), the runner's trunk lean, speed and segment rates held at their means.
BOUNDS_DEG = {k: RANGE_OF_MOTION_DEG[k] for k in VARIABLES}
SUPPORT = 0.0  # the support term's weight: T_c alone (README, "What the optimum weighs")


FILTER_BAND_HZ = (8.0, 20.0)  # the markers' cut-offs T_c's uncertainty spans: running
#   kinematics are low-passed at 6-20 Hz (Winter's residual analysis gives 6-10 Hz for thigh
#   and shank, the foot near touchdown keeps content up to 15-20 Hz); 8 and 20 bracket the
#   choices around the default 10 Hz without passing the impact's marker artefacts
TIME_SHIFTS = (-1, 1)  # marker frames: the touchdown one frame earlier and later
VARIANTS = tuple([f"cutoff {f:g} Hz" for f in FILTER_BAND_HZ] + [f"touchdown {n:+d} frame" for n in TIME_SHIFTS])


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
class SideOptimum:
    """One side's optimum: the gait-anchored optimum of the mean touchdown of that side's
    steps with the side's dominant impact point (valid markers), and its saving's band.

    The saving is measured only against a reference that is valid under the law; its band
    is saving +- u, u the largest change of the side's mean measured T_c when the markers'
    cut-off moves across FILTER_BAND_HZ or the touchdown by TIME_SHIFTS (the optimum holds the
    same measured rates, so what the measurement cannot fix in T_c it cannot fix in the
    saving); `resolvable` when the band excludes zero."""

    side: str
    point: str  # the impact point of its steps (heel, forefoot)
    steps: list[int]  # touchdown indices averaged
    reference: np.ndarray  # their mean touchdown state (model.STATE, SI)
    checked: ImpactResult  # the impact at the mean touchdown under the law
    problem: Problem | None
    optimum: Optimum | None  # None: no optimum solved (why_not)
    why_not: str = ""
    uncertainty: float = float("nan")  # J: u above
    shifts: dict[str, float] = field(default_factory=dict)  # J: each variant's mean T_c - the nominal
    hip_from_strike: tuple[float, float] = (0.0, 0.0)  # m
    per_step: dict[int, StepOptimum] = field(default_factory=dict)

    @property
    def saving(self) -> float | None:
        """J per step, against a valid reference only."""
        opt = self.optimum
        return opt.saving if opt is not None and opt.success and self.checked.valid else None

    @property
    def band(self) -> tuple[float, float] | None:
        s = self.saving
        return None if s is None else (s - self.uncertainty, s + self.uncertainty)

    @property
    def resolvable(self) -> bool | None:
        band = self.band
        return None if band is None else bool(band[0] > 0 or band[1] < 0)

    @property
    def headline(self) -> str:
        """One line: the optimum's verdict, or why there is none or no saving."""
        if self.optimum is None:
            return f"NO OPTIMUM: {self.why_not}"
        if not self.checked.valid:
            return (f"REFERENCE INVALID under {self.checked.law} ({'; '.join(self.checked.warnings)}): "
                    f"no saving measured against it; {self.optimum.verdict}")
        if self.resolvable is False:
            return f"no change that the measurement can resolve; {self.optimum.verdict}"
        return self.optimum.verdict


SEQUENCE_DT_S, SEQUENCE_MAX_S = 1e-3, 0.2  # the flat step's landing: its step and longest span
#   (the second point comes down 0.4-1.7 ms after the first in RBDS001's flat steps; the
#   landing locates that event itself, between steps)


@dataclass(frozen=True)
class FlatSequence:
    """A flat step as the sequence it is (issue 24): the first point's impact (the model's
    sole puts it lower), then the second point's impact as the landing from the step's
    measured state simulates it (mechanics.landing.simulate_state, the comparison's law and
    friction). The rigid flat impact (both points pinned at once) bounds it from above."""

    first: str  # "heel" or "forefoot": the point down first
    first_J: float  # T_c of the first point's impact
    total_J: float  # the landing's T_c_total: both impacts and any re-impact of the first
    second_ms: float | None  # ms after the first: the second point's impact (None: never)
    violations: tuple[str, ...]  # the landing's own checks it breaks (Landing.violations)


def flat_sequence(lm: LandingModel, first: str, x, friction: float) -> FlatSequence | None:
    """The FlatSequence of a flat step of state `x` (model.STATE, SI) landing on `first`;
    None when the landing cannot run from it (diverges, or refuses a state with the other
    point below the ground): the rigid flat impact then stands, said in the notes."""
    try:
        landing = simulate_state(lm, first, x, friction, SEQUENCE_DT_S, SEQUENCE_MAX_S)
    except (Diverged, InputError):
        return None
    second = next((e.time for e in landing.impacts if e.contact != first), None)
    return FlatSequence(first, landing.impacts[0].T_c, landing.T_c_total,
                        None if second is None else second * 1e3, tuple(landing.violations))


@dataclass(frozen=True)
class ImpactMass:
    """The rigid map's effective mass at a touchdown's impact point beside the plate's
    two-mass fit (measure.plate.two_mass_fit): the map stops m_eff = 1 / (n^T J M^-1 J^T n)
    = 1 / W_nn (W_c the contact-space inverse inertia, mechanics.impact) in an instant with the
    normal impulse p_n = m_eff |v_n| (frictionless; the law's own beside it); the plate's
    stopped mass pushes J1 over a pulse of 2 t1, and J1 / |v_n| is the mass that impulse
    stops from the same approach speed."""

    m_eff: float  # kg
    v_n: float  # m/s: the impact point's normal velocity before the impact (< 0 approaching)
    p_n_law: float  # N s: the normal impulse under the comparison's law
    fit: TwoMassFit | None  # None without a plate (or a contact cut by the record's end)

    @property
    def p_n(self) -> float:
        return self.m_eff * -self.v_n

    @property
    def plate_mass(self) -> float | None:
        """kg: J1 / |v_n|."""
        return self.fit.impulse_1 / -self.v_n if self.fit is not None and self.v_n < 0 else None


def impact_mass(impact: Impact, x, result: ImpactResult, fit: TwoMassFit | None) -> ImpactMass | None:
    """The ImpactMass of one touchdown (state x, model.STATE) at `impact`'s point; None for a
    flat strike (two points: no single normal direction's mass)."""
    out = impact.evaluate(x)
    W_nn = float(np.asarray(out["W_c"], float)[1, 1])
    if not math.isfinite(W_nn):
        return None
    return ImpactMass(1.0 / W_nn, float(np.asarray(out["v_contact"], float).ravel()[1]),
                      result.impulse_total[1], fit)


@dataclass
class Comparison:
    measurement: Measurement
    results: list[ImpactResult]  # one per touchdown under `law`, at its impact point
    points: list[str]  # the model's impact point per touchdown (heel, forefoot, flat)
    T_c_band: list[tuple[float, float]]  # J per touchdown: least and most T_c over the variants
    sides: dict[str, SideOptimum]
    body: Body
    law: str  # the contact law of `results` and of the optima (contact.LAWS)
    settings: dict  # every setting that made this comparison (to_dict()["settings"])
    sole: list[tuple[str, float, float]]  # per touchdown: the model sole's lower point, the
    #                 other's time down (s), T_c (J) of an impact at the lower point alone
    plate: list[PlateImpact | None] = field(default_factory=list)  # per touchdown, trials with forces
    sequence: list[FlatSequence | None] = field(default_factory=list)  # per touchdown: flat steps'
    stride: StrideAnswer | None = None  # when asked (compare_stride.answer)
    masses: list[ImpactMass | None] = field(default_factory=list)  # per touchdown

    def step_T_c(self, k: int) -> float:
        """The headline T_c (J) of touchdown k: a flat step's sequence total, else its impact's."""
        seq = self.sequence[k] if self.sequence else None
        return seq.total_J if seq is not None else self.results[k].T_c

    @property
    def steps(self) -> Steps:
        return self.measurement.steps

    @property
    def flat_notes(self) -> list[str]:
        """What a side whose impacts are flat should be read with: the sequence's T_c (the
        headline), the first point's alone, the rigid flat impact's upper bound, and the
        landings that break their own checks or diverged."""
        out = []
        for side, o in self.sides.items():
            if o.point != "flat":
                continue
            seqs = [self.sequence[k] for k in o.steps] if self.sequence else []
            done = [q for q in seqs if q is not None]
            rigid = np.mean([self.results[k].T_c for k in o.steps])
            name = "right" if side == "R" else "left"
            if not done:
                out.append(f"{name}: flat steps, T_c {rigid:.2f} J as a rigid flat impact (no "
                           "landing of the sequence could run from the steps' states): an upper bound")
                continue
            second = [q.second_ms for q in done if q.second_ms is not None]
            broken = sum(bool(q.violations) for q in done)
            out.append(f"{name}: flat steps as their sequence, T_c {np.mean([q.total_J for q in done]):.2f} J "
                       f"(the first point's impact {np.mean([q.first_J for q in done]):.2f} J, the "
                       f"second point down {np.median(second) if second else float('nan'):.1f} ms later "
                       f"as the landing simulates it); the rigid flat impact, {rigid:.2f} J, is its "
                       f"upper bound"
                       + (f"; {broken} of {len(done)} landings break their own checks" if broken else "")
                       + (f"; {len(seqs) - len(done)} could not land (rigid flat kept)" if len(done) < len(seqs) else ""))
        return out

    @property
    def main_side(self) -> SideOptimum:
        """The side with the most steps averaged (a shorthand; the sides are never pooled)."""
        return max(self.sides.values(), key=lambda o: len(o.steps))

    @property
    def strike(self) -> str:
        """The main side's impact point."""
        return self.main_side.point

    @property
    def optimum(self) -> Optimum | None:
        """The main side's optimum (None when it has none: SideOptimum.why_not)."""
        return self.main_side.optimum

    def to_dict(self) -> dict:
        """JSON-ready dictionary (README, "Measured touchdowns"): the settings, the measurement,
        every touchdown, the per-side summary, each side's optimum against its mean touchdown,
        and its per-step optima."""
        cal, st = self.measurement.calibration, self.steps
        return {
            "settings": self.settings, "source": self.measurement.trial.source,
            "law": self.law, "cadence_spm": st.cadence_spm, "belt_speed": st.belt_speed,
            "speed": st.speed, "touchdown_method": st.method, "axes": cal.axes.describe(),
            "segment_lengths_m": cal.lengths, "body": self.body.source,
            "touchdowns_total": len(st.touchdowns), "touchdowns_valid_data": len(st.valid),
            "left_out": st.left_out, "notes": [*st.notes, *self.flat_notes],
            "touchdowns": [touchdown_row(self, k) for k in range(len(st.touchdowns))],
            "summary": summary(self),
            "optimum": {side: side_dict(self, o) for side, o in self.sides.items()},
            **({"stride": self.stride.to_dict()} if self.stride is not None else {}),
        }


def side_dict(c: Comparison, o: SideOptimum) -> dict:
    """One side's optimum in the JSON report: reference, optimum, saving with its band."""
    reference = _angles_deg(o.reference)
    out = {"point": o.point, "law": c.law, "steps": len(o.steps), "headline": o.headline,
           "reference": {"angles_deg": reference, "T_c": o.checked.T_c, "valid": o.checked.valid,
                         "warnings": list(o.checked.warnings)},
           "saving_J_per_step": o.saving, "saving_band_J": list(o.band) if o.band else None,
           "resolvable": o.resolvable, "T_c_uncertainty_J": _finite(o.uncertainty),
           "T_c_shift_J": {k: _finite(v) for k, v in o.shifts.items()},
           "saving_W": None if o.saving is None else o.saving * c.steps.cadence_spm / 60.0}
    opt, problem = o.optimum, o.problem
    if opt is None or problem is None:
        return out
    optimum = _angles_deg(opt.state)
    out.update({
        "success": opt.success, "status": opt.status, "verdict": opt.verdict,
        "bounds_deg": {v: [math.degrees(lo), math.degrees(hi)] for v, lo, hi in
                       zip(problem.variables, problem.lower, problem.upper)},
        "objective_terms": problem.objective,
        "gait": {"hip_from_strike_m": list(o.hip_from_strike), "hip_velocity": list(o.reference[4:6]),
                 "cadence_spm": c.steps.cadence_spm},
        "touchdown": {"angles_deg": optimum, "hip_velocity": list(opt.state[4:6])},
        "T_c": opt.impact.T_c, "terms": opt.terms, "objective": opt.objective,
        "reference_terms": opt.reference_terms, "held_by": [a.name for a in opt.held_by],
        "active": [a.name for a in opt.active], "notes": list(opt.notes),
        "difference_deg": {k: optimum[k] - reference[k] for k in JOINTS},
        "per_step": per_step_summary(o)})
    return out


def impact_point(sole: ca.Function, td: Touchdown) -> tuple[str, str, float]:
    """(impact point, the model sole's first point, the other point's time to the ground, s)
    of a measured touchdown. The impact point is where the foot first pushes: with a plate the
    centre of pressure's class (measure.plate.cop_point), else the markers' contact order. The
    model's sole (flat in the foot frame) at the measured foot angle relative to standing puts
    its lower point down first, the other following after its height over the ground divided by
    its own approach speed (inf when it rises): kept beside it, not trusted over it, because a
    sagittal foot angle cannot see a foot landing on its lateral edge (RBDS001 lands on the
    lateral metatarsal with a sagittal foot angle of 1-3 deg toe up: the model's sole says heel
    for 80 of 85 steps of T35, the plate forefoot for all)."""
    z_heel, z_fore, v_heel, v_fore = np.asarray(sole(td.state()), float).ravel()
    lower, gap, speed = (("heel", z_fore - z_heel, -v_fore) if z_heel <= z_fore
                         else ("forefoot", z_heel - z_fore, -v_heel))
    follows = gap / speed if speed > 0 else math.inf
    point = cop_point(td.cop_index) if td.cop_index is not None else td.contact_order
    return point, lower, follows


def sole_function(body: Body) -> ca.Function:
    """x -> [z_heel, z_forefoot, vz_heel, vz_forefoot] (m, m/s; hip at 0) of the model's foot."""
    x = ca.SX.sym("x", len(STATE))
    marks = landmarks(x, body)
    return ca.Function("sole", [x], [ca.vertcat(marks["heel"][0][1], marks["forefoot"][0][1],
                                                marks["heel"][1][1], marks["forefoot"][1][1])])


def modelled_state(td: Touchdown, point: str) -> np.ndarray:
    """The touchdown state the impact takes: a flat step, and a step whose impact point the
    measured foot angle holds above the other point (a foot landing on its edge, impact_point),
    with its sole put level on the ground (the ankle turned by the foot strike angle); the
    others as measured."""
    x = td.state()
    if point == "flat" or (point == "forefoot") == (td.foot_strike_angle > 0):
        x[STATE.index("ankle")] -= td.foot_strike_angle
    return x


def dominant(points: list[str]) -> str:
    """The most frequent impact point (heel first, then forefoot, on a tie)."""
    return max(STRIKES, key=points.count)


def compare(trial: mocap.Trial, static: mocap.Trial, mass: float, height: float,
            sex: str = "male", *, friction: float, starts: int = 4, seed: int = 0,
            law: str = "coulomb", bounds_deg: dict | None = None, support: float = SUPPORT,
            options: Options = Options(), per_step: bool = True, progress=None) -> Comparison:
    """Every touchdown of `trial` through the impact at its model impact point under `law`
    (each result also carries the other laws, ImpactResult.contact_laws), its T_c's band over
    the measurement's variants (variants), and per side the gait-anchored optimum under `law`
    within `bounds_deg` ({joint: (lo, hi)}, deg; missing joints keep BOUNDS_DEG), with
    `per_step` the optimum of each valid step of that side's impact point as well.
    `friction`: the ground's coefficient (no default: every report says which was used);
    `progress(text)`, when given, is told of each stage of a run that takes seconds."""
    say = progress or (lambda text: None)
    say(f"measuring {trial.source}")
    m = measure(trial, static, height, options)
    steps = m.steps
    if not steps.valid:
        raise mocap.MocapError(f"{trial.source}: no touchdown with sound markers "
                               f"({'; '.join(steps.left_out[:3])})")
    body = scaled_body(mass, height, sex)
    model = build_model(body, "leg")
    sole = sole_function(body)
    firsts = [impact_point(sole, td) for td in steps.touchdowns]
    points = [p for p, _, _ in firsts]
    impacts = {s: Impact(model, s, 0.0, friction, law=law) for s in STRIKES}
    results = [impacts[p](modelled_state(td, p)) for td, p in zip(steps.touchdowns, points)]
    lm = LandingModel(model, law=law, compiled=False)  # interpreted: ~4 ms a landing, no compile
    sequence = [flat_sequence(lm, first, td.state(), friction) if p == "flat" else None
                for td, (p, first, _) in zip(steps.touchdowns, firsts)]
    nominal = np.array([q.total_J if q is not None else r.T_c for q, r in zip(sequence, results)])
    say(f"{len(steps.touchdowns)} touchdowns; T_c's band: the step measured {len(VARIANTS)} more ways")
    spread = np.array([[headline_T_c(v, p, sole, impacts, lm, friction) if v else np.nan
                        for v, p in zip(variant, points)]
                       for variant in variants(trial, static, height, options, m)])
    bounds = {**BOUNDS_DEG, **(bounds_deg or {})}
    lower, upper = zip(*(map(math.radians, bounds[v]) for v in VARIABLES))
    problem = Problem(VARIABLES, lower, upper,
                      {"T_c": 1.0, "support": support} if support else {"T_c": 1.0},
                      starts=starts, seed=seed, gait=Gait(cadence_spm=steps.cadence_spm))
    settings = {**run_settings(m, options, law, friction, bounds), "support": support, "starts": starts,
                "seed": seed, "body": {"mass_kg": mass, "height_m": height, "sex": sex}}
    sides = {}
    for side in SIDES:
        own = [k for k, td in enumerate(steps.touchdowns) if td.side == side and td.valid_data]
        if own:
            say(f"side {side}: the optimum" + (" and each step's" if per_step else ""))
            sides[side] = side_optimum(side, own, points, results, nominal, spread, steps,
                                       impacts, problem, friction, per_step)
    band = [(float(np.nanmin([a, *col])), float(np.nanmax([a, *col])))
            for a, col in zip(nominal, spread.T)]
    plate = plate_impacts(m, mass)
    return Comparison(m, results, points, band, sides, body, law, settings,
                      [(lower, follows, r.T_c if p == lower else impacts[lower](td.state()).T_c)
                       for (p, lower, follows), r, td in zip(firsts, results, steps.touchdowns)], plate,
                      sequence, masses=impact_masses(m, points, results, impacts, plate))


def run_settings(m: Measurement, options: Options, law: str, friction: float, bounds: dict) -> dict:
    """The measurement's and the impact's settings a comparison ran with (Comparison.settings)."""
    return {"markers": m.calibration.markerset.name, "cutoff_hz": options.cutoff_hz,
            "effective_cutoff_hz": round(effective_cutoff(m.trial.rate, options.cutoff_hz), 2),
            "uncertainty": {"cutoff_hz": list(FILTER_BAND_HZ), "touchdown_frames": list(TIME_SHIFTS)},
            "flat_tolerance_s": FLAT_S,
            "force_threshold_n": options.force_threshold_n,
            "foot_speed_fraction": options.foot_speed_fraction, "contact": law,
            "friction": friction, "bounds_deg": {k: list(v) for k, v in bounds.items()}}


def plate_impacts(m: Measurement, mass: float) -> list[PlateImpact | None]:
    """Each touchdown's impact as the plate measured it (touchdowns.plate_impact; `mass`, kg),
    None for all without a plate."""
    t, axes = m.trial, m.calibration.axes
    return [plate_impact(t.force, t.force_rate, axes.forward, axes.up, td.time, mass * G, t.source)
            if m.steps.method == "force plate" and t.force_rate is not None else None
            for td in m.steps.touchdowns]


def impact_masses(m: Measurement, points, results, impacts: dict, plate) -> list[ImpactMass | None]:
    """Each touchdown's ImpactMass at its impact point, the plate's two-mass fit beside it
    where the touchdown has a plate impact."""
    t = m.trial
    return [impact_mass(impacts[p], modelled_state(td, p), r,
                        two_mass_fit(t.force, t.force_rate, m.calibration.axes.up, td.time, t.source)
                        if pl is not None and t.force_rate is not None else None)
            for td, p, r, pl in zip(m.steps.touchdowns, points, results, plate)]


def headline_T_c(td: Touchdown, point: str, sole: ca.Function, impacts: dict, lm: LandingModel,
                 friction: float) -> float:
    """T_c (J) of a step at its impact point: a flat one's sequence total (FlatSequence),
    landing on the point its own sole puts lower, rigid flat where the landing cannot run;
    the others their impact's."""
    seq = flat_sequence(lm, impact_point(sole, td)[1], td.state(), friction) if point == "flat" else None
    return seq.total_J if seq is not None else impacts[point](modelled_state(td, point)).T_c


def variants(trial, static, height: float, options: Options, m: Measurement) -> list[list]:
    """The touchdowns measured again with each cut-off of FILTER_BAND_HZ (matched by side and
    time, None where not found within 20 ms) and taken TIME_SHIFTS frames off, aligned with
    m's touchdowns."""
    out = []
    for cutoff in FILTER_BAND_HZ:
        other = measure(trial, static, height, replace(options, cutoff_hz=cutoff)).steps.touchdowns
        out.append([min((o for o in other if o.side == td.side and abs(o.time - td.time) < 0.02),
                        key=lambda o: abs(o.time - td.time), default=None)
                    for td in m.steps.touchdowns])
    for frames in TIME_SHIFTS:
        out.append([shifted(m.kinematics, td, frames, m.steps.belt_speed) for td in m.steps.touchdowns])
    return out


def side_optimum(side: str, own: list[int], points, results, nominal, spread, steps: Steps,
                 impacts: dict, problem: Problem, friction: float, per_step: bool) -> SideOptimum:
    """The optimum of one side (SideOptimum): its dominant impact point's steps averaged,
    the mean checked, the optimum solved (Coulomb's mode followed, PostureProblem.solve), the
    band from the variants' T_c, and each of those steps' optimum when asked."""
    point = dominant([points[k] for k in own])
    chosen = [k for k in own if points[k] == point]
    shift = np.nanmean(spread[:, chosen], axis=1) - nominal[chosen].mean()
    reference = np.mean([modelled_state(steps.touchdowns[k], point) for k in chosen], axis=0)
    checked = impacts[point](reference)
    law = impacts[point].law
    if point == "flat" and law == "coulomb":
        return SideOptimum(side, point, chosen, reference, checked, None, None,
                           f"{len(chosen)} of {len(own)} steps are flat (both points down within "
                           f"{FLAT_S * 1e3:.0f} ms, the model and the markers agreeing): a flat "
                           "strike's Coulomb impact has no smooth optimum (optim.posture.admissible)",
                           float(np.nanmax(np.abs(shift))), shifts=dict(zip(VARIANTS, map(float, shift))))
    if point == "flat":
        problem = replace(problem, variables=VARIABLES[:2], lower=problem.lower[:2],
                          upper=problem.upper[:2])  # the ankle follows from the sole on the ground
    pp = PostureProblem(impacts[point].model, point, reference, problem, 0.0, friction, law=law)
    o = SideOptimum(side, point, chosen, reference, checked, problem, pp.solve(),
                    uncertainty=float(np.nanmax(np.abs(shift))),
                    shifts=dict(zip(VARIANTS, map(float, shift))),
                    hip_from_strike=pp.hip_from_strike(reference))
    if per_step and o.optimum is not None and o.optimum.success:
        o.per_step = {k: step_optimum(pp, modelled_state(steps.touchdowns[k], point), o.optimum.state, friction)
                      for k in chosen if results[k].valid}
    return o


def step_optimum(pp: PostureProblem, state, start, friction: float) -> StepOptimum:
    """The optimum of one measured touchdown `state`, its placement held, from `start` (the
    mean step's optimum): one IPOPT run of the same NLP, the step in its parameters."""
    p = pp.posture.parameters(friction=friction, reference=state)
    sol, stats, _ = pp.solve_from(pp.start(start), p)
    w, x, _impact, why = pp.accept(sol, stats, p)
    post = pp.posture
    own = (np.asarray(state)[post.index] - post.lower) / (post.upper - post.lower)  # unclipped
    return StepOptimum(why == "", f"rejected: {why}" if why else stats["return_status"],
                       x, float(pp.objective_function(w, p)), float(pp.objective_function(own, p)))


def impulse_ratio(law) -> float | None:
    """Tangential over normal impulse (forward positive) of one law's impact (LawResult)."""
    t = sum(v[0] for v in law.impulse.values())
    n = sum(v[1] for v in law.impulse.values())
    return t / n if n > 0 else None


def _finite(value: float) -> float | None:
    """JSON has no inf or nan: None."""
    return value if math.isfinite(value) else None


def _deg(values: dict) -> dict:
    return {k: math.degrees(v) for k, v in values.items()}


def _angles_deg(state) -> dict:
    """The trunk and joint angles (deg) of a touchdown state (model.STATE, SI)."""
    return {k: math.degrees(state[STATE.index(k)]) for k in JOINTS}


def touchdown_row(c: Comparison, k: int) -> dict:
    """One touchdown in the JSON report (README, "Measured touchdowns")."""
    td, p, r = c.steps.touchdowns[k], c.points[k], c.results[k]
    row = {"time": td.time, "side": td.side, "frame": td.frame, "method": c.steps.method,
           "strike": td.strike, "foot_strike_angle_deg": math.degrees(td.foot_strike_angle),
           "impact_point": p, "contact_order": td.contact_order,
           "cop_index": td.cop_index, "cop_point": None if td.cop_index is None else cop_point(td.cop_index),
           "model_sole": {"first": c.sole[k][0], "other_down_ms": _finite(c.sole[k][1] * 1e3),
                          "T_c_first_alone": c.sole[k][2]},
           "reach_ms": {"heel": td.reach_s[0] * 1e3, "forefoot": td.reach_s[1] * 1e3},
           "segment_angles_deg": _deg(td.segments), "angles_deg": _deg(td.angles),
           "rates_dps": _deg(td.rates), "hip_velocity_mps": list(td.hip_velocity),
           "hip_height_m": td.hip_height,
           "hip_from_point_m": {q: list(v) for q, v in td.hip_from_point.items()},
           "valid_data": td.valid_data, "data_problems": list(td.problems),
           "T_c": c.step_T_c(k), "T_c_band_J": list(c.T_c_band[k]), "mu_c": r.mu_c, "valid": r.valid,
           "contact_laws": {law: {**{key: getattr(v, key) for key in ("T_c", "valid", "mode", "slip_velocity")},
                                  "impulse_ratio": impulse_ratio(v)}
                            for law, v in r.contact_laws.items()}}
    seq = c.sequence[k] if c.sequence else None
    if seq is not None:
        row["flat_sequence"] = {"first": seq.first, "T_c_first_J": seq.first_J, "T_c_total_J": seq.total_J,
                                "second_down_ms": seq.second_ms, "violations": list(seq.violations),
                                "T_c_rigid_flat_J": r.T_c}
    pl = c.plate[k] if c.plate else None
    if pl is not None:
        row.update({"plate_impulse_ratio": pl.impulse_ratio, "impact_peak_bw": pl.impact_peak_bw,
                    "loading_rate_bw_per_s": pl.loading_rate_bw_per_s,
                    "impact_window_ms": pl.window_s * 1e3, "impact_peak_found": pl.peak})
    im = c.masses[k] if c.masses else None
    if im is not None:
        row["rigid_impact"] = {"m_eff_kg": im.m_eff, "m_eff_pct_body_mass": 100 * im.m_eff / c.body.mass,
                               "v_n_mps": im.v_n, "p_n_Ns": im.p_n, "p_n_law_Ns": im.p_n_law}
        if im.fit is not None:
            f = im.fit
            row["plate_two_mass"] = {"J1_Ns": f.impulse_1, "t1_ms": f.t1 * 1e3, "t1_on_bound": f.bounded,
                                     "J2_Ns": f.impulse_2, "contact_ms": f.contact * 1e3, "r2": f.r2,
                                     "r2_half_sine_alone": f.r2_half_sine, "J1_per_v_n_kg": im.plate_mass}
    side = c.sides.get(td.side)
    if side is not None and k in side.per_step:
        o = side.per_step[k]
        row["optimum"] = {"success": o.success, "status": o.status,
                          "angles_deg": _angles_deg(o.state),
                          "objective": o.objective, "measured_objective": o.measured,
                          "saving_J": o.saving}
    return row


def per_step_summary(o: SideOptimum) -> dict:
    """A side's per-step optima: how many converged, their angles and savings (mean, sd)."""
    done = [s for s in o.per_step.values() if s.success]
    if not done:
        return {"steps": len(o.per_step), "converged": 0}
    angles = np.degrees([[s.state[STATE.index(j)] for j in VARIABLES] for s in done])
    saving = np.array([s.saving for s in done])
    return {"steps": len(o.per_step), "converged": len(done),
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
        point = c.sides[side].point
        T_c = stats([c.step_T_c(k) for k in c.sides[side].steps])
        patterns = [td.strike for td, _ in rows]
        mine = [c.points[k] for k, td in enumerate(c.steps.touchdowns) if td.side == side and td.valid_data]
        orders = [td.contact_order for td, _ in rows]
        firsts = [c.sole[k][0] for k, td in enumerate(c.steps.touchdowns) if td.side == side and td.valid_data]
        out[side] = {"steps": len(rows),
                     "left_out": sum(td.side == side and not td.valid_data for td in c.steps.touchdowns),
                     "strike": max(set(patterns), key=patterns.count),
                     "patterns": {p: patterns.count(p) for p in ("heel", "midfoot", "forefoot")},
                     "impact_points": {p: mine.count(p) for p in STRIKES},
                     "impact_point_share": {p: mine.count(p) / len(mine) for p in STRIKES},
                     "contact_order": {p: orders.count(p) for p in STRIKES},
                     "model_sole": {p: firsts.count(p) for p in STRIKES},
                     "centre_of_pressure": cop_summary([td for td, _ in rows], firsts),
                     "angles_deg_mean": dict(zip(JOINTS, angles[0])),
                     "angles_deg_sd": dict(zip(JOINTS, angles[1])),
                     "segment_angles_deg_mean": dict(zip(SEGMENTS, segments[0])),
                     "segment_angles_deg_sd": dict(zip(SEGMENTS, segments[1])),
                     "foot_strike_angle_deg_mean": float(fsa[0]), "foot_strike_angle_deg_sd": float(fsa[1]),
                     "T_c_point": point, "T_c_mean": float(T_c[0]), "T_c_sd": float(T_c[1]),
                     "plate": plate_summary(c, side),
                     "impact_mass": mass_summary(c, side),
                     "laws": {law: {"T_c_mean": float(np.mean([r.contact_laws[law].T_c for _, r in rows])),
                                    "impulse_ratio_median": _median([impulse_ratio(r.contact_laws[law]) for _, r in rows]),
                                    "valid": sum(r.contact_laws[law].valid for _, r in rows)}
                              for law in LAWS}}
    return out


def cop_summary(tds: list[Touchdown], firsts: list[str]) -> dict | None:
    """A side's impact points by the plate's centre of pressure (valid steps; None without a
    plate): the count of each class, its index's median and 10-90 % range, and how many steps
    the markers' contact order and the model sole's lower point put in the same class."""
    index = [td.cop_index for td in tds if td.cop_index is not None]
    if not index:
        return None
    ref = [cop_point(td.cop_index) for td in tds if td.cop_index is not None]
    orders = [td.contact_order for td in tds if td.cop_index is not None]
    soles = [f for f, td in zip(firsts, tds) if td.cop_index is not None]
    return {"points": {p: ref.count(p) for p in STRIKES}, "index_median": float(np.median(index)),
            "index_10_90": [float(v) for v in np.percentile(index, [10, 90])], "steps": len(ref),
            "contact_order_agrees": sum(a == b for a, b in zip(orders, ref)),
            "model_sole_agrees": sum(a == b for a, b in zip(soles, ref)),
            "contact_order_by_cop": {r: {p: sum(o == p for o, q in zip(orders, ref) if q == r) for p in STRIKES}
                                     for r in STRIKES if r in ref}}


def mass_summary(c: Comparison, side: str) -> dict | None:
    """A side's rigid effective mass and normal impulse (valid steps with a single impact
    point; medians) beside the plate's two-mass fit where there is one: J1, J1 / |v_n|, t1
    (and how many fits put it on its bound: no separate impact pulse), R^2 (median, least)
    and the half sine's alone."""
    rows = [im for im, td in zip(c.masses, c.steps.touchdowns) if im is not None and td.side == side and td.valid_data]
    if not rows:
        return None
    mass = c.body.mass
    out: dict = {"steps": len(rows), "m_eff_kg": float(np.median([r.m_eff for r in rows])),
           "m_eff_pct_body_mass": float(np.median([100 * r.m_eff / mass for r in rows])),
           "v_n_mps": float(np.median([r.v_n for r in rows])),
           "p_n_Ns": float(np.median([r.p_n for r in rows])), "p_n_law_Ns": float(np.median([r.p_n_law for r in rows]))}
    fits = [(r.fit, r.plate_mass) for r in rows if r.fit is not None]
    if fits:
        out["plate"] = {"steps": len(fits), "J1_Ns": float(np.median([f.impulse_1 for f, _ in fits])),
                        "J1_per_v_n_pct_body_mass": _median([None if m is None else 100 * m / mass for _, m in fits]),
                        "t1_ms": float(np.median([f.t1 for f, _ in fits]) * 1e3),
                        "t1_on_bound": sum(f.bounded for f, _ in fits),
                        "r2_median": float(np.median([f.r2 for f, _ in fits])), "r2_least": min(f.r2 for f, _ in fits),
                        "r2_half_sine_alone": float(np.median([f.r2_half_sine for f, _ in fits]))}
    return out


def _median(values) -> float | None:
    values = [v for v in values if v is not None]
    return float(np.median(values)) if values else None


def plate_summary(c: Comparison, side: str) -> dict | None:
    """A side's plate impacts (valid steps): the median impulse ratio of the plate and of each
    law (medians: a law's ratio is unbounded where its normal impulse is near zero), mean
    impact peak and loading rate, how many steps have a distinct impact peak, and the law
    whose median ratio is nearest the plate's."""
    rows = [(pl, r) for pl, td, r in zip(c.plate, c.steps.touchdowns, c.results)
            if pl is not None and td.side == side and td.valid_data]
    if not rows:
        return None
    ratio = float(np.median([pl.impulse_ratio for pl, _ in rows]))
    laws = {law: _median([impulse_ratio(r.contact_laws[law]) for _, r in rows]) for law in LAWS}
    known = {law: v for law, v in laws.items() if v is not None}
    return {"impulse_ratio_median": ratio, "impulse_ratio_sd": float(np.std([pl.impulse_ratio for pl, _ in rows])),
            "impact_peak_bw_mean": float(np.mean([pl.impact_peak_bw for pl, _ in rows])),
            "loading_rate_bw_per_s_mean": float(np.mean([pl.loading_rate_bw_per_s for pl, _ in rows])),
            "window_ms_mean": float(np.mean([pl.window_s for pl, _ in rows]) * 1e3),
            "impact_peaks": sum(pl.peak for pl, _ in rows), "steps": len(rows),
            "laws_impulse_ratio": laws,
            "nearest_law": min(known, key=lambda law: abs(known[law] - ratio), default=None)}
