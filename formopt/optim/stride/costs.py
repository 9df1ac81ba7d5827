"""The stride's objective: named cost terms, each an integral over the half stride divided by
the step length d (per distance) and scaled so that IPOPT sees values of order one:

    J = sum_k  weight_k * scale_k * I_k / d

with the integrals I_k (the transcription's quadrature of the node integrands, ocp.INTEGRANDS):

    effort     int sum_j tau_j^2 dt                           (N^2 m^2 s), scale 100 / (m g)^2
    positive   int sum_j P_j+ dt,  negative  int sum_j P_j- dt  (J), P_j = P_j+ - P_j-, P_j+- >= 0
    impacts    sum of the impacts' T_c + a slide's friction work   (J)
    smoothing  the transcription's (collocation): trapezoid sum_k h |theta''_k+1 - theta''_k|^2,
               Hermite-Simpson sum_k h |theta''_k - 2 theta''_m + theta''_k+1|^2 (per distance);
               with muscles theta'' stacked with their activations' rates times
               StrideSettings.activation_rate_smoothing (actuation.MuscleDriven.smoothed)

    joint_metabolic   int sum_j |tau_j| w_j phi(v_j) / f_V(-v_j) dt  (J; v_j = -tau_j theta'_j / (w_j |tau_j|):
                      Minetti & Alexander 1997's muscle at each joint, `joint_metabolic_rate`)
    muscle_metabolic  int sum_i E'_i dt  (J; mechanics.muscles.metabolic_rate, both legs)
    activation        int sum_legs sum_i V_i a_i^3 / sum_i V_i dt  (s), scale ACTIVATION_SCALE
    force_rate        int sum_legs sum_i V_i F'_i^2 / sum_i V_i dt  (s^-1; F' the normalised tendon
                      forces' rates, mechanics.muscles.force_rate_cost), scale FORCE_RATE_SCALE
    force_rate_abs    int sum_legs sum_i V_i |F'_i| / sum_i V_i dt  (1; |F'| smoothed,
                      mechanics.muscles.FORCE_RATE_SMOOTHING), scale FORCE_RATE_ABS_SCALE
    muscle_rates      int sum_i (F'_i / 10)^2 dt  (s^-1)
    reserves          int sum_j r_j^2 dt  ((N m/kg)^2 s; the muscles' reserve moments)
    moment_rates      int sum_j tau_j'^2 dt  (N^2 m^2 / s; the torque rungs' moment dynamics),
                      scale the effort's, weight T^2 (StrideSettings.moment_time, s)

The objectives (problem.OBJECTIVES): effort; work = W+ (scale 1 / (m g)); metabolic =
W+/0.25 + W-/1.2 (Margaria 1968); joint-metabolic = joint_metabolic (scale 1 / (m g): a cost of
transport); work and metabolic add WORK_REGULARISATION times effort.
With muscles (problem.MUSCLE_OBJECTIVES): metabolic = the muscles' energy (Bhargava et al. 2004,
scale 1 / (m g)) plus StrideSettings.force_rate_weight (problem.FORCE_RATE_WEIGHT, calibrated on
RBDS001 at 3.5 m/s and frozen) times the force-rate term (StrideSettings.force_rate_power 2,
the default, or with power 1 force_rate_abs and its own weight, problem.FORCE_RATE_WEIGHTS):
Bhargava's heat is paid per activation and time, the same per distance for short contacts as
for long, while runners pay for generating force quickly (Kram & Taylor 1990; Kipp, Grabowski & Kram 2018); activation = the
activation term; both add MUSCLE_RATE_REGULARISATION times muscle_rates and
StrideSettings.reserve_weight (problem.RESERVE_WEIGHT) times reserves. With moment dynamics
(StrideSettings.moment_time = T > 0) the torque rungs add T^2 times the moments' squared rates
at the effort's scale: with effort, J = 100/(m g)^2 int sum_j (tau_j^2 + T^2 tau_j'^2) dt / d,
so a moment that changes by dtau within a time t costs about dtau^2 t for being held and
T^2 dtau^2 / t for its change: changes faster than T cost more than the moment itself. Any objective adds
impact_weight times the impacts (scale 1 / (m g)) and SMOOTHING.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca

from ...mechanics.joint_space import GRAVITY
from ...mechanics.muscles import force_velocity
from .actuation import max_rates
from .problem import (
    EFFICIENCY_NEGATIVE,
    EFFICIENCY_POSITIVE,
    SMOOTHING,
    WORK_REGULARISATION,
    StrideSettings,
    force_rate_weight,
)

# The activation term's scale (m/s): its integral per distance (s/m, about 0.01-0.05 a step)
# made of order 0.1-1, as the other terms.
ACTIVATION_SCALE = 10.0
# The force-rate term's scale (s m): its integral per distance (18-20 /(s m) at the optimum
# without the term, 3.9 at the calibrated one: RBDS001, 3.5 m/s, 171.4 steps/min,
# docs/concepts/muscles.md) made of order 0.1.
FORCE_RATE_SCALE = 0.01
# The force-rate term's scale with power 1 (m): its integral per distance (int sum_legs sum_i
# V_i |F'_i| / sum V dt / d: 1.18 /m at weight 1, 24 nodes; 0.69 at the calibrated weight 12:
# RBDS001, 3.5 m/s, graded 80 nodes, docs/concepts/muscles.md) made of order 0.1.
FORCE_RATE_ABS_SCALE = 0.1
# A small weight on the tendon forces' squared rates (per distance) keeps F' from chattering
# where the muscles are slack (problems/muscle_redundancy.py uses the same).
MUSCLE_RATE_REGULARISATION = 1e-4


# -- The torque rungs' metabolic energy, joint by joint (`joint_metabolic_rate`) ---------------
# Minetti & Alexander 1997 (J Theor Biol 186:467): a fully active muscle's metabolic power over
# F_max v_max as a function of its shortening velocity v / v_max,
#     phi(v) = (0.054 + 0.506 v + 2.46 v^2) / (1 - 1.13 v + 12.8 v^2 - 1.64 v^3),
# the coefficients as GaitSym's MAMuscle (Sellers; "Minetti & Alexander, J theor Biol (1997)
# 186, 467-476") and OpenSim Moco's MinettiAlexander1997Metabolics evaluate them. GaitSym uses
# the same phi for lengthening (v < 0, clamped to |v| <= 1); what the paper assumes there the
# search could not confirm. The denominator stays above 0.97 for every v <= 1.2.
MINETTI_NUMERATOR = (0.054, 0.506, 2.46)  # 1, v, v^2
MINETTI_DENOMINATOR = (1.0, -1.13, 12.8, -1.64)  # 1, v, v^2, v^3
# |tau| as sqrt(tau^2 + eps^2) - eps (zero at zero, within eps of |tau|; the velocity v divides
# by sqrt(tau^2 + eps^2)), eps = this (N m/kg) times the body's mass: 5 % of the torque limit,
# 8 % of a stance ankle's 2.5 N m/kg; it undercharges a moment by up to eps (a third of a swing
# hip's 30 N m). RBDS001, torque+springs, heel, 3.5 m/s, one start (2026-11-25): 0.05 N m/kg
# left IPOPT short of convergence after 1000 iterations at 40 nodes; 0.1 converged in 415
# (188 steps/min, objective 0.096), 0.2 in 149 (184 steps/min, 0.079).
JOINT_METABOLIC_SMOOTHING = 0.2
# v is capped smoothly at VELOCITY_CAP (v - w ln(1 + exp((v - cap) / w)), w = CAP_WIDTH) where
# the force-velocity factor still holds (f_V = 0.046 at 0.9): the joints' rates reach 15 rad/s
# (collocation.STATE_RATE), 1.18 omega_max at the ankle, where a muscle makes no force at all.
VELOCITY_CAP, CAP_WIDTH = 0.9, 0.02


def minetti_alexander(v):
    """phi(v) (module constants MINETTI_*): metabolic power over F_max v_max at v = v/v_max."""
    a, b = MINETTI_NUMERATOR, MINETTI_DENOMINATOR
    return (a[0] + v * (a[1] + v * a[2])) / (b[0] + v * (b[1] + v * (b[2] + v * b[3])))


def joint_metabolic_rate(tau, rate, mass: float):
    """Metabolic power (W) of the active joint moments tau (N m, extensor positive) at the joint
    flexion rates theta' (rad/s), both (6,) in JOINTS order: a muscle of Minetti & Alexander's
    at each joint, its activation the moment over what it can make at its velocity,

        E' = sum_j |tau_j| w_j phi(v_j) / f_V(-v_j),  v_j = P_j / (w_j |tau_j|),  P_j = -tau_j theta'_j,

    w_j = JOINT_MAX_RATE, |tau| ~ sqrt(tau^2 + eps^2) - eps before phi and sqrt(tau^2 + eps^2)
    in v, so v -> 0 with tau (eps: JOINT_METABOLIC_SMOOTHING times the mass), v the
    shortening rate over w (positive where tau does positive work, capped at VELOCITY_CAP) and
    f_V mechanics.muscles.force_velocity (De Groote et al. 2016; lengthening positive there).
    Without f_V, work at v > 0.2 would cost less than the work itself."""
    eps = JOINT_METABOLIC_SMOOTHING * mass
    w = max_rates()
    size = ca.sqrt(tau ** 2 + eps ** 2)
    v = -tau * rate / (w * size)
    v = v - CAP_WIDTH * ca.log1p(ca.exp((v - VELOCITY_CAP) / CAP_WIDTH))
    return ca.sum1((size - eps) * w * minetti_alexander(v) / force_velocity(-v))


@dataclass(frozen=True)
class CostTerm:
    """weight * scale * I / d (module docstring), I the integral named `integral`."""

    integral: str
    scale: float
    weight: float = 1.0

    def __call__(self, integrals: dict, distance):
        return self.weight * self.scale * integrals[self.integral] / distance


def own_terms(objective: str, mass: float, muscles: bool = False,
              rate_weight: float | None = None, force_rate_power: int = 2) -> list[CostTerm]:
    """An objective's own terms (problem.OBJECTIVES; module docstring), without its
    regularisation, the impacts and the smoothing; the force-rate term's weight by default its
    power's calibrated one (problem.force_rate_weight)."""
    weight = mass * GRAVITY
    if muscles:
        if objective == "activation":
            return [CostTerm("activation", ACTIVATION_SCALE)]
        rate_weight = force_rate_weight(force_rate_power, rate_weight)
        rate = (CostTerm("force_rate", FORCE_RATE_SCALE, rate_weight) if force_rate_power == 2
                else CostTerm("force_rate_abs", FORCE_RATE_ABS_SCALE, rate_weight))
        return [CostTerm("muscle_metabolic", 1.0 / weight), rate]
    if objective == "effort":
        return [CostTerm("effort", 100.0 / weight ** 2)]
    if objective == "work":
        return [CostTerm("positive", 1.0 / weight)]
    if objective == "joint-metabolic":
        return [CostTerm("joint_metabolic", 1.0 / weight)]
    return [CostTerm("positive", 1.0 / (weight * EFFICIENCY_POSITIVE)),
            CostTerm("negative", 1.0 / (weight * EFFICIENCY_NEGATIVE))]


