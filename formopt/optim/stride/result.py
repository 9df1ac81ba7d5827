"""The solved half stride: the `Stride` result, its energy budget and checks.

Energy budget over the half stride (J), every integral by the trapezoidal rule on the nodes
(the transcription's own quadrature):

    W+ = int sum max(P_j, 0) dt,  W- = int sum max(-P_j, 0) dt,  P_j = -tau_j phi_j' (W)
    impacts = sum of T_c (the flat-foot impact, if any, and the touchdown)
    friction = -int f . v_c dt (the work the held contacts take: zero if they do not move)
    passive = -int tau_pass . theta' dt (the work the joints' passive moments take)
    spring = int tau_spring . phi' dt (what the tendons still hold at toe-off, lost when they
             let go; problem.TENDON_JOINTS; W+- count the active moments only)
    balance = W+ - W- - impacts - friction - passive - spring - m g d sin(slope)

Kinetic and potential energy return to their start over a period, so `balance` is zero up to
the transcription's error (O(h^2)). With muscles, W+- are the joint-level work of the muscles'
net moments (their reserves' included); their own metabolic energy and their tendons' stored
and returned energy are in `Stride.muscles` (muscle_readings.muscle_outputs), outside the
balance. Cost of transport W+ / (m g d); mechanical power W+ / T (T the half-period, d = speed T
the step length).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ...mechanics.joint_space import GRAVITY, JOINTS
from .bounds import held_by_bounds, held_text, on_bounds
from .checks import (
    deepest_stance_knee,
    drift,
    forward,
    half_period,
    impact_check,
    swing_clearance,
    unlike_a_runner,
)
from .collocation import NX, StrideNLP
from .layout import Solved
from .muscle_readings import muscle_outputs
from .ocp import INTEGRANDS, Impact, periodicity, step_length
from .problem import metabolic, other_leg

if TYPE_CHECKING:
    from .refine import MeshCheck

FOOT_POINTS = ("heel_R", "forefoot_R")
# What a stride's own checks may show and still be the stride it claims (`Stride.failed_checks`),
# each several times what optima of a runner show (paper body, 3.5 m/s, heel and forefoot,
# 2026-11-25: at 40 nodes with tendons drift 0.3-0.6 mm, forward 0.02-0.03 rad, balance 1e-9
# (imposed), impact maps 1e-13 J, periodicity 1e-16; at 24 nodes without tendons drift 1.7-1.9
# mm and balance 0.4-1.1 % of W+, the trapezoid's O(h^2)):
TOLERANCES = {
    "drift_m": 5e-3,  # a held point that moves 5 mm is half a shoe sole's compression
    "forward_theta": 0.1,  # rad (6 deg): beyond it the optimal moments do not make the stride
    "balance_relative": 5e-2,  # of W+: a budget 5 % off misstates the cost it reports
    "impact_map_J": 1e-6,  # the joint-space impact against formopt's natural-coordinate map
    "impact_nlp_J": 1e-5,  # the NLP's T_c against the exact impact at its state (IPOPT's tol)
    "periodicity": 1e-6,  # m or rad: the touchdown equals the start (a constraint of the NLP)
    # the muscles' reserve moments (N m per kg), their largest mean over 10 ms
    # (muscle_readings.reserve_mean): 0.1 is 6 N m at 62 kg, a tenth of the hip flexors' toe-off
    # moment; beyond it the muscles do not make the stride they are credited with
    "reserve_nm_per_kg": 0.1,
}
# A sticking impulse this close to the friction cone's edge (|1 - mu_c / mu|) is on it (the
# impacts' `friction_margin` and `on_cone_edge`): it uses all the friction. Valid up to mu_c =
# mu (1 + CONE_EDGE), under no-slip and under Coulomb (whose map may call it a slide by
# round-off): the edge is the sticking condition's own boundary (|p_t| <= mu p_n), where
# Coulomb's sliding impulse equals the sticking one with no slip after it, and IPOPT's
# tolerance leaves an optimum on it at mu (1 +- 2e-6) (the work objective's heel touchdown:
# 0.800001 at mu 0.8, 2026-11-25), and a small impulse further (a sliding forefoot strike's
# heel drop of 8e-5 J: 0.800053); formopt's Coulomb map absorbs the same T_c there within
# 2e-8 J on the shipped scenes.
CONE_EDGE = 1e-4
# A point that reaches the ground this slowly (m/s) touches it rather than leaves it, and is held
# from the impact on like any other: a flat touchdown's second point, or a forefoot set down with
# no collision of its own, arrives at 3e-9 to 5e-9 m/s (round-off; the paper body's flat
# strike and its Hermite-Simpson heel strike at 80 nodes, 2026-11-25), which a strict sign test
# called invalid.
GRAZING_MPS = 1e-6


@dataclass
class Stride:
    """A periodic half stride (SI inside; degrees only in `touchdown.angles_deg`)."""

    success: bool
    status: str
    iterations: int
    solve_s: float
    build_s: float
    speed_mps: float
    slope: float  # rad
    friction: float
    law: str
    strike: str
    objective: str
    objective_value: float
    cadence_spm: float
    step_length_m: float
    half_period_s: float
    stance_s: float
    flight_s: float
    duty_factor: float  # stance / stride time
    peak_vertical_grf_bw: float
    touchdown: dict
    impacts: list
    budget: dict
    cost_of_transport: float  # W+ / (m g d), dimensionless (J/(kg m) divided by g)
    mechanical_power_W: float
    checks: dict
    phases: list  # (name, duration s)
    mass_kg: float
    t: np.ndarray = field(repr=False)  # (n,) s, node times (a phase boundary appears twice)
    phase: list = field(repr=False)  # phase name per node
    theta: np.ndarray = field(repr=False)  # (n, 9) THETA, m and rad
    thetad: np.ndarray = field(repr=False)  # (n, 9)
    tau: np.ndarray = field(repr=False)  # (n, 6) N m, JOINTS, extensor positive
    force: np.ndarray = field(repr=False)  # (n, 2, 2) N, world (x, z) per FOOT_POINTS
    solved: Solved | None = field(repr=False, default=None)  # the raw solution (a warm start)
    tau_spring: np.ndarray | None = field(repr=False, default=None)  # (n, 6) N m, the tendons' moments
    # the muscles (actuation "muscles"): names (both legs, "<muscle>_R", ...), activation and
    # tendon force (N) histories (n, 16), per muscle the tendon energy stored and returned (J)
    muscles: dict | None = field(repr=False, default=None)
    # the phases held by a duration bound ({"phase", "duration_s", "side": "low" | "high",
    # "bound_s"}, bounds.on_bounds): the bound, not the mechanics, sets them
    on_bound: list = field(default_factory=list)
    # the other variables on one of the solve's bounds (bounds.held_by_bounds: states, rates,
    # accelerations, forces, the torque limit), grouped by variable
    held: list = field(default_factory=list)
    # m: the swing foot's least height while the other foot holds the ground (checks.swing_clearance;
    # the NLP holds it at or above StrideSettings.clearance)
    swing_clearance_m: float = float("nan")
    # deg: the stance knee's deepest flexion over the phases with a contact (`deepest_stance_knee`;
    # beyond CROUCH_DEG the remarks call the stride crouched)
    stance_knee_deg: float = float("nan")
    # the global search that found it (search.global_optimum: its spend, what it spent, the
    # optima it met and their spread); None: solved from the given starts (`optimum`)
    search: dict | None = None
    # the stride solved again on twice its nodes from itself (refine.mesh_check: what that moved
    # its cadence and cost); None: not checked
    mesh_check: MeshCheck | None = None

    def bound_text(self) -> str:
        """The phases on a duration bound, in words ("" when none)."""
        return "; ".join(f"{b['phase']} phase {b['duration_s'] * 1e3:.1f} ms on its {b['side']} bound "
                         f"({b['bound_s'] * 1e3:g} ms)" for b in self.on_bound) + \
            (": set by the bound, not the mechanics" if self.on_bound else "")

    @property
    def unlike_a_runner(self) -> list[str]:
        """Where the stride is far from a runner's (checks.unlike_a_runner): a crouch, a stiff landing."""
        return unlike_a_runner(self.stance_knee_deg, self.budget.get("impacts_J", 0.0))

    @property
    def remarks(self) -> list[str]:
        """What a valid stride's headline must say besides its numbers: each phase held by a
        duration bound, a crouch or a stiff landing (checks.unlike_a_runner), the other bounds
        of the solve it sits on (bounds.held_text), each
        sliding touchdown, and each sticking impact on the friction cone's edge (valid: the
        no-slip condition is |p_t| <= mu p_n, and Coulomb's sticking mode ends there; but it
        uses all the friction, so the friction sets the optimum there)."""
        out = [self.bound_text()] if self.on_bound else []
        out += self.unlike_a_runner
        out += [held_text(self.held)] if self.held else []
        out += self.slides
        return out + [f"{i['point']} impact of leg {i['leg']} on the friction cone's edge (mu_c "
                      f"{i['mu_c']:.4f}, mu {self.friction:g}), solved sticking: valid under {i['law']}, "
                      "but it uses all the friction" for i in self.impacts if i["on_cone_edge"]]

    @property
    def slides(self) -> list[str]:
        """Each sliding touchdown in words: how long and how far it slides."""
        return [f"{i['point']} impact of leg {i['leg']} solved sliding under {i['law']}: it slides "
                f"{i['slide_s'] * 1e3:.0f} ms and {abs(i['slide_m']) * 100:.1f} cm"
                for i in self.impacts if i["mode"] == "slide"]

    @property
    def failed_checks(self) -> list[str]:
        """The checks beyond their TOLERANCES ("drift_m 0.24 > 0.005") and the impacts that
        break the scene's contact law. The forward check counts where it was run (`formopt
        stride`, the API's strides, compare's free optima: `forward_checked`); maps and
        compare's curves do not simulate, so their `valid` holds every check but that one."""
        failed = [f"{k} {self.checks[k]:.3g} > {limit:g}" for k, limit in TOLERANCES.items()
                  if k in self.checks and not self.checks[k] <= limit]
        return failed + [f"{i['point']} impact of leg {i['leg']} invalid under {i['law']} "
                         f"(mu_c {i['mu_c'] if i['mu_c'] is None else round(i['mu_c'], 4)}, "
                         f"approach {i['approach_mps']:.3f} m/s)" for i in self.impacts if not i["valid"]]

    @property
    def valid(self) -> bool:
        """Converged, every impact valid under the scene's law and every check within its
        tolerance: the stride the model says it is."""
        return self.success and not self.failed_checks

    def to_dict(self) -> dict:
        """JSON-ready summary (no histories), with `valid` and `failed_checks`."""
        skip = {"t", "phase", "theta", "thetad", "tau", "force", "solved", "tau_spring", "muscles"}
        out = {k: getattr(self, k) for k in self.__dataclass_fields__ if k not in skip}
        if self.mesh_check is not None:
            out["mesh_check"] = self.mesh_check.to_dict()
        if self.muscles is not None:  # the per-muscle figures, not the histories
            out["muscles"] = {k: v for k, v in self.muscles.items() if k not in ("activation", "tendon_force_N")}
        return {**out, "valid": self.valid, "failed_checks": self.failed_checks, "remarks": self.remarks}


