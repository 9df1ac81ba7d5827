"""IPOPT searches the touchdown posture that absorbs the least energy (or another objective).

The NLP is assembled here from its parts: the parameterisation (variables.Posture: decision
vector, parameters, touchdown state), the objective (objective.py: weighted, normalised
terms), the constraint records (constraints.py: name, bounds, meaning, expression) and the
contact law at the impact; multistart.solve runs it and solution.py reports the optimum (what
holds it, its sensitivities). Derivatives are CasADi's (exact Hessian for the impact alone).

Under Coulomb the impact's mode and sliding direction are fixed for each solve (from the
reference touchdown unless given): the mode's closed form is smooth, and the inequalities that
bound the mode's region are constraints. An optimum held by one of them is not left there:
solve() solves again in the neighbouring mode (NEIGHBOURS), and on until no region holds the
optimum or every neighbour has been tried, and keeps the best.

With [optimize.gait] the gait's placement is held: the hip's position over the strike point
(and optionally the foot's speed along the ground) are equalities, the hip velocity and the
segment rates stay the reference's, and the free variables are what the runner chooses for
that placement (foot angle, the knee-ankle split, trunk lean).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Any

import casadi as ca
import numpy as np

from ..mechanics import contact, limits
from ..mechanics.compiled import cached_nlpsol
from ..mechanics.errors import InputError
from ..mechanics.impact import Impact, ImpactResult, check_ground, impact_function
from ..mechanics.integrators import DEFAULT_INTEGRATOR
from ..mechanics.landing import Joints, LandingModel, simulate_state
from ..mechanics.landing_function import landing_function
from ..mechanics.model import STRIKES, Model, ground_axes, positions
from . import multistart
from .constraints import posture_constraints, stack
from .objective import STANCE_PEAK_BW, normalised, support
from .solution import AGREE, CONVERGED, FEASIBLE, Optimum, active_set, is_active
from .variables import FRICTION, PARAMETERS, SLOPE, Posture

LANDING_STEPS = 40  # RK4 steps over the contact phase between the two impacts
GAIT_TOLERANCE = 1e-10  # m: IPOPT's constr_viol_tol when the gait's equalities are held


@dataclass(frozen=True)
class Gait:
    """What the runner's gait fixes ([optimize.gait])."""

    hip_from_strike: tuple[float, float] | None = None  # m, (along, normal to the ground); None: the reference's
    foot_velocity: float | None = None  # m/s, the strike point's velocity along the ground before the impact
    cadence_spm: float | None = None  # steps per minute: J per step to W


@dataclass(frozen=True)
class Problem:
    """What to optimise: variables (STATE names) with SI bounds, an objective, constraints."""

    variables: tuple[str, ...]
    lower: tuple[float, ...]  # rad or rad/s
    upper: tuple[float, ...]
    objective: dict[str, float]  # term (objective.OBJECTIVES) -> weight; minimise the weighted sum
    max_overstride: float | None = None  # m, strike point ahead of the hip along the ground
    hip_height: tuple[float, float] | None = None  # m, above the strike point, normal to the ground
    starts: int = 8
    seed: int = 0
    tolerance: float = 1e-8
    contact_friction: bool = False  # |f_t| <= mu f_n, f_n >= 0 through the contact phase
    max_iterations: int = 200  # IPOPT's max_iter
    max_slip: float | None = None  # m/s, |tangential velocity| of the strike point after the impact
    gait: Gait | None = None
    radius: float | None = None  # rad: local mode, the best posture within this of the reference
    stance_peak_bw: float = STANCE_PEAK_BW  # the support term's force, body weights

    def __post_init__(self):
        """The solver's settings within mechanics.limits (a scene's [optimize] table is checked
        by the loader; this holds for solve()'s overrides and Problems built in code)."""
        for name, allowed, whole in (("starts", limits.STARTS, True), ("seed", limits.SEED, True),
                                     ("tolerance", limits.TOLERANCE, False),
                                     ("max_iterations", limits.MAX_ITERATIONS, True)):
            limits.check(name, getattr(self, name), allowed, whole)
        if not all(math.isfinite(v) for v in (*self.lower, *self.upper)):
            raise InputError(f"bounds of {', '.join(self.variables)}: must be finite numbers")

    @property
    def landing(self) -> bool:
        """Whether the problem needs the whole landing (T_c_total or contact-phase friction)."""
        return "T_c_total" in self.objective or self.contact_friction


