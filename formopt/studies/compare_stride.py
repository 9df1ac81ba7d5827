"""compare's stride section: the measured runner against the stride optimum of their body.

At the measured speed, for the body scaled from the runner's mass and height (de Leva), the
free half-stride optimum (optim.stride) with the runner's own impact point (compare's main side)
and with each strike ("best": the least costly that converged); the runner's cadence, step
length, placement of the striking point ahead of the hip and strike beside it; and what-if
strides with the cadence imposed at WHAT_IF_PCT of the runner's, at each the least costly
optimum found (stride_map.cadence_curve). A change is measured against the
stride at the runner's own cadence (imposed too, so the model's answer is a change and not the
distance to its own optimum):

    dP(c) = P(c) - P(c_runner),  P = W+ / T (mechanical power, W), likewise the impact loss
    sum T_c / T (W).

Each nominal stride is the least costly optimum found from several starts (cadence_curve: from
the free optimum and from both neighbours, swept until nothing improves); where other starts
ended in costlier local optima, `notes` says how much costlier. The curve is an envelope: the
free optimum's objective is at most the least imposed stride's (ENVELOPE, relative); where
cadence_curve finds a better free optimum from an imposed stride, the curve is solved again
from it (at most ROUNDS times). The family: from the free optimum, each cadence solved warm
from its neighbour towards it (a continuation, `family`); a curve's stride that this
continuation reaches (FAMILY) is of the free optimum's family, and a what-if between strides of
two families says so (`WhatIf.same_family`, `notes`). Its band [low_W, high_W] spans dP over
the variants (studies.compare_band: the friction, the objective and the legs' share of the
body's mass), each solved warm from the nominal's stride at the same cadence (variant_curve);
`WhatIf.parts` is each part's own width (the span of dP over the nominal and that part's
variants). A variant that fails to converge at any cadence is left out of the band and named
in `notes`. A change whose band holds zero is "no change the model can resolve". The solves
that do not wait for each other run on one pool of worker processes (studies.pool.Background):
the other strikes' free optima beside the nominal curve, the curve's first sweep
(stride_map.first_sweep), the band's free optima beside the family and its strides after it
(compare_band; benchmarks/compare_speed.py --stride times each stage and process,
docs/reference/performance.md). What the section says beside its numbers: compare_notes.
Every stride is built as the section's model builds it (stride_form.STRIDE_MODELS: scenes,
formopt stride's and the default, or quick, a preview on the trapezoid).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..measure import stance_knee_deg
from ..mechanics.body import scaled_body
from ..optim.stride import Stride, rank, summarise
from ..optim.stride.problem import STRIKES
from .compare_band import (
    BAND_PARTS,
    WORKERS,
    Variant,
    band_results,
    band_text,
    band_variants,
    check_tasks,
    start_band,
    strike_tasks,
)
from .compare_notes import ENVELOPE, section_notes
from .pool import Background
from .stride_form import STRIDE_MODEL, joint_work, model_of, placement_m, stride_scene
from .stride_map import better, cadence_curve, warm

WHAT_IF_PCT = (-10.0, -5.0, 5.0, 10.0)  # cadence changes asked (% of the runner's cadence)
STRIDE_LAWS = ("no-slip", "coulomb")  # the stride's impact laws; compare's others map to coulomb
ROUNDS = 2  # the curve solved again from a better free optimum found on it, at most
# one family: a continuation that reaches a curve's stride within this (relative objective)
FAMILY = 1e-3


@dataclass
class Curve:
    """One variant's strides at the runner's cadence and the what-if cadences."""

    name: str
    cadences: list[float]  # steps/min: the runner's first, then WHAT_IF_PCT's
    free: Stride | None = None
    strides: list[Stride] = field(default_factory=list)
    why_not: str = ""  # empty when every stride converged
    spread: list[float] = field(default_factory=list)  # CadenceCurve.spread (nominal only)
    free_from: str = "free"  # CadenceCurve.free_from
    part: str = ""  # the band's part a variant stands for (BAND_PARTS; "" the nominal)
    # per cadence, how much costlier (relative) the continuation from the free optimum reached
    # than the curve's stride (`family`; None: it did not converge there; nominal only)
    family_gap: list = field(default_factory=list)
    # under Coulomb, when the free optimum's touchdown slides and the imposed strides stick
    # (cadence_curve solves them sticking): the sticking strides' own free optimum, solved warm
    # from the least costly of them (`sticking_free`, kept converged or not); the envelope and
    # the family are theirs
    own_free: Stride | None = None

    @property
    def own_free_failed(self) -> bool:
        """The sticking strides' own free optimum was solved and did not converge."""
        return self.own_free is not None and not self.own_free.success

    @property
    def envelope_free(self) -> Stride | None:
        """Where the family and the band's sticking starts begin: the free optimum of the
        curve's own strides (`own_free`, else `free`); where `own_free` did not converge, the
        least costly imposed stride (optim.stride.rank: the best sticking stride known, no
        optimum; the sliding `free` is not of their NLP)."""
        if self.own_free_failed:
            return min(self.strides, key=rank, default=None)
        return self.own_free or self.free

    @property
    def same_family(self) -> list[bool]:
        """Per cadence, whether the curve's stride is of the free optimum's family (FAMILY)."""
        return [g is not None and g <= FAMILY for g in self.family_gap]

    @property
    def envelope_gap(self) -> float | None:
        """How far (relative) the free optimum's objective lies above the least imposed
        stride's (<= 0: it is the curve's minimum); None without a free optimum of the strides'
        NLP (none solved, no strides, or `own_free` did not converge)."""
        free = self.envelope_free
        if free is None or not self.strides or self.own_free_failed:
            return None
        least = min(s.objective_value for s in self.strides if s.success)
        return (free.objective_value - least) / abs(free.objective_value)

    @property
    def ok(self) -> bool:
        return not self.why_not

    def power(self) -> np.ndarray:
        return np.array([s.mechanical_power_W for s in self.strides])

    def impact_loss(self) -> np.ndarray:
        return np.array([s.budget["impacts_J"] / s.half_period_s for s in self.strides])

    def to_dict(self) -> dict:
        out = {"name": self.name, "converged": self.ok, "why_not": self.why_not,
               "cadence_spm": self.cadences, "local_optima_spread": self.spread, "part": self.part}
        if self.ok and self.free is not None:
            out.update(mechanical_power_W=self.power().tolist(), impact_loss_W=self.impact_loss().tolist(),
                       free_cadence_spm=self.free.cadence_spm,
                       free_mechanical_power_W=self.free.mechanical_power_W,
                       free_impact_loss_W=self.free.budget["impacts_J"] / self.free.half_period_s,
                       envelope_gap=self.envelope_gap)
        if self.ok and self.own_free is not None:  # its figures null where it did not converge
            own = self.own_free
            values = {"cadence_spm": own.cadence_spm, "mechanical_power_W": own.mechanical_power_W,
                      "impact_loss_W": own.budget["impacts_J"] / own.half_period_s}
            out.update({f"own_free_{k}": v if own.success else None for k, v in values.items()},
                       own_free_status=own.status)
        if self.family_gap:
            out.update(family_gap=self.family_gap, same_family=self.same_family)
        return out