def rank(stride: Stride) -> tuple:
    """The one order of strides, wherever one is chosen (`min(strides, key=rank)`): valid
    before invalid, converged before not, then the least objective (per distance)."""
    return not stride.valid, not stride.success, stride.objective_value


def histories(nlp: StrideNLP, blocks: dict, slope: float):
    """Node histories (t, phase, theta, theta', tau, tau_spring, force) over the half stride: tau
    the active moments, tau_spring the springs' (the tendons in parallel; with tau the net)."""
    t, names, X, U, springs, force = [], [], [], [], [], []
    start = 0.0
    tangent, normal = np.array([np.cos(slope), np.sin(slope)]), np.array([-np.sin(slope), np.cos(slope)])
    for i, (phase, c) in enumerate(zip(nlp.phases, nlp.columns)):
        T = blocks[f"T_{phase.name}"].item()
        t.append(start + nlp.times(i, T))
        names += [phase.name] * (c)
        X.append(blocks[f"X_{phase.name}"])
        active, passive = nlp.moments(blocks, i)
        U.append(active)
        springs.append(passive)
        F = nlp.mass * GRAVITY * blocks[f"F_{phase.name}"]
        f = np.zeros((c, len(FOOT_POINTS), 2))
        for k, (point, axis) in enumerate(phase.rows):
            f[:, FOOT_POINTS.index(point)] += np.outer(F[k], tangent if axis == "t" else normal)
        force.append(f)
        start += T
    states = np.hstack(X).T
    return (np.concatenate(t), names, states[:, :NX], states[:, NX:], np.hstack(U).T, np.hstack(springs).T,
            np.concatenate(force))