class Inadmissible(InputError):
    """A contact law, strike and problem that do not go together; `key` names the scene key
    that says so, `reason` why."""

    def __init__(self, key: str, reason: str):
        self.key, self.reason = key, reason
        super().__init__(f"{key}: {reason}")


def admissible(law: str, strike: str, problem: Problem) -> None:
    """The one rule for what a contact law (contact.LAWS), a strike (model.STRIKES) and a
    problem admit; raises Inadmissible (an InputError) naming the scene key."""
    if law not in contact.LAWS:
        raise Inadmissible("ground.contact", f"{law!r}: expected one of {', '.join(contact.LAWS)}")
    if strike not in STRIKES:
        raise Inadmissible("touchdown.strike", f"{strike!r}: expected one of {', '.join(STRIKES)}")
    flat = strike == "flat"
    if flat and "ankle" in problem.variables:
        raise Inadmissible("optimize.variables", "'ankle' follows from a flat strike (the sole "
                                                 "on the ground); leave it out")
    if problem.landing and flat:
        raise Inadmissible("optimize.objective", "the landing (T_c_total, contact_friction) "
                                                 "starts with a heel or forefoot strike, not a flat one")
    if problem.landing and law != "no-slip":
        raise Inadmissible("ground.contact", "the landing objective (T_c_total, contact_friction) "
                                             f"holds the strike point: no-slip only, not {law!r}")
    if law == "coulomb" and flat:
        raise Inadmissible("ground.contact", "a flat strike's Coulomb impact (two contacts, the "
                                             "velocity-level law) switches mode inside the NLP: "
                                             "optimise it as \"no-slip\" or \"frictionless\"")
    if problem.max_slip is not None and law == "no-slip":
        raise Inadmissible("optimize.max_slip_mps", "bounds the slip that ground.contact = "
                                                    "\"coulomb\" or \"frictionless\" allows; "
                                                    "under \"no-slip\" the foot never slips")
    if problem.gait and problem.gait.foot_velocity is not None and flat:
        raise Inadmissible("optimize.gait.foot_velocity_mps", "is the strike point's speed: a "
                                                              "heel or forefoot strike, not a flat one")


# Coulomb: (mode, region row) -> the modes across that boundary (contact.coulomb_in_mode's rows:
# 0 the sliding direction s v_t >= 0 (across it: the other direction); SLIDE 1 k_n > 0 (no
# neighbour: the sliding impact stops pressing), 2 the slide ends before v_t reaches zero;
# STICK and REVERSE 1 v_t reaches zero first, 2 sticking holds (STICK) or not (REVERSE)).
NEIGHBOURS = {(contact.SLIDE, 2): (contact.STICK, contact.REVERSE),
              (contact.STICK, 1): (contact.SLIDE,), (contact.REVERSE, 1): (contact.SLIDE,),
              (contact.STICK, 2): (contact.REVERSE,), (contact.REVERSE, 2): (contact.STICK,)}


def neighbours(mode: tuple[int, int], row: int) -> list[tuple[int, int]]:
    """The (mode, sliding direction) pairs across region row `row` (0-based) of `mode`."""
    if row == 0:
        return [(mode[0], -mode[1])]
    return [(m, mode[1]) for m in NEIGHBOURS.get((mode[0], row), ())]


def ipopt_options(problem: Problem, hessian: str) -> dict:
    """IPOPT's options of a touchdown NLP: quiet, the problem's tolerance and iterations, the
    Hessian ("exact" or "limited-memory"), a gait's looser constraint tolerance."""
    options = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
               "ipopt.tol": problem.tolerance, "ipopt.max_iter": problem.max_iterations,
               "ipopt.hessian_approximation": hessian}
    if problem.gait is not None:
        options["ipopt.constr_viol_tol"] = GAIT_TOLERANCE
    return options


