"""The stride's objective: named cost terms, each an integral over the half stride divided by
the step length d (per distance) and scaled so that IPOPT sees values of order one:

    J = sum_k  weight_k * scale_k * I_k / d

with the integrals I_k (the transcription's quadrature of the node integrands, ocp.INTEGRANDS):

    effort     int sum_j tau_j^2 dt                           (N^2 m^2 s), scale 100 / (m g)^2
    positive   int sum_j P_j+ dt,  negative  int sum_j P_j- dt  (J), P_j = P_j+ - P_j-, P_j+- >= 0
    impacts    sum of the impacts' T_c + a slide's friction work   (J)
    smoothing  sum_k h |theta''_k+1 - theta''_k|^2            (between nodes, per distance)

    muscle_metabolic  int sum_i E'_i dt  (J; mechanics.muscles.metabolic_rate, both legs)
    activation        int sum_legs sum_i V_i a_i^3 / sum_i V_i dt  (s), scale ACTIVATION_SCALE
    muscle_rates      int sum_i (F'_i / 10)^2 dt  (s^-1)
    reserves          int sum_j r_j^2 dt  ((N m/kg)^2 s; the muscles' reserve moments)

The objectives (problem.OBJECTIVES): effort; work = W+ (scale 1 / (m g)); metabolic =
W+/0.25 + W-/1.2 (Margaria 1968); the work objectives add WORK_REGULARISATION times effort.
With muscles (problem.MUSCLE_OBJECTIVES): metabolic = the muscles' energy (scale 1 / (m g))
plus StrideSettings.activation_weight (problem.ACTIVATION_WEIGHT, frozen) times the activation term; activation = the activation term;
both add MUSCLE_RATE_REGULARISATION times muscle_rates and RESERVE_WEIGHT times reserves. Any objective adds impact_weight times
the impacts (scale 1 / (m g)) and SMOOTHING.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...mechanics.joint_space import GRAVITY
from .problem import (
    ACTIVATION_WEIGHT,
    EFFICIENCY_NEGATIVE,
    EFFICIENCY_POSITIVE,
    SMOOTHING,
    WORK_REGULARISATION,
    StrideSettings,
)

# The activation term's scale (m/s): its integral per distance (s/m, about 0.01-0.05 a step)
# made of order 0.1-1, as the other terms.
ACTIVATION_SCALE = 10.0
# A small weight on the tendon forces' squared rates (per distance) keeps F' from chattering
# where the muscles are slack (problems/muscle_redundancy.py uses the same).
MUSCLE_RATE_REGULARISATION = 1e-4
# The reserves' weight (m/s per (N m/kg)^2): 1 N m/kg held over a step costs about 3, ten times a
# stride's whole objective, so the muscles make every moment they can.
RESERVE_WEIGHT = 10.0


@dataclass(frozen=True)
class CostTerm:
    """weight * scale * I / d (module docstring), I the integral named `integral`."""

    integral: str
    scale: float
    weight: float = 1.0

    def __call__(self, integrals: dict, distance):
        return self.weight * self.scale * integrals[self.integral] / distance


def own_terms(objective: str, mass: float, muscles: bool = False,
              activation_weight: float = ACTIVATION_WEIGHT) -> list[CostTerm]:
    """An objective's own terms (problem.OBJECTIVES; module docstring), without its
    regularisation, the impacts and the smoothing."""
    weight = mass * GRAVITY
    if muscles:
        activation = CostTerm("activation", ACTIVATION_SCALE)
        if objective == "activation":
            return [activation]
        return [CostTerm("muscle_metabolic", 1.0 / weight),
                CostTerm("activation", ACTIVATION_SCALE, activation_weight)]
    if objective == "effort":
        return [CostTerm("effort", 100.0 / weight ** 2)]
    if objective == "work":
        return [CostTerm("positive", 1.0 / weight)]
    return [CostTerm("positive", 1.0 / (weight * EFFICIENCY_POSITIVE)),
            CostTerm("negative", 1.0 / (weight * EFFICIENCY_NEGATIVE))]


def terms(settings: StrideSettings, mass: float) -> tuple[CostTerm, ...]:
    """The cost terms of a stride's settings (module docstring)."""
    muscles = settings.muscles is not None
    out = own_terms(settings.objective, mass, muscles, settings.activation_weight)
    if muscles:
        out += [CostTerm("muscle_rates", 1.0, MUSCLE_RATE_REGULARISATION), CostTerm("reserves", 1.0, RESERVE_WEIGHT)]
    elif settings.objective != "effort":
        out.append(CostTerm("effort", own_terms("effort", mass)[0].scale, WORK_REGULARISATION))
    if settings.impact_weight:
        out.append(CostTerm("impacts", 1.0 / (mass * GRAVITY), settings.impact_weight))
    return (*out, CostTerm("smoothing", 1.0, SMOOTHING))


def objective(cost_terms, integrals: dict, distance):
    """J = sum of the terms (module docstring); symbolic or numeric."""
    return sum(term(integrals, distance) for term in cost_terms)


def needs_power_split(settings: StrideSettings) -> bool:
    """Whether the objective integrates W+ or W- (the power split's slack variables)."""
    return settings.muscles is None and settings.objective != "effort"
