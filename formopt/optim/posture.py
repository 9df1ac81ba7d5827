"""IPOPT searches the touchdown posture that absorbs the least energy (or another objective).

The decision variables are some of the touchdown state's angles (and, if asked, segment
angular velocities), scaled to [0, 1] between their bounds; the rest of the state stays as
the scene gives it. Every constraint is smooth:

- under the no-slip law, no slip at the strike: t - mu n <= 0 and -t - mu n <= 0 (t, n: the
  ground's impulse; the total over heel and forefoot for a flat strike); under every law
  n >= 0 at every strike point; under Coulomb and frictionless optionally |slip| <= max_slip
  (as slip^2 <= max_slip^2);
- under Coulomb, the impact's mode and sliding direction fixed for the solve, from the
  reference touchdown: the mode's closed form is smooth, and the inequalities that bound
  the mode's region (contact.coulomb_in_mode) are constraints, so an optimum on a mode
  switch says so among its active constraints;
- the strike point approaches the ground (normal velocity < 0), the other foot point is
  not below it;
- joint ranges of motion (RANGE_OF_MOTION_DEG) and the scene's bounds (box constraints);
- optionally the overstride (strike point ahead of the hip, m) and the hip height (m).

Derivatives are CasADi's (exact Hessian). A multi-start from a printed seed reports every
start; only a start IPOPT reports as converged, and whose optimum passes the checked impact
map, can be the optimum. The sensitivity of the optimal objective to the running speed and
the friction coefficient comes from the envelope theorem (dF*/dp = dL/dp at the optimum).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ..mechanics import contact
from ..mechanics.compiled import cached_nlpsol
from ..mechanics.impact import Impact, ImpactResult, impact_function
from ..mechanics.landing import Joints, LandingModel, landing_function, simulate_state
from ..mechanics.model import STATE, STRIKES, Model, ground_axes, landmarks
from ..mechanics.errors import InputError

ANGLES = ("trunk", "hip", "knee", "ankle")
RATES = ("omega_trunk", "omega_thigh", "omega_shank", "omega_foot")
OBJECTIVES = ("T_c", "T_c_total", "dv_trunk_x", "dv_trunk_z", "dv_com_x", "dv_com_z")
LANDING_STEPS = 40  # RK4 steps over the contact phase between the two impacts
# The second point must strike at least this fast (m/s, normal): a grazing touch (zero normal
# velocity, which absorbs nothing) dips below the ground by less than the integration error,
# so a slower strike is not an event the simulation would see.
SECOND_APPROACH = -0.01
# Active ranges of motion (deg): American Academy of Orthopaedic Surgeons (1965), Joint Motion:
# Method of Measuring and Recording, as tabulated in Norkin C.C. & White D.J. (2016) Measurement
# of Joint Motion, 5th ed.: hip extension 30 / flexion 120, knee flexion 135 (0 = straight),
# ankle plantarflexion 50 / dorsiflexion 20; trunk: thoracolumbar extension 25 / flexion 80.
RANGE_OF_MOTION_DEG = {"trunk": (-25.0, 80.0), "hip": (-30.0, 120.0), "knee": (0.0, 135.0),
                       "ankle": (-50.0, 20.0)}
CONVERGED = ("Solve_Succeeded", "Solved_To_Acceptable_Level")
# IPOPT's return statuses in plain words (the ones a posture problem meets).
STATUS_EXPLAINED = {
    "Solve_Succeeded": "converged to the requested tolerance",
    "Solved_To_Acceptable_Level": "converged to IPOPT's looser 'acceptable' tolerance",
    "Infeasible_Problem_Detected": "no posture near where this start ended satisfies every "
                                   "constraint (too little friction for any posture, bounds that "
                                   "exclude a landing, ...); other starts may still find one",
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


def explain(status: str) -> str:
    return STATUS_EXPLAINED.get(status, "see IPOPT's documentation of this return status")


@dataclass(frozen=True)
class Problem:
    """What to optimise: variables (STATE names) with SI bounds, an objective, constraints."""

    variables: tuple[str, ...]
    lower: tuple[float, ...]  # rad or rad/s
    upper: tuple[float, ...]
    objective: dict[str, float]  # indicator -> weight; minimise the weighted sum
    max_overstride: float | None = None  # m, strike point ahead of the hip along the ground
    hip_height: tuple[float, float] | None = None  # m, above the strike point, normal to the ground
    starts: int = 8
    seed: int = 0
    tolerance: float = 1e-8
    contact_friction: bool = False  # |f_t| <= mu f_n, f_n >= 0 through the contact phase
    max_iterations: int = 200  # IPOPT's max_iter
    max_slip: float | None = None  # m/s, |tangential velocity| of the strike point after the impact

    @property
    def landing(self) -> bool:
        """Whether the problem needs the whole landing (T_c_total or contact-phase friction)."""
        return "T_c_total" in self.objective or self.contact_friction


@dataclass(frozen=True)
class Constraint:
    """A constraint (or variable bound) at the optimum."""

    name: str
    value: float
    bound: float
    multiplier: float  # d(objective*)/d(bound): objective units per unit of the bound (deg for angles)
    meaning: str


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
    notes: tuple[str, ...] = field(default=())


class PostureProblem:
    """The NLP of one model, strike, ground and problem; solve() runs the multi-start."""

    def __init__(self, model: Model, strike: str, reference, problem: Problem,
                 slope: float = 0.0, friction: float = 0.8, joints: Joints | None = None,
                 duration: float = 0.2, graph: str = "SX", compiled: bool = False,
                 hessian: str = "auto", integrator: str = "rk4", law: str = "no-slip"):
        """`reference`: the touchdown state (STATE, SI) whose other values stay fixed;
        `duration` (s): the longest landing; `graph`, `compiled`, `hessian` ("auto": exact
        for impacts, limited-memory through a landing), `integrator`: scene [numerics];
        `law`: the contact law at the impact (contact.LAWS)."""
        t0 = time.perf_counter()
        self.model, self.strike, self.problem = model, strike, problem
        self.slope, self.friction = slope, friction
        self.reference = np.asarray(reference, float)
        self.index = [STATE.index(v) for v in problem.variables]
        self.lower, self.upper = np.array(problem.lower), np.array(problem.upper)
        self.law = law
        if law != "no-slip" and problem.landing:
            raise InputError(f"a landing objective (T_c_total, contact_friction) holds the strike "
                             f"point: it takes the no-slip law, not {law!r}")
        if law == "coulomb" and strike == "flat":
            raise InputError("a flat strike's Coulomb impact (two contacts, the velocity-level "
                             "law) switches mode inside the NLP: optimise it as no-slip or "
                             "frictionless")
        self.impact = Impact(model, strike, slope, friction, law=law)
        self.mode = self._coulomb_mode() if law == "coulomb" else None
        us, ps = ca.SX.sym("u", len(self.index)), ca.SX.sym("p", 2)
        self._state = ca.Function("state", [us, ps], [self.state(us, ps)])
        self.duration = duration
        self.landing = (LandingModel(model, joints or Joints(), slope, integrator=integrator)
                        if problem.landing else None)
        # exact Hessians pay for the impact alone; through the landing's RK4 chain a
        # limited-memory Hessian solves 4x faster (benchmarks/solve_speed.py)
        if hessian == "auto":
            hessian = "limited-memory" if self.landing else "exact"
        self.graph, self.compiled, self.hessian = graph, compiled, hessian
        sym = ca.MX if self.landing or graph == "MX" else ca.SX
        u = sym.sym("u", len(self.index))
        p = sym.sym("p", 2)  # running speed (hip_vx, m/s), friction coefficient
        tau = sym.sym("tau", 1 if self.landing else 0)  # second impact at tau * duration
        w = ca.vertcat(u, tau)
        x = self._state(u, p)
        out = self._law(impact_function(model, strike, slope, graph=graph)(x=x), p[1])
        terms = {"T_c": out["T_c"], "dv_trunk_x": out["dv_trunk"][0],
                 "dv_trunk_z": out["dv_trunk"][1], "dv_com_x": out["dv_com"][0],
                 "dv_com_z": out["dv_com"][1]}
        landing = None
        if self.landing:
            if strike not in ("heel", "forefoot"):
                raise InputError("a landing objective needs a heel or forefoot strike (the other "
                                 "point comes down second)")
            self._t_ref = self._second_impact(self.reference)
            if self._t_ref is None:
                raise InputError("the reference touchdown's landing never brings the other foot point "
                                 f"down within {duration * 1e3:g} ms: no landing to optimise "
                                 "(check [joints] and [landing].duration_ms)")
            landing = landing_function(self.landing, strike, LANDING_STEPS)(x=x, t_e=tau * duration)
            terms["T_c_total"] = landing["T_c_total"]
            self._T_c_total = ca.Function("T_c_total", [w, p], [landing["T_c_total"]])
        f = sum(wt * terms[k] for k, wt in problem.objective.items())
        self.objective_function = ca.Function("objective", [w, p], [f])
        self._first = self.start(self.reference)  # the first start, and the objective's scale
        self.scale = 1.0 / max(abs(float(self.objective_function(self._first, self.p0))), 1e-2)
        g, self.constraints = self._constraints(x, out, p, landing)
        self.nlp = {"x": w, "p": p, "f": self.scale * f, "g": g}
        opts = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
                "ipopt.tol": problem.tolerance, "ipopt.max_iter": problem.max_iterations,
                "ipopt.hessian_approximation": hessian}
        self.solver = cached_nlpsol("touchdown", self.nlp, opts, compiled)
        lam = sym.sym("lam", g.shape[0])
        lagrangian = self.scale * f + ca.dot(lam, g)
        self._dL_dp = ca.Function("dL_dp", [w, p, lam], [ca.gradient(lagrangian, p) / self.scale])
        self.constraint_function = ca.Function("g", [w, p], [g])
        self.build_time = time.perf_counter() - t0

    def _coulomb_mode(self) -> tuple[int, int]:
        """(mode, sliding direction s) of the reference touchdown's Coulomb impact."""
        f = impact_function(self.model, self.strike, self.slope, ["mode_coulomb", "v_contact"],
                            law="coulomb", friction=self.friction)
        mode, v0 = f(self.reference)
        return int(round(float(mode))), 1 if float(v0[0]) >= 0 else -1

    def _law(self, out, mu) -> dict:
        """The impact indicators under the problem's law, smooth in the posture: no-slip and
        frictionless as impact_function gives them, Coulomb in the fixed mode (with mu the
        NLP's parameter) and the inequalities of its region."""
        if self.law != "coulomb":
            key = self.law.replace("-", "_")
            law = {k: out[f"{k}_{key}"] for k in ("T_c", "impulse", "slip", "dv_trunk", "dv_com")}
        else:
            W_c, v0 = out["W_c"], out["v_contact"]
            impulse, region = contact.coulomb_in_mode(W_c, v0, mu, *self.mode)
            law = {"T_c": contact.absorbed(W_c, v0, impulse), "impulse": impulse,
                   "slip": (v0 + W_c @ impulse)[0], "region": region,
                   "dv_trunk": out["dv_trunk_per_impulse"] @ impulse,
                   "dv_com": out["dv_com_per_impulse"] @ impulse}
        points = len(STRIKES[self.strike])
        law["impulse_total"] = ca.vertcat(sum(law["impulse"][2 * k] for k in range(points)),
                                          sum(law["impulse"][2 * k + 1] for k in range(points)))
        return {**out, **law}

    def _simulate(self, x, dt: float):
        """The event-driven landing from touchdown state x, or None if the state cannot land."""
        try:
            return simulate_state(self.landing, self.strike, x, self.friction, dt, self.duration)
        except InputError:
            return None

    @staticmethod
    def _two_impacts(L) -> bool:
        """The landing the NLP models: the strike point held, never released, until the other
        point comes down."""
        return L is not None and len(L.impacts) == 2 and not L.releases

    def _second_impact(self, x) -> float | None:
        """Time (s) of the second impact of the two-impact landing from x; None otherwise."""
        L = self._simulate(x, 5e-4)
        return L.impacts[1].time if self._two_impacts(L) else None

    def _landing_agrees(self, w, x, rtol=1e-3) -> bool:
        """The event-driven simulation from x gives the same two-impact landing and T_c_total."""
        L = self._simulate(x, 2e-4)
        nlp = float(self._T_c_total(w, self.p0))
        return self._two_impacts(L) and abs(L.T_c_total - nlp) <= rtol * max(1.0, abs(nlp))

    def start(self, x) -> np.ndarray:
        """The scaled decision vector of a touchdown state: posture (and event time) in [0, 1]."""
        u = self.to_unit(x)
        if not self.landing:
            return u
        posture = self.to_state(u)
        # the reference (unless the bounds clip it) has been simulated already
        t_e = self._t_ref if np.allclose(posture, self.reference) else self._second_impact(posture)
        return np.append(u, (t_e or self._t_ref) / self.duration)

    @property
    def p0(self) -> np.ndarray:
        return np.array([self.reference[STATE.index("hip_vx")], self.friction])

    def state(self, u, p):
        """The touchdown state (SX) of scaled variables u and parameters p."""
        x = ca.SX(ca.DM(self.reference))
        for k, i in enumerate(self.index):
            x[i] = self.lower[k] + (self.upper[k] - self.lower[k]) * u[k]
        x[STATE.index("hip_vx")] = p[0]
        if self.strike == "flat":  # the sole on the ground: the ankle follows the other angles
            heel, fore = (np.array(self.model.body["foot"].landmarks[k]) for k in ("heel", "forefoot"))
            sole = math.atan2(fore[1] - heel[1], fore[0] - heel[0])
            x[3] = self.slope - sole - x[1] + x[0] + x[2]
        return x

    def to_unit(self, x) -> np.ndarray:
        x = np.asarray(x, float)
        return np.clip((x[self.index] - self.lower) / (self.upper - self.lower), 0.0, 1.0)

    def to_state(self, w, p=None) -> np.ndarray:
        """The touchdown state (SI) of a scaled decision vector (and parameters p)."""
        u = np.asarray(w, float)[:len(self.index)]
        return np.asarray(self._state(u, self.p0 if p is None else p), float).ravel()

    def _constraints(self, x, out, p, landing=None):
        """Stacked constraints g (lbg <= g <= ubg) and their names, kinds and bounds."""
        rows, names = [], []
        t_axis, n_axis = ground_axes(self.slope)
        mu = p[1]
        total_t, total_n = out["impulse_total"][0], out["impulse_total"][1]
        if self.law == "no-slip":
            rows += [total_t - mu * total_n, -total_t - mu * total_n]
            names += [("no_slip_forward", "upper", 0.0), ("no_slip_backward", "upper", 0.0)]
        if "region" in out:
            rows.append(out["region"])
            names += [(f"coulomb_mode_{k + 1}", "lower", 0.0) for k in range(out["region"].shape[0])]
        if self.problem.max_slip is not None:
            rows.append(out["slip"] ** 2)
            names.append(("max_slip", "upper", self.problem.max_slip ** 2))
        points = STRIKES[self.strike]
        for k, point in enumerate(points):
            rows.append(out["impulse"][2 * k + 1])
            names.append((f"push_{point}", "lower", 0.0))
            rows.append(out["approach"][k])
            names.append((f"approach_{point}", "upper", -1e-3))
        if self.strike != "flat":
            rows.append(out["clearance"])
            other = "heel" if points == ("forefoot",) else "forefoot"
            names.append((f"clearance_{other}", "lower", 0.0))
        world = landmarks(x, self.model.body, points[0])
        hip = world["hip"][0]
        if self.problem.max_overstride is not None:
            rows.append(ca.dot(-hip, ca.DM(t_axis)))
            names.append(("overstride", "upper", self.problem.max_overstride))
        if self.problem.hip_height is not None:
            lo, hi = self.problem.hip_height
            rows += [ca.dot(hip, ca.DM(n_axis))] * 2
            names += [("hip_height_min", "lower", lo), ("hip_height_max", "upper", hi)]
        if landing is not None:
            other = "heel" if points == ("forefoot",) else "forefoot"
            rows.append(landing["residual"])
            names.append((f"{other}_down_at_second_impact", "equal", 0.0))
            rows.append(landing["approach"])  # a real impact, seen by the event-driven simulation too
            names.append((f"approach_{other}", "upper", SECOND_APPROACH))
            rows.append(landing["height"][:-1])
            names += [(f"{other}_above_ground_{k + 1}", "lower", 0.0) for k in range(LANDING_STEPS - 1)]
            f_t, f_n = landing["force_t"], landing["force_n"]
            rows.append(f_n)  # the held point is pushed, never pulled, through the phase
            names += [(f"contact_push_{k + 1}", "lower", 0.0) for k in range(LANDING_STEPS)]
            if self.problem.contact_friction:
                rows += [f_t - mu * f_n, -f_t - mu * f_n]
                for label in ("contact_no_slip_forward", "contact_no_slip_backward"):
                    names += [(f"{label}_{k + 1}", "upper", 0.0) for k in range(LANDING_STEPS)]
        self.lbg = np.array([b if kind in ("lower", "equal") else -np.inf for _, kind, b in names])
        self.ubg = np.array([b if kind in ("upper", "equal") else np.inf for _, kind, b in names])
        return ca.vertcat(*rows), names

    def starts(self) -> list[np.ndarray]:
        """The reference posture first, then seeded uniform starts in the bounds.

        For a landing problem a start must land: its simulated landing brings the other foot
        point down (otherwise the event constraint has no solution near it); up to 50 draws
        per start are tried.
        """
        rng = np.random.default_rng(self.problem.seed)
        if not self.landing:
            return [self._first] + [rng.uniform(0.0, 1.0, len(self.index))
                                    for _ in range(self.problem.starts - 1)]
        found = [self._first]
        for _ in range(50 * self.problem.starts):
            if len(found) == self.problem.starts:
                break
            u = rng.uniform(0.0, 1.0, len(self.index))
            t_e = self._second_impact(self.to_state(u))
            if t_e is not None:
                found.append(np.append(u, t_e / self.duration))
        return found

    def solve_from(self, w0, p=None):
        p = self.p0 if p is None else p
        lbx = np.zeros(len(w0))
        if self.landing:
            lbx[-1] = 1e-3
        t = time.perf_counter()
        sol = self.solver(x0=w0, p=p, lbx=lbx, ubx=1.0, lbg=self.lbg, ubg=self.ubg)
        elapsed = time.perf_counter() - t
        stats = self.solver.stats()
        return sol, stats, elapsed

    def solve(self, progress=None) -> Optimum:
        """Run the multi-start; `progress(k, n, start)` is called after each start."""
        results, starts = [], []
        for k, u0 in enumerate(self.starts()):
            sol, stats, elapsed = self.solve_from(u0)
            u = np.asarray(sol["x"], float).ravel()
            status = stats["return_status"]
            x = self.to_state(u)
            converged = status in CONVERGED and self._feasible(u) and self.impact(x).valid
            if converged and self.landing:  # the event-driven simulation agrees
                converged = self._landing_agrees(u, x)
            objective = float(sol["f"]) / self.scale
            start = Start(k + 1, _named(self.problem.variables, self.to_state(u0)[self.index]), status,
                          converged, objective, _named(self.problem.variables, x[self.index]),
                          int(stats["iter_count"]))
            starts.append(start)
            results.append((sol, u, x, start, elapsed))
            if progress:
                progress(k + 1, self.problem.starts, start)
        converged = [r for r in results if r[3].converged]
        pool = converged or results
        sol, u, x, best, _ = min(pool, key=lambda r: r[3].objective)
        notes = []
        if not converged:
            statuses = sorted({r[3].status for r in results})
            notes.append(f"no start converged: {'; '.join(f'{s}: {explain(s)}' for s in statuses)}. "
                         "The state shown is the best last iterate, not an optimum")
        impact = self.impact(x)
        if self.mode is not None:
            mode, direction = self.mode
            notes.append(f"Coulomb mode fixed for every start from the reference touchdown: "
                         f"{contact.MODES[mode]}, sliding {'forward' if direction > 0 else 'backward'}"
                         f" at first; the impact at the state shown ends in {impact.mode}")
        active = self._active(u, sol) if converged else ()
        sensitivity = self._sensitivity(u, sol) if converged else {}
        return Optimum(success=bool(converged), status=best.status, objective=best.objective,
                       state=x, impact=impact, reference=self.impact(self.reference),
                       active=active, sensitivity=sensitivity, starts=tuple(starts),
                       local_optima=_distinct([r[2][self.index] for r in converged]),
                       seed=self.problem.seed,
                       solve_time=float(np.median([r[4] for r in results])),
                       build_time=self.build_time, notes=tuple(notes))

    def _feasible(self, u, tol=1e-6) -> bool:
        g = np.asarray(self.constraint_function(u, self.p0), float).ravel()
        return bool(np.all(g >= self.lbg - tol) and np.all(g <= self.ubg + tol))

    def _active(self, u, sol) -> tuple[Constraint, ...]:
        g = np.asarray(self.constraint_function(u, self.p0), float).ravel()
        # IPOPT's multipliers of L = f + lam' g: d(f*)/d(bound) = -lam (envelope theorem)
        lam_g = -np.asarray(sol["lam_g"], float).ravel() / self.scale
        lam_x = -np.asarray(sol["lam_x"], float).ravel() / self.scale
        active = []
        for (name, _, bound), value, lam in zip(self.constraints, g, lam_g):
            if abs(value - bound) < 1e-6 * max(1.0, abs(bound)) and abs(lam) > 1e-9:
                active.append(Constraint(name, float(value), bound, float(lam), _meaning(name)))
        for k, var in enumerate(self.problem.variables):
            at = "lower" if u[k] < 1e-6 else "upper" if u[k] > 1 - 1e-6 else None
            if at and abs(lam_x[k]) > 1e-9:
                value = self.lower[k] if at == "lower" else self.upper[k]
                unit = math.degrees(value)
                active.append(Constraint(f"{var}_{at}", unit, unit,
                                         float(lam_x[k]) * math.pi / 180 / (self.upper[k] - self.lower[k]),
                                         f"{var} held at its {at} bound: the objective would keep "
                                         f"falling past it"))
        return tuple(active)

    def _sensitivity(self, u, sol) -> dict:
        """d(objective*)/dp by the envelope theorem; d(posture*)/dp (deg per unit) by
        warm-started re-solves at p +- h (central differences), p = speed, friction."""
        d = np.asarray(self._dL_dp(u, self.p0, sol["lam_g"]), float).ravel()
        out = {"d_objective_d_speed": float(d[0]), "d_objective_d_friction": float(d[1])}
        for k, (name, h) in enumerate((("speed", 1e-3), ("friction", 1e-3))):
            moved = []
            for sign in (1.0, -1.0):
                p = self.p0.copy()
                p[k] += sign * h
                re, stats, _ = self.solve_from(u, p)
                if stats["return_status"] not in CONVERGED:
                    break
                moved.append(self.to_state(np.asarray(re["x"], float).ravel(), p)[self.index])
            if len(moved) == 2:
                slope = np.degrees((moved[0] - moved[1]) / (2 * h))
                out[f"d_posture_d_{name}_deg"] = dict(zip(self.problem.variables, map(float, slope)))
        return out