def budget(nlp: StrideNLP, solved: Solved, impacts: float) -> dict:
    """The energy budget (module docstring), J, from the NLP's own node integrands
    (StrideNLP.integrands: the same functions and quadrature the NLP integrates); also the
    metabolic figure."""
    sums = dict.fromkeys(("positive", "negative", "friction", "passive", "spring"), 0.0)
    joints = [INTEGRANDS.index(f"power_{j}") for j in JOINTS]
    for L, w in nlp.integrands(solved.blocks, solved.parameters):
        power = L[joints]
        sums["positive"] += float(np.maximum(power, 0).sum(axis=0) @ w)
        sums["negative"] += float(np.maximum(-power, 0).sum(axis=0) @ w)
        sums["friction"] -= float(L[INTEGRANDS.index("contact")] @ w)
        sums["passive"] -= float(L[INTEGRANDS.index("passive")] @ w)
        sums["spring"] += float(L[INTEGRANDS.index("spring")] @ w)
    par = solved.parameters
    climb = nlp.mass * GRAVITY * step_length(par["speed"], half_period(nlp, solved.blocks)) * np.sin(par["slope"])
    balance = (sums["positive"] - sums["negative"] - impacts - sums["friction"] - sums["passive"]
               - sums["spring"] - climb)
    return {"positive_work_J": sums["positive"], "negative_work_J": sums["negative"],
            "impacts_J": impacts, "friction_J": sums["friction"], "passive_J": sums["passive"],
            "spring_J": sums["spring"],
            "climb_J": climb, "balance_J": balance,
            "metabolic_J": metabolic(sums["positive"], sums["negative"])}


