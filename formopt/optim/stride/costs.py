"""The stride's objective: named cost terms, each an integral over the half stride divided by
the step length d (per distance) and scaled so that IPOPT sees values of order one:

    J = sum_k  weight_k * scale_k * I_k / d

with the integrals I_k (the transcription's quadrature of the node integrands, ocp.INTEGRANDS):

    effort     int sum_j tau_j^2 dt                           (N^2 m^2 s), scale 100 / (m g)^2
    positive   int sum_j P_j+ dt,  negative  int sum_j P_j- dt  (J), P_j = P_j+ - P_j-, P_j+- >= 0
    impacts    sum of the impacts' T_c + a slide's friction work   (J)
    smoothing  sum_k h |theta''_k+1 - theta''_k|^2            (between nodes, per distance)

The objectives (problem.OBJECTIVES): effort; work = W+ (scale 1 / (m g)); metabolic =
W+/0.25 + W-/1.2 (Margaria 1968); the work objectives add WORK_REGULARISATION times effort; any
objective adds impact_weight times the impacts (scale 1 / (m g)) and SMOOTHING.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...mechanics.joint_space import GRAVITY
from .problem import EFFICIENCY_NEGATIVE, EFFICIENCY_POSITIVE, SMOOTHING, WORK_REGULARISATION, StrideSettings


@dataclass(frozen=True)
class CostTerm:
    """weight * scale * I / d (module docstring), I the integral named `integral`."""

    integral: str
    scale: float
    weight: float = 1.0

    def __call__(self, integrals: dict, distance):
        return self.weight * self.scale * integrals[self.integral] / distance


def own_terms(objective: str, mass: float) -> list[CostTerm]:
    """An objective's own terms (problem.OBJECTIVES; module docstring), without its
    regularisation, the impacts and the smoothing."""
    weight = mass * GRAVITY
    if objective == "effort":
        return [CostTerm("effort", 100.0 / weight ** 2)]
    if objective == "work":
        return [CostTerm("positive", 1.0 / weight)]
    return [CostTerm("positive", 1.0 / (weight * EFFICIENCY_POSITIVE)),
            CostTerm("negative", 1.0 / (weight * EFFICIENCY_NEGATIVE))]


def terms(settings: StrideSettings, mass: float) -> tuple[CostTerm, ...]:
    """The cost terms of a stride's settings (module docstring)."""
    out = own_terms(settings.objective, mass)
    if settings.objective != "effort":
        out.append(CostTerm("effort", own_terms("effort", mass)[0].scale, WORK_REGULARISATION))
    if settings.impact_weight:
        out.append(CostTerm("impacts", 1.0 / (mass * GRAVITY), settings.impact_weight))
    return (*out, CostTerm("smoothing", 1.0, SMOOTHING))


def objective(cost_terms, integrals: dict, distance):
    """J = sum of the terms (module docstring); symbolic or numeric."""
    return sum(term(integrals, distance) for term in cost_terms)


def needs_power_split(settings: StrideSettings) -> bool:
    """Whether the objective integrates W+ or W- (the power split's slack variables)."""
    return settings.objective != "effort"
