"""What a solved posture problem reports: the optimum, what holds it, how it moves.

- The active set follows from the constraint records (constraints.Record) and IPOPT's
  multipliers: for L = f + lam_g' g + lam_x' w, d(f*)/d(bound) = -lam (envelope theorem).
  One rule (is_active) decides it, on the NLP as IPOPT sees it: the multiplier of the
  normalised objective (weights / sum |weights|), so the verdict does not depend on the
  weights' scale; the multiplier reported is then converted to the objective's units.
  Equalities (the gait held, the landing's event) are what the problem fixes; the optimum is
  *interior* when no inequality or variable bound is active, and *held* by the ones that are.
- Parametric sensitivities d(w*)/dp and d(f*)/dp (p = speed, friction) come from CasADi's
  sensitivity of the NLP solution (the KKT system at the optimum), not from re-solves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..mechanics.impact import ImpactResult
from .objective import UNITS
from .variables import RANGE_OF_MOTION_DEG

CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
# IPOPT's return statuses in plain words (the ones a posture problem meets).
STATUS_EXPLAINED = {
    "Solve_Succeeded": "converged to the requested tolerance",
    "Solved_To_Acceptable_Level": "converged to IPOPT's looser 'acceptable' tolerance",
    "Infeasible_Problem_Detected": "no posture near where this start ended satisfies every "
                                   "constraint (the gait's hip placement out of reach from there, "
                                   "too little friction, bounds that exclude a landing, ...); "
                                   "other starts may still find one",
    "Maximum_Iterations_Exceeded": "stopped at the iteration limit before converging "
                                   "(raise [optimize].max_iterations, or start elsewhere)",
    "Restoration_Failed": "IPOPT lost feasibility and could not regain it from this start",
    "Search_Direction_Becomes_Too_Small": "the steps became too small to make progress: a "
                                          "flat or ill-scaled objective near this point",
    "Error_In_Step_Computation": "the linear system of a step could not be solved (a singular "
                                 "or badly conditioned problem near this point)",
    "Invalid_Number_Detected": "a function returned NaN or inf at a trial point",
    "Diverging_Iterates": "the iterates ran off to very large values",
    "Maximum_CpuTime_Exceeded": "stopped at the time limit before converging",
}
# An IPOPT solution is an optimum only when its own checks hold (PostureProblem.accept):
# every constraint record within FEASIBLE of its bounds (its own units, m or rad: IPOPT's
# constr_viol_tol is 1e-4, looser than a posture needs; the gait's equalities within 1e-9 m);
# and within AGREE, relative to max(1 J, |T_c|), the NLP's T_c against the checked impact map
# at the same state, and a landing problem's T_c_total against the event-driven simulation.
# The NLP evaluates the same map (under Coulomb one mode's closed form; through a landing a
# fixed-step chain), so a larger difference means the state left the mode's region or the
# chain missed an event: the NLP's number is not the model's. 1e-3 is far above round-off
# (accepted optima agree to 1e-12) and below the 1 % that any comparison of optima reports.
FEASIBLE = 1e-6
AGREE = 1e-3
ACTIVE = 1e-6  # relative distance to a bound under which a constraint counts as active
# |multiplier| of the normalised objective (sum of |weights| 1) above which a constraint at
# its bound holds the optimum; below it the bound is touched, not pushed against
MULTIPLIER = 1e-9
DISTINCT = math.radians(0.5)  # optima closer than this in every variable count as one


def explain(status: str) -> str:
    return STATUS_EXPLAINED.get(status, "see IPOPT's documentation of this return status")


@dataclass(frozen=True)
class Constraint:
    """A constraint (or variable bound) at the optimum."""

    name: str
    value: float
    bound: float
    multiplier: float  # d(objective*)/d(bound): objective units per unit of the bound (deg for angles)
    meaning: str
    equality: bool = False  # fixed by the problem (the gait, the landing's event), not a limit


@dataclass(frozen=True)
class Start:
    """One start of the multi-start: where it began and how IPOPT ended it."""

    index: int  # 1-based, in the order run (1 is the reference posture)
    initial: dict[str, float]  # deg or deg/s
    status: str
    converged: bool
    objective: float
    final: dict[str, float]
    iterations: int
    rejected: str = ""  # why a solution IPOPT called converged is not an optimum (accept's checks)


@dataclass(frozen=True)
class Local:
    """The local mode's reading: the radius searched and the marginal values at the reference."""

    radius_deg: float
    marginal: dict[str, float]  # d(objective)/d(angle) at the reference, per deg, others held