@dataclass(frozen=True)
class WhatIf:
    """The predicted change at one imposed cadence (W) and its band over the variants."""

    cadence_change_pct: float
    cadence_spm: float
    mechanical_power_change_W: float
    impact_loss_change_W: float
    low_W: float  # band of the mechanical power's change
    high_W: float
    impact_low_W: float  # band of the impact loss's change
    impact_high_W: float
    parts: tuple = ()  # ((part, width W), ...): each part's own span of the power's change
    same_family: bool = True  # this stride and the runner's cadence's of one family (`family`)

    def shares(self) -> dict[str, float]:
        """Each part's share of the parts' summed widths (0-1; empty when no part has width)."""
        total = sum(w for _, w in self.parts)
        return {p: w / total for p, w in self.parts} if total > 0 else {}

    @property
    def resolvable(self) -> bool:
        return self.low_W > 0 or self.high_W < 0

    def words(self) -> str:
        """The change in words: its sign when the band excludes zero, else that it is not
        resolved."""
        if not self.resolvable:
            return "no change the model can resolve"
        return "costs more" if self.low_W > 0 else "saves power"

    def to_dict(self) -> dict:
        return {"cadence_change_pct": self.cadence_change_pct, "cadence_spm": self.cadence_spm,
                "mechanical_power_change_W": self.mechanical_power_change_W,
                "impact_loss_change_W": self.impact_loss_change_W, "low_W": self.low_W,
                "high_W": self.high_W, "impact_loss_band_W": [self.impact_low_W, self.impact_high_W],
                "band_parts_W": dict(self.parts), "band_shares": self.shares(),
                "same_family": self.same_family, "resolvable": self.resolvable, "words": self.words()}