def _meaning(name: str) -> str:
    if name.startswith("coulomb_mode"):
        return ("the impact's Coulomb mode changes past here (slide, stick or reversed slide, "
                "or the sliding direction): solve again from a posture in the next mode")
    if name == "max_slip":
        return "the strike point leaves the impact sliding as fast as allowed ([optimize] max_slip_mps)"
    if name.startswith("contact_no_slip"):
        return "friction during the contact phase holds the optimum: the held point would slide"
    if name.startswith("no_slip"):
        return ("friction holds the optimum: the foot would slip past it; more friction lets the "
                "posture go further")
    if name.startswith(("push", "contact_push")):
        return "the ground would have to pull the foot past here: the contact would not hold"
    if name.startswith("approach"):
        return "the point would strike the ground no faster than allowed: no impact past here"
    if name.startswith("clearance"):
        return "the other foot point touches the ground: past here the strike pattern changes"
    if "_down_at_second_impact" in name:
        return "the event itself: the other point reaches the ground at the second impact"
    if "_above_ground_" in name:
        return "the other point would touch the ground earlier in the contact phase"
    if name == "overstride":
        return "the foot lands as far ahead of the hip as allowed"
    return "the hip height limit holds the optimum"


def _named(names, values) -> dict[str, float]:
    return {n: float(math.degrees(v)) for n, v in zip(names, values)}


DISTINCT = math.radians(0.5)  # optima closer than this in every variable count as one


def _distinct(points, tol=DISTINCT) -> int:
    found = []
    for p in points:
        if all(np.max(np.abs(p - q)) > tol for q in found):
            found.append(p)
    return len(found)