@dataclass(frozen=True)
class Optimum:
    """The result of a posture optimisation. `success` is False unless a start converged."""

    success: bool
    status: str
    objective: float
    state: np.ndarray  # STATE, SI: the optimum (or, when not successful, the best last iterate)
    impact: ImpactResult  # checked indicators at `state`
    reference: ImpactResult  # and at the scene's touchdown
    active: tuple[Constraint, ...]
    sensitivity: dict  # d(objective*)/d(speed, friction); d(posture*)/d(speed, friction) in deg
    starts: tuple[Start, ...]
    local_optima: int  # distinct converged optima (0.5 deg apart)
    seed: int
    solve_time: float  # s, median over the starts
    build_time: float  # s
    terms: dict = field(default_factory=dict)  # objective term -> value at the optimum (unweighted)
    weights: dict = field(default_factory=dict)  # the objective: term -> weight
    reference_objective: float = float("nan")  # the objective at the reference posture
    reference_terms: dict = field(default_factory=dict)  # and its terms
    cadence_spm: float | None = None  # the gait's, when given: J per step to W
    local: Local | None = None
    notes: tuple[str, ...] = field(default=())

    @property
    def quantity(self) -> str | None:
        """The term the headline reports: T_c when the objective weighs it, else the objective's
        first term (None without weights). A weighted objective's drop is never called a saving."""
        return "T_c" if "T_c" in self.weights else next(iter(self.weights), None)

    @property
    def saving(self) -> float:
        """The headline quantity at the reference minus at the optimum, unweighted (J per step
        for energies; negative when the optimum costs more of it); without terms, the
        objective's drop."""
        q = self.quantity
        if q not in self.terms or q not in self.reference_terms:
            return self.reference_objective - self.objective
        return self.reference_terms[q] - self.terms[q]

    @property
    def power(self) -> float | None:
        """The saving at the gait's cadence, W (J per step * steps per s); None unless the
        quantity is an energy (J) and the gait gives a cadence."""
        energy = UNITS.get(self.quantity or "T_c") == "J"
        return self.saving * self.cadence_spm / 60.0 if self.cadence_spm and energy else None

    @property
    def held_by(self) -> tuple[Constraint, ...]:
        """The active inequalities and bounds: what keeps the optimum from going further."""
        return tuple(c for c in self.active if not c.equality)

    @property
    def verdict(self) -> str:
        """One line for a table's headline: interior, held by named limits, or no optimum."""
        if self.success:
            return verdict_of(self.active)
        why = next((s.rejected for s in self.starts if s.rejected), "")
        return f"NO OPTIMUM (IPOPT converged, but {why})" if why else f"NO OPTIMUM ({self.status})"

    def to_dict(self) -> dict:
        """JSON-ready dictionary: the outcome, indicators at the optimum and at the reference
        (ImpactResult.to_dict), objective terms, saving (J per step, W), active set, starts.
        The touchdowns in the scene's schema (degrees) are the caller's context."""
        from dataclasses import asdict

        return {
            "success": self.success, "status": self.status, "status_explained": explain(self.status),
            "objective": self.objective, "T_c": self.impact.T_c,
            "impulse": {k: list(v) for k, v in self.impact.impulse.items()},
            "indicators": self.impact.to_dict(),
            "reference": {"indicators": self.reference.to_dict()},
            "verdict": self.verdict, "terms": self.terms,
            "reference_objective": self.reference_objective, "reference_terms": self.reference_terms,
            "saving_of": self.quantity, "saving_per_step": self.saving, "saving_W": self.power,
            "active": [asdict(c) for c in self.active], "held_by": [c.name for c in self.held_by],
            "local": asdict(self.local) if self.local else None, "sensitivity": self.sensitivity,
            "starts": [asdict(s) for s in self.starts], "local_optima": self.local_optima,
            "seed": self.seed, "solve_time_s": self.solve_time, "build_time_s": self.build_time,
            "notes": list(self.notes)}


def verdict_of(active) -> str:
    """'interior optimum', or 'HELD BY' the active inequalities and bounds."""
    held = [c.name for c in active if not c.equality]
    return "HELD BY " + ", ".join(held) if held else "interior optimum"


def is_active(distance: float, bound: float, lam: float, scale: float) -> bool:
    """The one active-set rule: within ACTIVE (relative to max(1, |bound|)) of the bound, and
    the multiplier of the normalised objective, lam / scale (lam: IPOPT's, of the NLP's
    objective scale * normalised objective), above MULTIPLIER."""
    return abs(distance) < ACTIVE * max(1.0, abs(bound)) and abs(lam) / scale > MULTIPLIER


def active_set(records, g, lam_g, lam_x, posture, u, scale, weight) -> tuple[Constraint, ...]:
    """The active constraints and variable bounds at u (is_active on IPOPT's multipliers
    lam_g, lam_x), with d(f*)/d(bound) in the reported objective's units; `scale`: the NLP's
    objective per unit of the normalised one, `weight`: the reported objective per unit of
    the normalised one (sum |weights|)."""
    lam_g, lam_x = np.asarray(lam_g, float).ravel(), np.asarray(lam_x, float).ravel()
    reported = -weight / scale  # d(reported f*)/d(bound) per unit of IPOPT's multiplier
    active = []
    for r, value, lam in zip(records, np.asarray(g, float).ravel(), lam_g):
        if r.equality or is_active(value - r.bound, r.bound, lam, scale):
            active.append(Constraint(r.name, float(value), r.bound, float(lam * reported), r.meaning,
                                     r.equality))
    for k, var in enumerate(posture.variables):
        at = "lower" if u[k] < ACTIVE else "upper" if u[k] > 1 - ACTIVE else None
        if at and is_active(0.0, 1.0, lam_x[k], scale):
            value = math.degrees(posture.lower[k] if at == "lower" else posture.upper[k])
            anatomical = var in RANGE_OF_MOTION_DEG and math.isclose(
                value, RANGE_OF_MOTION_DEG[var][0 if at == "lower" else 1])
            active.append(Constraint(f"{var}_{at}", value, value,
                                     float(lam_x[k] * reported / posture.per_unit()[k]),
                                     f"{var} held at its {at} bound"
                                     + (" (the joint's range of motion, AAOS)" if anatomical else
                                        " (the scene's bounds_deg)")
                                     + ": the objective would keep falling past it"))
    return tuple(active)


def distinct(points, tol=DISTINCT) -> int:
    """How many of the points (arrays, rad) differ by more than tol in some entry."""
    found: list[np.ndarray] = []
    for p in points:
        if all(np.max(np.abs(p - q)) > tol for q in found):
            found.append(p)
    return len(found)