def impacts(nlp: StrideNLP, blocks: dict, slope: float, mu: float) -> list[dict]:
    """Each impact of the half stride: the NLP's T_c and formopt's impact map at its state;
    `mode` the NLP's (stick, or slide for a sliding touchdown), `valid` when
    the points approach (or graze: GRAZING_MPS), the ground pushes and the law agrees (no-slip: within the friction
    cone; Coulomb: formopt's Coulomb map gives the same mode); a sticking impact's
    `friction_margin` 1 - mu_c / mu (None sliding) and `on_cone_edge` (under CONE_EDGE)."""
    out, time = [], 0.0
    transitions: list[tuple] = []
    for i, phase in enumerate(nlp.phases):
        T = blocks[f"T_{phase.name}"].item()
        time += T
        if i + 1 < len(nlp.phases) and nlp.impact_before(i + 1):
            after = nlp.phases[i + 1]
            transitions.append((after.rows, blocks[f"X_{phase.name}"][:, -1],
                                blocks[f"X_{after.name}"][NX:, 0], time, _added(nlp, i + 1), None))
    end = blocks[f"X_{nlp.phases[-1].name}"][:, -1]
    slip = nlp.settings.slip
    sliding = (other_leg(nlp.phases[0].sliding), slip, mu) if nlp.phases[0].sliding else None
    transitions.append((nlp.touchdown_rows, end, blocks["V_touchdown"].ravel(), time,
                        tuple(dict.fromkeys(p for p, _ in nlp.touchdown_rows)), sliding))
    M = nlp.js.mass
    law = nlp.settings.law
    for rows, X, plus, t, points, slides in transitions:
        th, minus = X[:NX], X[NX:]
        Mk = np.asarray(M(th), float)
        T_c = 0.5 * minus @ Mk @ minus - 0.5 * plus @ Mk @ plus
        check = impact_check(nlp.js, rows, th, minus, slope, mu, slides)
        approach = max(float(nlp.js.points[p](th, minus, slope)[1][1]) for p in points)
        mode = "slide" if slides else "stick"
        margin = None if check["mu_c"] is None or slides else float(1.0 - check["mu_c"] / mu)
        edge = margin is not None and abs(margin) < CONE_EDGE
        # on the cone's edge the sticking impulse is Coulomb's sliding one too (no slip after it)
        agrees = (margin is not None and margin > -CONE_EDGE if law == "no-slip"
                  else check["coulomb_mode"] == mode or (mode == "stick" and edge))
        valid = check["impulse_n"] > 0 and approach < GRAZING_MPS and agrees
        entry = {"point": "+".join(p.rsplit("_", 1)[0] for p in points),
                 "leg": points[0][-1], "time_s": t, "T_c": float(T_c), "law": law,
                 "mode": mode,
                 "mu_c": check["mu_c"], "valid": bool(valid),
                 "friction_margin": margin, "on_cone_edge": bool(edge),
                 "T_c_exact": check["T_c"], "T_c_formopt": check["T_c_formopt"],
                 "impact_map_difference_J": check["difference_J"],
                 "coulomb_mode": check["coulomb_mode"], "T_c_coulomb": check["T_c_coulomb"],
                 "impulse_Ns": [check["impulse_t"], check["impulse_n"]],
                 "approach_mps": approach}
        if slides:
            entry.update(slide(nlp, blocks, slope, mu))
        out.append(entry)
    return out