class PostureProblem:
    """The NLP of one model, strike, ground and problem; solve() runs the multi-start.

    Public parts: `posture` (the parameterisation), `records` (constraint records, with
    `lbg`, `ubg`), `nlp` (x, p, f, g), `objective_function(w, p)` (the weighted objective,
    unnormalised), `terms_function(w, p)` (each term), `constraint_function(w, p)`,
    `solve_from(w0, p)`, `solve()`, `sensitivity(w, p, lam_x, lam_g)`.
    """

    def __init__(self, model: Model, strike: str, reference, problem: Problem,
                 slope: float, friction: float, joints: Joints | None = None,
                 duration: float = 0.2, graph: str = "SX", compiled: bool = False,
                 hessian: str = "auto", integrator: str = DEFAULT_INTEGRATOR, law: str = "no-slip",
                 mode: tuple[int, int] | None = None):
        """`reference`: the touchdown state (STATE, SI) whose other values stay fixed;
        `slope` (rad), `friction`: the problem's ground (p0; parameters of the NLP);
        `duration` (s): the longest landing; `graph`, `compiled`, `hessian` ("auto": exact
        for impacts, limited-memory through a landing), `integrator`: scene [numerics];
        `law`: the contact law at the impact (contact.LAWS); `mode`: Coulomb's (mode, sliding
        direction) to fix (default the reference's). The objective's terms come from `_terms`;
        this assembles the NLP from them in order (normalised objective, records, solver)."""
        t0 = time.perf_counter()
        admissible(law, strike, problem)
        self.model, self.strike, self.problem = model, strike, problem
        self.slope, self.friction, self.law = slope, friction, law
        self.reference = np.asarray(reference, float)
        self.posture = Posture(model, strike, reference, problem.variables, problem.lower,
                               problem.upper, friction, slope)
        self.impact = Impact(model, strike, slope, friction, law=law)  # checks every optimum
        self.mode: tuple[int, int] | None = (mode or self._coulomb_mode()) if law == "coulomb" else None
        self._arguments = dict(model=model, strike=strike, reference=reference, problem=problem,
                               slope=slope, friction=friction, joints=joints, duration=duration,
                               graph=graph, compiled=compiled, hessian=hessian,
                               integrator=integrator, law=law)
        self.duration = duration
        self.landing = (LandingModel(model, joints or Joints(), slope, compiled, integrator=integrator)
                        if problem.landing else None)
        # exact Hessians pay for the impact alone; through the landing's RK4 chain a
        # limited-memory Hessian solves 4x faster (benchmarks/solve_speed.py)
        if hessian == "auto":
            hessian = "limited-memory" if self.landing else "exact"
        self.graph, self.compiled, self.hessian = graph, compiled, hessian
        sym = ca.MX if self.landing or graph == "MX" else ca.SX
        u = sym.sym("u", self.posture.size)
        p = sym.sym("p", PARAMETERS)  # speed (hip_vx, m/s), friction, slope, reference state
        tau = sym.sym("tau", 1 if self.landing else 0)  # second impact at tau * duration
        w = ca.vertcat(u, tau)
        x = self.posture.function(u, p)
        terms, out, landing = self._terms(x, p, tau, graph)
        if landing is not None:
            self._T_c_total = ca.Function("T_c_total", [w, p], [landing["T_c_total"]])
        weights, self.weight = normalised(problem.objective)
        f = sum(wt * terms[k] for k, wt in weights.items())  # normalised: scaling-free
        self.objective_function = ca.Function("objective", [w, p], [self.weight * f])
        self.term_names = tuple(sorted(set(problem.objective) | {"T_c"}))
        self.terms_function = ca.Function("terms", [w, p], [ca.vertcat(*[terms[k] for k in self.term_names])])
        self._first = self.start(self.reference)  # the first start, and the objective's scale
        normalised_value = float(ca.Function("f", [w, p], [f])(self._first, self.p0))
        self.scale = 1.0 / max(abs(normalised_value), 1e-2)
        self.records = posture_constraints(self.posture, problem, law, u, x, out, p,
                                           self.hip_from_strike(self.reference), landing)
        g, self.lbg, self.ubg = stack(self.records)
        self.nlp = {"x": w, "p": p, "f": self.scale * f, "g": g}
        self.options = ipopt_options(problem, hessian)
        self.solver = cached_nlpsol("touchdown", self.nlp, self.options, compiled)
        self._sensitivity: ca.Function | None = None  # built on first use (sensitivity())
        self._solvers: dict[str, ca.Function] = {}  # other IPOPT options (solve_from(options=...))
        self.constraint_function = ca.Function("g", [w, p], [g])
        self.build_time = time.perf_counter() - t0

    def _terms(self, x, p, tau, graph: str) -> tuple[dict, dict, dict | None]:
        """The objective's terms at touchdown state x (symbolic) and parameters p: the impact's
        (T_c, dv_trunk, dv_com) under the law, the stance's support, and through a landing
        problem T_c_total with the second impact at tau * duration. Returns (terms, the law's
        impact outputs, the landing's outputs or None)."""
        model, strike, problem = self.model, self.strike, self.problem
        impact = self.impact.function if graph == "SX" else impact_function(model, strike, graph=graph)
        out = self._law(impact(x=x, friction=p[FRICTION], slope=p[SLOPE]), p[FRICTION])
        terms = {"T_c": out["T_c"], "dv_trunk_x": out["dv_trunk"][0],
                 "dv_trunk_z": out["dv_trunk"][1], "dv_com_x": out["dv_com"][0],
                 "dv_com_z": out["dv_com"][1]}
        if "support" in problem.objective:
            terms["support"] = support(x, model, STRIKES[strike][0], problem.stance_peak_bw)
        if not self.landing:
            return terms, out, None
        t_ref = self.second_impact(self.reference)
        if t_ref is None:
            raise InputError("the reference touchdown's landing never brings the other foot point "
                             f"down within {self.duration * 1e3:g} ms: no landing to optimise "
                             "(check [joints] and [landing].duration_ms)")
        self._t_ref: float = t_ref  # s, the reference's second impact
        landing = landing_function(self.landing, strike, LANDING_STEPS)(x=x, t_e=tau * self.duration)
        terms["T_c_total"] = landing["T_c_total"]
        return terms, out, landing

    def _coulomb_mode(self) -> tuple[int, int]:
        """(mode, sliding direction s) of the reference touchdown's Coulomb impact."""
        out = self.impact.evaluate(self.reference)
        mode, v0 = np.ravel(out["mode_coulomb"])[0], np.ravel(out["v_contact"])
        return round(float(mode)), 1 if float(v0[0]) >= 0 else -1

    def _law(self, out, mu) -> dict:
        """The impact indicators under the problem's law, smooth in the posture: no-slip and
        frictionless as impact_function gives them, Coulomb in the fixed mode (with mu the
        NLP's parameter) and the inequalities of its region."""
        if self.law != "coulomb":
            key = self.law.replace("-", "_")
            law = {k: out[f"{k}_{key}"] for k in ("T_c", "impulse", "slip", "dv_trunk", "dv_com")}
        else:
            W_c, v0 = out["W_c"], out["v_contact"]
            assert self.mode is not None  # set for the Coulomb law (__init__)
            impulse, region = contact.coulomb_in_mode(W_c, v0, mu, *self.mode)
            law = {"T_c": contact.absorbed(W_c, v0, impulse), "impulse": impulse,
                   "slip": (v0 + W_c @ impulse)[0], "region": region,
                   "dv_trunk": out["dv_trunk_per_impulse"] @ impulse,
                   "dv_com": out["dv_com_per_impulse"] @ impulse}
        points = len(STRIKES[self.strike])
        law["impulse_total"] = ca.vertcat(sum(law["impulse"][2 * k] for k in range(points)),
                                          sum(law["impulse"][2 * k + 1] for k in range(points)))
        return {**out, **law}

    def _simulate(self, x, dt: float, friction: float | None = None):
        """The event-driven landing from touchdown state x, or None if the state cannot land."""
        assert self.landing is not None  # called only for a problem with a landing
        try:
            return simulate_state(self.landing, self.strike, x,
                                  self.friction if friction is None else friction, dt, self.duration)
        except InputError:
            return None

    @staticmethod
    def _two_impacts(L) -> bool:
        """The landing the NLP models: the strike point held, never released, until the other
        point comes down."""
        return L is not None and len(L.impacts) == 2 and not L.releases

    def second_impact(self, x) -> float | None:
        """Time (s) of the second impact of the two-impact landing from x; None otherwise."""
        L = self._simulate(x, 5e-4)
        return L.impacts[1].time if self._two_impacts(L) else None

    def landing_disagrees(self, w, x, p) -> str:
        """Why the event-driven simulation from x does not give the NLP's two-impact landing
        and its T_c_total within solution.AGREE ("" when it does)."""
        L = self._simulate(x, 2e-4, float(p[FRICTION]))
        nlp = float(self._T_c_total(w, p))
        if not self._two_impacts(L):
            return "the event-driven landing from it is not the NLP's two impacts"
        if abs(L.T_c_total - nlp) > AGREE * max(1.0, abs(nlp)):
            return (f"its landing's T_c_total {nlp:.6g} J differs from the event-driven "
                    f"simulation's {L.T_c_total:.6g} J by more than {AGREE:g} (relative)")
        return ""

    def checked(self, x, p=None) -> ImpactResult:
        """The checked impact map at touchdown state x on the ground of p (default p0)."""
        p = self.p0 if p is None else p
        return self.impact.at(float(p[FRICTION]), float(p[SLOPE]))(x)

    def parameters(self, speed: float | None = None, friction: float | None = None,
                   slope: float | None = None, reference=None) -> np.ndarray:
        """The NLP's parameters (variables.Posture.parameters), checked: a ground the impact
        takes, and a landing problem's slope the one its landing model was built for."""
        p = self.posture.parameters(speed, friction, slope, reference)
        check_ground(float(p[FRICTION]), float(p[SLOPE]))
        if self.landing and p[SLOPE] != self.slope:
            raise InputError(f"slope = {p[SLOPE]!r} rad: the landing of this problem was built "
                             f"for {self.slope!r} rad (build the problem for the other slope)")
        return p

    def accept(self, sol, stats, p=None) -> tuple[np.ndarray, np.ndarray, ImpactResult, str | None]:
        """(w, touchdown state, checked impact, verdict) of an IPOPT solution; the verdict is
        "" for an optimum (converged by IPOPT's status and its checks hold: every constraint
        record within solution.FEASIBLE, a valid checked impact whose T_c is the NLP's within
        solution.AGREE and, for a landing, the event-driven simulation agreeing), why not when
        IPOPT converged but a check fails, None when IPOPT did not converge."""
        p = self.p0 if p is None else p
        w = np.asarray(sol["x"], float).ravel()
        x = self.to_state(w, p)
        impact = self.checked(x, p)
        if stats["return_status"] not in CONVERGED:
            return w, x, impact, None
        return w, x, impact, self.rejection(w, x, impact, p)

    def rejection(self, w, x, impact: ImpactResult, p) -> str:
        """Why a converged solution w (touchdown state x, checked impact) is not an optimum:
        the checks of `accept`, the cheap ones first; "" when they hold."""
        if not self.feasible(w, p):
            return f"a constraint is violated by more than {FEASIBLE:g}"
        if not impact.valid:
            return "the checked impact is invalid (" + "; ".join(impact.warnings) + ")"
        T_c = float(self.terms_function(w, p)[self.term_names.index("T_c")])
        if abs(T_c - impact.T_c) > AGREE * max(1.0, abs(T_c)):
            return (f"its T_c {T_c:.6g} J differs from the checked impact's {impact.T_c:.6g} J by "
                    f"more than {AGREE:g} (relative)")
        return self.landing_disagrees(w, x, p) if self.landing else ""

    def hip_from_strike(self, x) -> tuple[float, float]:
        """The hip's place over the strike point (m): along and normal to the ground."""
        hip = positions(x, self.model.body, STRIKES[self.strike][0])["hip"]
        t_axis, n_axis = ground_axes(self.slope)
        return float(hip @ t_axis), float(hip @ n_axis)

    def start(self, x) -> np.ndarray:
        """The decision vector of a touchdown state: posture in [0, 1] (and the event time)."""
        u = self.posture.to_unit(x)
        if not self.landing:
            return u
        posture = self.to_state(u)
        # the reference (unless the bounds clip it) has been simulated already
        t_e = self._t_ref if np.allclose(posture, self.reference) else self.second_impact(posture)
        return np.append(u, (t_e or self._t_ref) / self.duration)

    @property
    def p0(self) -> np.ndarray:
        """The problem's own parameters: [speed (m/s), friction, slope (rad), reference]."""
        return self.posture.parameters()

    @property
    def index(self) -> list[int]:
        return self.posture.index

    def to_unit(self, x) -> np.ndarray:
        return self.posture.to_unit(x)

    def to_state(self, w, p=None) -> np.ndarray:
        """The touchdown state (SI) of a decision vector (and parameters p, default p0)."""
        return self.posture.to_state(w, self.p0 if p is None else p)

    def bounds(self, size: int) -> tuple[np.ndarray, np.ndarray]:
        """lbx, ubx of a decision vector of `size` entries."""
        lbx = np.zeros(size)
        if self.landing:
            lbx[-1] = 1e-3
        return lbx, np.ones(size)

    def solve_from(self, w0, p=None, lam_x0=None, lam_g0=None, options=None):
        """One IPOPT run from w0 (with multipliers when given; `options`: extra IPOPT options,
        e.g. warm-start ones, for a solver built once per set): (solution dict, IPOPT's stats,
        seconds)."""
        p = self.p0 if p is None else p
        solver = self.solver
        if options:
            key = repr(sorted(options.items()))
            if key not in self._solvers:
                self._solvers[key] = cached_nlpsol("touchdown", self.nlp, {**self.options, **options},
                                                   self.compiled)
            solver = self._solvers[key]
        lbx, ubx = self.bounds(len(w0))
        warm = {} if lam_x0 is None else {"lam_x0": lam_x0, "lam_g0": lam_g0}
        t = time.perf_counter()
        sol = solver(x0=w0, p=p, lbx=lbx, ubx=ubx, lbg=self.lbg, ubg=self.ubg, **warm)
        elapsed = time.perf_counter() - t
        return sol, solver.stats(), elapsed

    def active(self, w, p, sol) -> tuple:
        """The active constraints and bounds of solution `sol` at w, p (solution.active_set)."""
        return active_set(self.records, self.constraint_function(w, p), sol["lam_g"], sol["lam_x"],
                          self.posture, w, self.scale, self.weight)

    def feasible(self, w, p=None, tol=FEASIBLE) -> bool:
        """Every constraint within tol (equalities of the gait within 1e-9 m)."""
        g = np.asarray(self.constraint_function(w, self.p0 if p is None else p), float).ravel()
        tight = np.array([min(tol, 1e-9) if r.equality else tol for r in self.records])
        return bool(np.all(g >= self.lbg - tight) and np.all(g <= self.ubg + tight))

    def sensitivity(self, w, p, lam_x, lam_g) -> dict:
        """d(objective*)/dp and d(variables*)/dp (deg per unit) at the optimum w, p = [speed,
        friction]: the envelope theorem, dF*/dp = dL/dp, and the parametric sensitivity of the
        KKT system on the active set A (fixed bounds removed, CasADi's exact derivatives),

            [H_ww  J_A^T] [dw/dp  ]     [H_wp ]
            [J_A   0    ] [dlam/dp] = - [J_A,p],   L = f + lam_g' g.
        """
        if self._sensitivity is None:
            x, pp, g = self.nlp["x"], self.nlp["p"], self.nlp["g"]
            lam = type(x).sym("lam", g.shape[0])
            L = self.nlp["f"] + ca.dot(lam, g)
            H, dLdw = ca.hessian(L, x)
            self._sensitivity = ca.Function("kkt", [x, pp, lam], [
                H, ca.jacobian(dLdw, pp), ca.jacobian(g, x), ca.jacobian(g, pp), ca.gradient(L, pp), g])
        lam_g = np.asarray(lam_g, float).ravel()
        H, Hwp, J, Jp, dLdp, g = (np.asarray(a, float) for a in self._sensitivity(w, p, lam_g))
        Hwp, Jp, dLdp, g = Hwp[:, :2], Jp[:, :2], dLdp.ravel()[:2], g.ravel()  # speed, friction
        active = [k for k, r in enumerate(self.records) if r.equality or is_active(
            g[k] - r.bound, r.bound, lam_g[k], self.scale)]
        lam_x = np.asarray(lam_x, float).ravel()
        lbx, ubx = self.bounds(len(w))
        free = [k for k in range(len(w)) if not is_active(
            min(w[k] - lbx[k], ubx[k] - w[k]), 1.0, lam_x[k], self.scale)]
        n, m = len(free), len(active)
        K = np.zeros((n + m, n + m))
        K[:n, :n] = H[np.ix_(free, free)]
        K[:n, n:] = J[np.ix_(active, free)].T
        K[n:, :n] = J[np.ix_(active, free)]
        rhs = -np.vstack([Hwp[free], Jp[active]])
        dw = np.zeros((len(w), 2))
        dw[free] = np.linalg.lstsq(K, rhs, rcond=None)[0][:n]
        df = dLdp.ravel() * self.weight / self.scale
        dx = dw[:self.posture.size] * self.posture.per_unit()[:, None]  # deg per unit of p
        result: dict[str, Any] = {"d_objective_d_speed": float(df[0]), "d_objective_d_friction": float(df[1])}
        for k, name in enumerate(("speed", "friction")):
            result[f"d_posture_d_{name}_deg"] = dict(zip(self.problem.variables, map(float, dx[:, k])))
        return result

    def marginal(self, x) -> dict[str, float]:
        """d(objective)/d(variable) at touchdown state x, per deg (per deg/s), others held."""
        w = self.start(x)
        wsym = ca.MX.sym("w", len(w))
        grad = ca.Function("grad", [wsym], [ca.gradient(self.objective_function(wsym, self.p0), wsym)])
        g = np.asarray(grad(w), float).ravel()[:self.posture.size] / self.posture.per_unit()
        return dict(zip(self.problem.variables, map(float, g)))

    def solve(self, progress=None) -> Optimum:
        """Run the multi-start (multistart.solve); `progress(k, n, start)` after each start.
        Under Coulomb an optimum held by its mode's region is solved again in each neighbouring
        mode (neighbours), and on from a better one, each mode once; the best is kept."""
        best = own = multistart.solve(self, progress)
        if self.mode is None:
            return best
        tried: set[tuple[int, int]] = {self.mode}
        queue = [(self.mode, best)]
        while queue:
            mode, found = queue.pop(0)
            if not found.success:
                continue
            rows = [int(c.name.rsplit("_", 1)[1]) - 1 for c in found.held_by
                    if c.name.startswith("coulomb_mode_")]
            for nxt in (n for row in rows for n in neighbours(mode, row) if n not in tried):
                tried.add(nxt)
                other = PostureProblem(**{**self._arguments, "mode": nxt}).solve_fixed(progress)
                if other.success and other.objective < best.objective - 1e-12:
                    # the reference is measured in its own mode (another mode's closed form
                    # does not hold there)
                    best = replace(other, reference_objective=own.reference_objective,
                                   reference_terms=own.reference_terms)
                    queue.append((nxt, other))
        if len(tried) > 1:
            best = replace(best, notes=best.notes + (
                "Coulomb modes tried: " + ", ".join(f"{contact.MODES[m]} {'forward' if s > 0 else 'backward'}"
                                                    for m, s in sorted(tried))
                + "; the best kept",))
        return best

    def solve_fixed(self, progress=None) -> Optimum:
        """The multi-start in this problem's Coulomb mode only (multistart.solve)."""
        return multistart.solve(self, progress)