def terms(settings: StrideSettings, mass: float) -> tuple[CostTerm, ...]:
    """The cost terms of a stride's settings (module docstring)."""
    muscles = settings.muscles is not None
    out = own_terms(settings.objective, mass, muscles, settings.rate_weight, settings.force_rate_power)
    if muscles:
        out += [CostTerm("muscle_rates", 1.0, MUSCLE_RATE_REGULARISATION), CostTerm("reserves", 1.0, settings.reserve_weight)]
    if settings.moment_time:  # T^2 times the effort's scale: sum_j tau_j^2 + T^2 tau_j'^2
        out.append(CostTerm("moment_rates", own_terms("effort", mass)[0].scale, settings.moment_time ** 2))
    if not muscles and needs_power_split(settings):
        out.append(CostTerm("effort", own_terms("effort", mass)[0].scale, WORK_REGULARISATION))
    if settings.impact_weight:
        out.append(CostTerm("impacts", 1.0 / (mass * GRAVITY), settings.impact_weight))
    return (*out, CostTerm("smoothing", 1.0, SMOOTHING))


def objective(cost_terms, integrals: dict, distance):
    """J = sum of the terms (module docstring); symbolic or numeric."""
    return sum(term(integrals, distance) for term in cost_terms)


def needs_power_split(settings: StrideSettings) -> bool:
    """Whether the objective integrates W+ or W- (the power split's slack variables)."""
    return settings.muscles is None and settings.objective in ("work", "metabolic")