def slide(nlp: StrideNLP, blocks: dict, slope: float, mu: float) -> dict:
    """The slide after a sliding touchdown (phase 0): its duration `slide_s` (s), the distance
    the point slid along the ground `slide_m` (m, signed), its slip sign `slip`, the least
    s v_t at its nodes (m/s), the friction work `slide_friction_J` (J, mu f_n |v_t| integrated
    by the transcription's quadrature) and `stick_friction_ratio` of the sticking phases after it."""
    phase, n, c, slip = nlp.phases[0], nlp.split[0], nlp.columns[0], nlp.settings.slip
    X, T = blocks[f"X_{phase.name}"], blocks[f"T_{phase.name}"].item()
    point = nlp.js.points[phase.sliding]
    tangent = np.array([np.cos(slope), np.sin(slope)])
    r0, r1 = (np.asarray(point(X[:NX, k], np.zeros(NX), slope)[0], float).ravel() for k in (0, -1))
    v_t = np.array([float(point(X[:NX, k], X[NX:, k], slope)[1][0]) for k in range(c)])
    f = blocks[f"F_{phase.name}"][phase.rows.index((phase.sliding, "t"))] * nlp.mass * GRAVITY
    w = np.asarray(nlp.transcription.weights(T / n, nlp.steps[0]), float).ravel()
    return {"slide_s": T, "slide_m": float((r1 - r0) @ tangent), "slip": int(slip),
            "slip_min_mps": float((slip * v_t).min()),
            "slide_friction_J": float(-np.sum(w * f * v_t)),
            "stick_friction_ratio": stick_friction_ratio(nlp, blocks, mu)}


def stick_friction_ratio(nlp: StrideNLP, blocks: dict, mu: float) -> float:
    """The largest |f_t| / (mu sum f_n) over the sticking stance nodes (<= 1: the cone holds;
    nodes with sum f_n under 1e-6 body weights left out)."""
    worst = 0.0
    for phase in nlp.phases:
        F = blocks[f"F_{phase.name}"]
        for k, (point, axis) in enumerate(phase.rows):
            if axis == "t" and point != phase.sliding:
                normal = sum(F[j] for j, (_, a) in enumerate(phase.rows) if a == "n")
                pushed = normal > 1e-6
                if pushed.any():
                    worst = max(worst, float((np.abs(F[k][pushed]) / (mu * normal[pushed])).max()))
    return worst