@dataclass
class StrideAnswer:
    """The runner's form against the stride optimum of their body (module docstring)."""

    speed_mps: float
    law: str
    measured: dict  # cadence_spm, step_length_m, placement_m (ahead of the hip), strike, stance_knee_deg
    curves: list[Curve]  # the nominal first
    best: dict[str, Stride | None]  # the free optimum per strike (nominal variant)
    what_if: list[WhatIf]
    notes: list[str]
    seconds: float
    nominal_nodes: int  # collocation intervals of every stride solved
    transcription: str  # theirs (StrideSettings.transcription)
    model: str | None = None  # theirs (stride_form.STRIDE_MODELS; None: another)

    @property
    def nominal(self) -> Curve:
        return self.curves[0]

    @property
    def best_strike(self) -> str | None:
        """The strike of the best free optimum (optim.stride.rank), None when none is valid
        (`notes` then says so)."""
        solved = {k: s for k, s in self.best.items() if s is not None}
        best = min(solved, key=lambda k: rank(solved[k]), default=None)
        return best if best is not None and solved[best].valid else None

    def to_dict(self) -> dict:
        """The section as JSON; `sticking_optimum_*` the nominal's `own_free`, null where it is
        none or did not converge (`sticking_optimum_status`: IPOPT's, null where none)."""
        own = self.nominal.free
        best = self.best_strike
        tried = self.nominal.own_free
        sticking = tried if tried is not None and tried.success else None
        return {"speed_mps": self.speed_mps, "law": self.law, "nodes": self.nominal_nodes, "transcription": self.transcription,
                "model": self.model,
                "measured_cadence_spm": self.measured["cadence_spm"],
                "measured_step_length_m": self.measured["step_length_m"],
                "measured_placement_m": self.measured["placement_m"],
                "measured_strike": self.measured["strike"],
                "measured_stance_knee_deg": self.measured["stance_knee_deg"],
                "optimum_cadence_spm": own.cadence_spm if own else None,
                "optimum_valid": own.valid if own else None,
                "optimum_step_length_m": own.step_length_m if own else None,
                "optimum_placement_m": placement_m(own) if own else None,
                "optimum_stance_knee_deg": own.stance_knee_deg if own else None,
                "optimum_mechanical_power_W": own.mechanical_power_W if own else None,
                "optimum_impact_loss_W": own.budget["impacts_J"] / own.half_period_s if own else None,
                "optimum_joint_work_J": joint_work(own) if own else None,
                "optimum_remarks": own.remarks if own else [],
                "sticking_optimum_cadence_spm": sticking.cadence_spm if sticking else None,
                "sticking_optimum_mechanical_power_W": sticking.mechanical_power_W if sticking else None,
                "sticking_optimum_valid": sticking.valid if sticking else None,
                "sticking_optimum_status": tried.status if tried else None,
                "best_strike": best,
                "strikes": {k: None if s is None else
                            {"success": s.success, "objective_value": s.objective_value,
                             "cadence_spm": s.cadence_spm, "mechanical_power_W": s.mechanical_power_W,
                             "impacts_valid": all(i["valid"] for i in s.impacts), "valid": s.valid,
                             "failed_checks": s.failed_checks}
                            for k, s in self.best.items()},
                "what_if": [w.to_dict() for w in self.what_if], "band": band_text(),
                "envelope_tolerance": ENVELOPE, "family_tolerance": FAMILY,
                "curves": [c.to_dict() for c in self.curves], "notes": self.notes,
                "seconds": self.seconds}