def summarise(nlp: StrideNLP, solved: Solved, simulate: bool = True) -> Stride:
    """The Stride of a solution, with its budget and checks (`simulate`: the forward check)."""
    b, par = solved.blocks, solved.parameters
    speed, slope, mu = par["speed"], par["slope"], par["mu"]
    m = nlp.mass
    T = half_period(nlp, b)
    step = step_length(speed, T)
    durations = [(p.name, b[f"T_{p.name}"].item()) for p in nlp.phases]
    stance = sum(d for p, (_, d) in zip(nlp.phases, durations) if p.rows)
    t, names, theta, thetad, tau, tau_spring, force = histories(nlp, b, slope)
    found = impacts(nlp, b, slope, mu)
    energy = budget(nlp, solved, sum(i["T_c"] for i in found))
    start, end = theta[0], theta[-1]
    periodic = np.abs(np.asarray(periodicity(end, b["V_touchdown"].ravel(), np.r_[start, thetad[0]], step,
                                             slope), float)).max()
    checks = {"periodicity": float(periodic),
              "impact_map_J": max(i["impact_map_difference_J"] for i in found),
              "impact_nlp_J": max(abs(i["T_c"] - i["T_c_exact"]) for i in found),
              "drift_m": drift(nlp, b, slope),
              "balance_relative": abs(energy["balance_J"]) / max(energy["positive_work_J"], 1e-9)}
    if simulate:
        checks.update(forward_checks(nlp, b, par))
    strike_point = "heel_R" if nlp.settings.strike != "forefoot" else "forefoot_R"
    r = np.asarray(nlp.js.points[strike_point](start, np.zeros(NX), slope)[0], float).ravel()
    end_v = b[f"X_{nlp.phases[-1].name}"][NX:, -1]
    touchdown = {"angles_deg": {"trunk": float(np.degrees(start[2])),
                                **{j[:-2]: float(np.degrees(start[3 + k])) for k, j in enumerate(JOINTS[:3])}},
                 "swing_angles_deg": {j[:-2]: float(np.degrees(start[6 + k])) for k, j in enumerate(JOINTS[:3])},
                 "hip_from_strike_m": {"ahead": float(start[0] - r[0]), "above": float(start[1] - r[1])},
                 "hip_velocity_mps": [float(end_v[0]), float(end_v[1])]}
    vertical = force[:, :, 1].sum(axis=1)
    positive = energy["positive_work_J"]
    return Stride(
        success=solved.success, status=solved.status, iterations=solved.iterations,
        solve_s=solved.solve_s, build_s=nlp.build_s, speed_mps=speed, slope=slope, friction=mu,
        law=nlp.settings.law, strike=nlp.settings.strike, objective=nlp.settings.objective,
        objective_value=solved.objective, cadence_spm=60.0 / T, step_length_m=step,
        half_period_s=T, stance_s=stance, flight_s=T - stance, duty_factor=stance / (2 * T),
        peak_vertical_grf_bw=float(vertical.max() / (m * GRAVITY)), touchdown=touchdown,
        impacts=found, budget=energy, cost_of_transport=positive / (m * GRAVITY * step),
        mechanical_power_W=positive / T, checks=checks, phases=durations, mass_kg=m,
        t=t, phase=names, theta=theta, thetad=thetad, tau=tau, force=force, solved=solved,
        tau_spring=tau_spring, muscles=muscle_outputs(nlp, solved, checks, t),
        on_bound=on_bounds(durations, nlp.settings.duration), held=held_by_bounds(nlp, b),
        swing_clearance_m=swing_clearance(nlp, b, slope), stance_knee_deg=deepest_stance_knee(nlp, names, theta))


def forward_checks(nlp: StrideNLP, blocks: dict, parameters: dict) -> dict:
    """The forward check's entries of `Stride.checks` (checks.forward: the controls replayed
    through the dynamics, reset to the trajectory at each phase, and open loop)."""
    sim = forward(nlp, blocks, parameters)
    return dict(forward_theta=sim["reset_theta"], forward_per_phase=sim["reset_per_phase"],
                open_loop_theta=sim["theta"], open_loop_thetad=sim["thetad"],
                open_loop_per_phase=sim["per_phase_theta"], open_loop_periodicity=sim["periodicity"],
                **{f"forward_{k}": v for k, v in sim.items() if k.startswith(("slip_", "moments_"))})


def forward_checked(nlp: StrideNLP, stride: Stride) -> Stride:
    """`stride`, summarised without the forward check (`summarise(..., simulate=False)`), with it
    added: under `nlp`, or its variant of the stride's touchdown mode (the sliding one, with the
    impact's slip sign, that local.touchdown_mode solved it with). A stride without its solution
    is returned as it is."""
    if stride.solved is None or "forward_theta" in stride.checks:
        return stride
    touchdown = stride.impacts[-1]
    if touchdown["mode"] != nlp.settings.touchdown:
        nlp = nlp.variant(touchdown=touchdown["mode"], slip=touchdown.get("slip", nlp.settings.slip))
    checks = {**stride.checks, **forward_checks(nlp, stride.solved.blocks, stride.solved.parameters)}
    return replace(stride, checks=checks)


def _added(nlp: StrideNLP, i: int) -> tuple[str, ...]:
    """The points the impact before phase i adds."""
    transition = nlp.ocp.transitions[i - 1]
    return transition.points if isinstance(transition, Impact) else ()