def measured_form(c) -> dict:
    """The runner's cadence (steps/min), step length (m), placement of the striking point
    ahead of the hip (m: the mean over the main side's steps of the hip's forward distance from
    the point the stride strikes with, the forefoot for a forefoot strike, else the heel, as
    optim.stride), strike (the main side's impact point) and stance knee at its deepest (deg, the
    main side's mean cycle: measure.stance_knee_deg; None without one)."""
    st, side = c.steps, c.main_side
    point = "forefoot" if side.point == "forefoot" else "heel"
    ahead = [-st.touchdowns[k].hip_from_point[point][0] for k in side.steps]
    knee, _ = stance_knee_deg(c.measurement, side.side)
    return {"cadence_spm": st.cadence_spm, "step_length_m": st.speed * 60.0 / st.cadence_spm,
            "placement_m": float(np.mean(ahead)), "strike": side.point,
            "stance_knee_deg": None if np.isnan(knee) else knee}


def run_curve(name: str, scene, speed: float, cadences: list[float], beside: Background | None = None) -> Curve:
    """The variant's strides at `cadences`: at each the least costly optimum found
    (stride_map.cadence_curve, its first sweep on `beside`'s pool where given), solved again
    from a better free optimum found on the curve (ROUNDS), so that the free optimum is the
    curve's least (module docstring)."""
    curve = Curve(name, cadences)
    try:
        got = cadence_curve(scene, speed, cadences, beside=beside)
        for _ in range(ROUNDS):
            if got.free_from == "free":
                break
            again = cadence_curve(scene, speed, cadences, start=got.free, beside=beside)
            got = again if again.free_from != "free" else replace(again, free_from=got.free_from)
    except RuntimeError as err:
        curve.why_not = str(err)
        return curve
    curve.free, curve.strides, curve.spread, curve.free_from = got.free, got.strides, got.spread(), got.free_from
    curve.own_free = sticking_free(scene, speed, curve)
    failed = [f"{s.cadence_spm:.0f}" for s in got.strides if not s.success]
    if failed:
        curve.why_not = f"no convergence at {', '.join(failed)} steps/min"
    return curve


def variant_curve(name: str, nominal: Curve, solved: list[Stride]) -> Curve:
    """A variant's strides, each warm-started from the nominal's at the same cadence (and its
    free optimum from the nominal's): the band then measures the variant's effect on the same
    family of strides. (Warm-started along its own cadences instead, the mass -5 % variant
    of RBDS001 at 3.58 m/s jumped at -10 % to another local optimum, 565 W against the
    nominal's 463 W, and made the band 10 times wider, 2026-11-23.) `solved`: its
    strides solved (compare_band.band_results: the free optimum first)."""
    curve = Curve(name, nominal.cadences)
    curve.free, *curve.strides = solved
    failed = [f"{s.cadence_spm:.0f} steps/min" for s in curve.strides if not s.success]
    failed += [] if curve.free.success else ["the free optimum"]
    if failed:
        curve.why_not = f"no convergence at {', '.join(failed)}"
    return curve


def touchdown_mode(stride: Stride) -> str:
    """How the stride's touchdown (its last impact) was solved: stick or slide."""
    return stride.impacts[-1]["mode"]


def sticking_free(scene, speed: float, curve: Curve) -> Stride | None:
    """Where the free optimum's touchdown slides and the curve's strides stick: the free
    optimum of the sticking strides, warm from the least costly of them (None otherwise)."""
    if curve.free is None or not curve.strides or touchdown_mode(curve.free) == touchdown_mode(curve.strides[0]):
        return None
    nlp = scene.nlp()
    return summarise(nlp, warm(nlp, min(curve.strides, key=rank), speed, scene.slope, scene.friction, None), False)


def family(scene, speed: float, curve: Curve) -> None:
    """The free optimum's family along the curve (`Curve.envelope_free`'s): the cadences above
    its cadence in rising order, and those below it falling, each solved warm from the one
    before (the first from it); `curve.family_gap` per cadence is how much costlier (relative) that
    continuation is than the curve's stride (None where it did not converge: the family ends).
    A continuation that ranks better replaces the curve's stride (gap 0)."""
    start = curve.envelope_free
    assert start is not None, "a curve with its free optimum"
    nlp, c_free = scene.nlp(), start.cadence_spm
    order = sorted(range(len(curve.cadences)), key=lambda k: curve.cadences[k])
    gaps: list = [None] * len(order)
    for side in ([k for k in order if curve.cadences[k] >= c_free],
                 [k for k in reversed(order) if curve.cadences[k] < c_free]):
        previous = start
        for k in side:
            chained = summarise(nlp, warm(nlp, previous, speed, scene.slope, scene.friction, curve.cadences[k]), False)
            if not chained.success:
                break
            if better(chained, curve.strides[k]):
                curve.strides[k] = chained
            kept = curve.strides[k].objective_value
            gaps[k] = (chained.objective_value - kept) / abs(kept)
            previous = chained
    curve.family_gap = gaps


def what_ifs(curves: list[Curve], cadences: list[float],
             changes: tuple[float, ...] = WHAT_IF_PCT) -> list[WhatIf]:
    """Each cadence change (`changes`, % of the runner's cadence cadences[0]; their cadences
    cadences[1:]) against the runner's cadence, nominal and banded, with each band part's width
    and whether both strides are of one family (module doc)."""
    ok = [c for c in curves if c.ok]
    power = np.array([c.power() - c.power()[0] for c in ok])
    impact = np.array([c.impact_loss() - c.impact_loss()[0] for c in ok])
    members = {p: [0] + [i for i, c in enumerate(ok) if c.part == p] for p in BAND_PARTS}
    same = ok[0].same_family if ok[0].family_gap else [True] * len(cadences)
    return [WhatIf(pct, cadences[k], float(power[0, k]), float(impact[0, k]),
                   float(power[:, k].min()), float(power[:, k].max()),
                   float(impact[:, k].min()), float(impact[:, k].max()),
                   tuple((p, float(np.ptp(power[m, k]))) for p, m in members.items() if len(m) > 1),
                   same[0] and same[k])
            for k, pct in enumerate(changes, 1)]


def answer(c, progress=None, nodes: int | None = None, band: bool = True,
           changes: tuple[float, ...] = WHAT_IF_PCT, workers: int = WORKERS,
           transcription: str | None = None, model: str = STRIDE_MODEL) -> StrideAnswer:
    """compare's stride section for a Comparison `c` (its speed, main side, body settings,
    friction and law); `progress(text)` is told of each stage; `band` False: the nominal
    variant and strike only (every band then the nominal value, no other strike: a cheap check,
    not a report); `changes`: the what-ifs' cadence changes (% of the runner's); `workers`: the
    processes of the section's pool (module docstring; band False: none, every solve here);
    `model` the strides' (stride_form.STRIDE_MODELS), `nodes` and `transcription` over its mesh."""
    say = progress or (lambda text: None)
    start = time.perf_counter()
    measured = measured_form(c)
    speed, body = c.steps.speed, c.settings["body"]
    law = c.law if c.law in STRIDE_LAWS else "coulomb"
    notes = [] if law == c.law else [f"the stride's impacts under coulomb (it has no {c.law} impacts)"]
    runner = measured["cadence_spm"]
    cadences = [runner] + [runner * (1 + p / 100) for p in changes]
    nominal = stride_scene(scaled_body(body["mass_kg"], body["height_m"], body["sex"]), speed,
                           measured["strike"], "effort", c.settings["friction"], law, nodes,
                           transcription=transcription, model=model)
    others = [s for s in STRIKES if s != measured["strike"]] if band else []
    variants = band_variants(nominal, body) if band else []
    _ = nominal.nlp().solver  # built before the pool forks: its workers inherit it (the first sweep's)
    with Background(workers if band else 1) as beside:
        # one other strike beside the nominal's free optimum, the rest behind the first sweep
        strikes = beside.start(strike_tasks(nominal, speed, others[:1]))
        strikes += beside.start(strike_tasks(nominal, speed, others[1:]), later=True)
        say(f"stride: the nominal (effort) at {len(cadences)} cadences, {len(others)} other strikes beside it")
        curves = [run_curve("effort (nominal)", nominal, speed, cadences, beside)]
        pair = (curves[0].free, curves[0].own_free)  # the converged ones forward-checked beside the family
        checking = beside.start(check_tasks(nominal, [s for s in pair if s is not None and s.success]))
        # the band's free optima beside the family where their starts are known before it
        frees = None if not curves[0].ok or curves[0].own_free_failed else \
            start_band(variants, band_points(curves[0])[:1], beside)
        say("stride: the free optimum's family along the cadences")
        if curves[0].ok and curves[0].free is not None:
            family(nominal, speed, curves[0])
        checked = iter(beside.results(checking, say))
        curves[0].free, curves[0].own_free = (next(checked) if s is not None and s.success else s for s in pair)
        best = {s: curves[0].free if s == measured["strike"] else None for s in STRIKES}
        best.update(zip(others, beside.results(strikes, say)))
        say(f"stride: {len(variants)} variants warm from the nominal on {min(workers, len(variants)) or 1} processes")
        curves += band_curves(curves[0], variants, beside, say, frees)
    notes += section_notes(curves, best, runner, nominal)
    return StrideAnswer(speed, law, measured, curves, best,
                        what_ifs(curves, cadences, changes) if curves[0].ok else [], notes,
                        time.perf_counter() - start, nominal.settings.nodes, nominal.settings.transcription,
                        model_of(nominal.settings))


def band_curves(nominal: Curve, variants: list[Variant], beside: Background, say,
                frees: list | None = None) -> list[Curve]:
    """The band's variants' curves (variant_curve), in `variants`' order, each variant solved
    warm from the nominal's free optimum and strides (`band_points`; compare_band.start_band on
    `beside`'s pool, `frees` its free optima started before where given); without a nominal
    each is named and left out. A variant's free optimum starts
    from the nominal's sticking strides' own (`Curve.envelope_free`: their least costly where
    that did not converge) where the nominal's slides
    and the variant's NLP is the nominal's (friction, the legs' mass), so with its multipliers:
    RBDS001's four took 29/114/56/84 IPOPT iterations from the sliding one's primal values,
    7/8/8/8 from it on T25 (T35 84/52/55/68 -> 8/10/8/8, RIC 71/67/97/64 -> 16/9/9/10), the same
    optima (objective 3e-6-2.1e-5 higher: the warm start's stop above the optimum; 2026-11-27,
    measured with IPOPT's complementarity tolerance 1e-4, before ipopt_options.WARM_START's 1e-8,
    which ends it within 3e-7 for a few iterations more). Another objective's starts from the
    sliding one's primal values, as before: the metabolic's from the sticking one's was cheaper
    on T25 (objective 0.1776 -> 0.0748) and costlier on T35 (0.1840 -> 0.2089), its landscape's
    local optima more than the start."""
    if not nominal.ok:
        for v in variants:  # each variant's stage, told as the band's are
            say(f"variant {v.name}: no nominal")
        return [Curve(v.name, nominal.cadences, why_not="no nominal", part=v.part) for v in variants]
    points = band_points(nominal)
    if frees is None:
        frees = start_band(variants, points[:1], beside)
    solved = band_results(variants, [frees, start_band(variants, points[1:], beside)], beside, say)
    return [replace(variant_curve(v.name, nominal, solved[v.name]), part=v.part) for v in variants]


def band_points(nominal: Curve) -> list[tuple]:
    """The band's (starts, cadence) per stride of a variant (compare_band.stride_at): its free
    optimum from the nominal's (the sliding one and `Curve.envelope_free`), cadence None, then
    each cadence from the nominal's stride there. The free optimum's starts are known once the
    nominal's curve is (but for a failed sticking free optimum: then the least costly stride,
    which `family` may replace), its strides' once their family is."""
    return [((nominal.free, nominal.envelope_free), None),
            *(((s,), c) for s, c in zip(nominal.strides, nominal.cadences))]
