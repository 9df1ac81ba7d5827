"""Direct collocation of the half stride, built once, solved for any parameters.

Decision variables per phase (nodes k = 0..N): the state theta, theta' (9 + 9), the
accelerations theta'' (9), the joint moments tau (6, piecewise linear) and the contact forces
f (one per contact row), and the phase's duration; per impact, the impulse p (one per contact
row of the phase after it; the touchdown's also its post-impact velocity). Constraints:

- at every node, the equations of motion (mechanics.joint_space, implicit: theta'' and f are
  variables) and, in stance, J_c theta'' + (dJ_c/dt) theta' = 0; f_n >= 0 and
  mu f_n -+ f_t >= 0; every foot point not held stays at or above the ground;
- on every interval, trapezoidal defects on x = (theta, theta') with x' = (theta', theta''):
  x_{k+1} - x_k = h/2 (x'_k + x'_{k+1}) (second order: the energy balance closes to O(h^2));
- a phase that adds a point: the point on the ground at the previous phase's end, moving into
  it; the impact M(theta) (theta'+ - theta'-) = J_c^T p with J_c theta'+ = 0 (the projection of
  mechanics.impact in joint coordinates), p_n >= 0 and mu sum p_n -+ p_t >= 0 (no-slip, and
  Coulomb's sticking mode: a sticking impulse lies in the cone);
- a phase that drops a point: that point's normal force zero at the previous phase's end;
- a sliding touchdown (settings.touchdown = "slide", Coulomb's sliding mode): the touchdown
  impulse on the cone's edge, p_t = -s mu p_n, p_n >= 0, the normal velocity zero after it and
  the slip's sign s held (s v_t >= 0 before and after); in the `slide` phase the point's
  tangential force is -s mu f_n, s v_t >= 0 at every node, and v_t = 0 at the phase's end
  (s, +1 or -1: settings.slip); the slide's friction work counts with its impact's
  T_c in the objective's impact term (the two are one Coulomb contact's loss);
- for the work objectives, each joint's power split P = P+ - P- (W/kg, P+- >= 0) at every node
  (problem.py says why);
- the touchdown of L at the flight's end, its impact, and periodicity: the post-impact state
  with the legs swapped and moved back by the step `speed * half-period` (along the ground) is
  the start; x_hip = 0 at the start.

Why trapezoidal: it converges from the generic guess in about a hundred iterations. A
Hermite-Simpson version (separated form, the equations of motion and contact accelerations
also at the midpoints) was tried and stalled from the same guess (dual infeasibility 1e14 after
200 iterations), so it is not shipped. The trapezoidal rule's weak point, a light foot ringing
node to node against a stiff range-of-motion wall, is closed by the walls' width and hard
bounds (mechanics.joint_space); the forward simulation (`Stride.checks`) measures what is left.
The drift of the held contact points is measured too. Parameters p = [speed (m/s), slope (rad), mu]; the cadence is
imposed, when asked, through the bounds of the half-period's row.
"""

from __future__ import annotations

import hashlib
import itertools
import math
import pickle
import time
from dataclasses import replace

import casadi as ca
import numpy as np

from ...mechanics.joint_space import JOINTS, LIMIT_MARGIN, RANGES, THETA, JointSpace, swap_legs
from .layout import Blocks, Rows, Solved, held_rows
from .problem import SMOOTHING, WORK_REGULARISATION, StrideSettings, metabolic, other_leg

NX = len(THETA)
NU = len(JOINTS)
PARAMETERS = ("speed", "slope", "mu")
ACCELERATION = 1000.0  # rad/s^2 (m/s^2 for the hip): bound on theta''
TRUNK = (math.radians(-20.0), math.radians(45.0))  # rad, the trunk's lean (forward positive)
IPOPT_DEFAULTS = {"print_level": 0, "sb": "yes", "mu_strategy": "adaptive",
                  "nlp_scaling_method": "gradient-based", "linear_solver": "mumps"}
# IPOPT's warm start from a neighbouring solution's primal and dual values (StrideNLP.resolve):
# the barrier starts small and decreases monotonically. Along a cadence chain (paper body, 30
# nodes, tendons, 165-180 steps/min at 3.5 m/s) 12-20 iterations instead of 43-52, the same
# optima to IPOPT's tolerance (benchmarks/stride_sweep_speed.py measures the map).
WARM_START = {"warm_start_init_point": "yes", "mu_strategy": "monotone", "mu_init": 1e-5,
              "warm_start_bound_push": 1e-6, "warm_start_mult_bound_push": 1e-6,
              "warm_start_slack_bound_push": 1e-6}


class StrideNLP:
    """The half stride NLP of one body and settings: build once, solve for any parameters."""

    _serial = itertools.count()  # each built NLP's own number (its `layout`)

    def __init__(self, js: JointSpace, settings: StrideSettings, ipopt: dict | None = None):
        start = time.perf_counter()
        self.js, self.settings, self.ipopt = js, settings, ipopt
        self.mass = js.mass_total
        self.phases = settings.phases
        self.split = settings.node_split()
        self.blocks, self.rows = Blocks(), Rows()
        self.p = ca.SX.sym("p", len(PARAMETERS))
        self.speed, self.slope, self.mu = ca.vertsplit(self.p)
        self.slip = settings.slip
        self._variables()
        self.terms = {"effort": 0, "positive": 0, "negative": 0, "impacts": 0, "smoothing": 0,
                      "ground": 0, "balance": 0}
        for i in range(len(self.phases)):
            self._phase(i)
        for i in range(1, len(self.phases)):
            self._transition(i)
        self._touchdown()
        self.period_row = self.rows.add(self.period, 0.0, np.inf)
        if any(settings.tendons.values()):  # the springs let the optimum draw energy from the transcription
            climb = self.mass * 9.81 * self.speed * self.period * ca.sin(self.slope)
            self.rows.add(ca.vertcat(self.terms["ground"], self.terms["balance"] - climb) / (self.mass * 9.81))
        objective = self._objective()
        self.problem = {"x": self.blocks.vector(), "p": self.p, "f": objective,
                        "g": ca.vertcat(*self.rows.expr)}  # the NLP's expressions
        self.options = {**IPOPT_DEFAULTS, "max_iter": settings.max_iter, "tol": settings.tolerance,
                        **(ipopt or {})}
        self.serial = next(StrideNLP._serial)
        self._solver: ca.Function | None = None
        self._warm_solver: ca.Function | None = None
        self.lbg, self.ubg = np.concatenate(self.rows.lower), np.concatenate(self.rows.upper)
        self.build_s = time.perf_counter() - start

    @property
    def solver(self) -> ca.Function:
        """IPOPT on the NLP, built on first use (its derivatives take most of a build: 2.6 s of
        2.8 s at 22 nodes with tendons); build_s counts it."""
        if self._solver is None:
            start = time.perf_counter()
            self._solver = ca.nlpsol("stride", "ipopt", self.problem, {"ipopt": self.options,
                                                                       "print_time": False})
            self.build_s += time.perf_counter() - start
        return self._solver

    # -- variables -------------------------------------------------------------------
    def _variables(self):
        b, s = self.blocks, self.settings
        joints = [RANGES[j[:-2]] for j in JOINTS]
        lo_th = np.r_[-np.inf, 0.4, TRUNK[0], [lo - LIMIT_MARGIN for lo, _ in joints]]  # m, rad
        hi_th = np.r_[np.inf, 1.4, TRUNK[1], [hi + LIMIT_MARGIN for _, hi in joints]]
        tau = s.torque_limit
        self.T, self.X, self.A, self.U, self.F, self.P, self.S = [], [], [], [], [], [], []
        for phase, n in zip(self.phases, self.split):
            k, rows = phase.name, phase.rows
            x_lo, x_hi = np.r_[lo_th, [-15] * NX][:, None], np.r_[hi_th, [15] * NX][:, None]
            f_lo = np.array([0.0 if a == "n" else -5.0 for _, a in rows])[:, None]  # body weights
            self.X.append(b.add(f"X_{k}", (2 * NX, n + 1), x_lo, x_hi))
            self.A.append(b.add(f"A_{k}", (NX, n + 1), -ACCELERATION, ACCELERATION))
            self.U.append(b.add(f"U_{k}", (NU, n + 1), -tau, tau))  # N m / kg
            self.F.append(b.add(f"F_{k}", (len(rows), n + 1), f_lo, 8.0))
            self.T.append(b.add(f"T_{k}", (1, 1), *s.duration[k]))
            if s.objective != "effort":  # joint power split: [positive; negative] parts, W/kg
                self.S.append(b.add(f"S_{k}", (2 * NU, n + 1), 0.0, np.inf))
        for i, phase in enumerate(self.phases[1:], 1):
            if self.added(i):
                self.P.append(b.add(f"P_{phase.name}", (len(phase.rows), 1), *self._impulse_bounds(phase.rows)))
            else:
                self.P.append(None)
        self.touchdown_rows = tuple((other_leg(p), a) for p, a in self.phases[0].rows)
        self.P_td = b.add("P_touchdown", (len(self.touchdown_rows), 1),
                          *self._impulse_bounds(self.touchdown_rows))
        self.V_td = b.add("V_touchdown", (NX, 1), -15, 15)
        self.period = ca.sum1(ca.vertcat(*self.T))

    def _impulse_bounds(self, rows):
        """Impulse bounds (N s per kg): normal >= 0 (the ground can only push)."""
        return (np.array([[0.0 if a == "n" else -np.inf] for _, a in rows]),
                np.array([[np.inf] for _ in rows]))

    def added(self, i) -> tuple[str, ...]:
        """The contact points phase i holds that phase i - 1 did not (an impact adds them)."""
        before = self.phases[i - 1].points
        return tuple(p for p in self.phases[i].points if p not in before)

    # -- pieces ----------------------------------------------------------------------
    def contact(self, rows, theta, thetad):
        """(Jacobian rows (r x 9), their dJ/dt theta' (r), velocities (r)) of contact rows."""
        jac, drift, vel = [], [], []
        for point, axis in rows:
            _, v, J, d = self.js.points[point](theta, thetad, self.slope)
            a = 0 if axis == "t" else 1
            jac.append(J[a, :])
            drift.append(d[a])
            vel.append(v[a])
        return ca.vertcat(*jac), ca.vertcat(*drift), ca.vertcat(*vel)

    def height(self, point, theta):
        r = self.js.points[point](theta, ca.DM.zeros(NX), self.slope)[0]
        return -ca.sin(self.slope) * r[0] + ca.cos(self.slope) * r[1]

    def normal_velocity(self, point, theta, thetad):
        return self.js.points[point](theta, thetad, self.slope)[1][1]

    def joint_power(self, theta_d, tau):
        """Power (W) of each joint moment: tau (extensor positive) times the extension rate."""
        return -tau * theta_d[3:]

    # -- phases ----------------------------------------------------------------------
    def _phase(self, i):
        """Node constraints, interval defects and the objective's integrals of phase i."""
        phase, n = self.phases[i], self.split[i]
        X, A, F, T = self.X[i], self.A[i], self.F[i], self.T[i]
        h = T / n
        for k in range(n + 1):
            spring = self.tendon_moments(phase, X[:NX, k], self.X[0][:NX, 0])
            self._node(phase, X[:, k], A[:, k], self.U[i][:, k], F[:, k], spring)
        for k in range(n):
            d0 = ca.vertcat(X[NX:, k], A[:, k])
            d1 = ca.vertcat(X[NX:, k + 1], A[:, k + 1])
            self.rows.add(X[:, k + 1] - X[:, k] - 0.5 * h * (d0 + d1))
            self.terms["smoothing"] += h * ca.sumsqr(A[:, k + 1] - A[:, k])
        for k, (weight, x, tau, f) in enumerate(self.samples(i, h)):
            self.terms["effort"] += weight * ca.sumsqr(tau)
            self.terms["ground"] += weight * self._ground_power(phase, x, f)
            self.terms["balance"] += weight * self._power_balance(phase, x, tau, f)
            if phase.sliding:  # the slide's friction work: the rest of its impact's loss
                t = phase.rows.index((phase.sliding, "t"))
                v_t = self.contact(((phase.sliding, "t"),), x[:NX], x[NX:])[2]
                self.terms["impacts"] -= weight * self.mass * 9.81 * f[t] * v_t
            if self.S:  # P = P+ - P-, P+- >= 0: minimising them makes them the exact parts
                S = self.S[i][:, k]
                self.rows.add(self.joint_power(x[NX:], tau) / self.mass - (S[:NU] - S[NU:]))
                self.terms["positive"] += weight * self.mass * ca.sum1(S[:NU])
                self.terms["negative"] += weight * self.mass * ca.sum1(S[NU:])

    def _power_balance(self, phase, x, tau, f):
        """The power (W) the budget's balance integrates at one node (result.budget): the
        active joints' net power less what the contacts, the range-of-motion walls and the
        tendons take."""
        th, thd = x[:NX], x[NX:]
        spring = self.tendon_moments(phase, th, self.X[0][:NX, 0])
        power = ca.sum1(self.joint_power(thd, tau)) + ca.dot(self.js.passive(th), thd) \
            - ca.dot(spring, thd[3:])
        if phase.rows:
            power += self.mass * 9.81 * ca.dot(f, self.contact(phase.rows, th, thd)[2])
        return power

    def _ground_power(self, phase, x, f):
        """The power (W) of the ground's force on the held contact points at one node: zero for
        a point that does not move; the transcription's drift makes it otherwise."""
        if not phase.rows:
            return 0.0
        held = held_rows(phase.rows, phase.sliding)
        v = self.contact(phase.rows, x[:NX], x[NX:])[2]
        return self.mass * 9.81 * ca.dot(f[held], v[held])

    def samples(self, i, h, blocks=None):
        """(trapezoidal weight (s), state, joint moments (N m), contact forces (body weights))
        at each node of phase i. `blocks`: numeric blocks by name (default: the symbols)."""
        name, n = self.phases[i].name, self.split[i]
        get = (lambda key: blocks[f"{key}_{name}"]) if blocks is not None else \
            (lambda key: self.blocks.symbols[self.blocks.names.index(f"{key}_{name}")])
        X, U, F = get("X"), self.mass * get("U"), get("F")
        return [(h * (0.5 if k in (0, n) else 1.0), X[:, k], U[:, k], F[:, k]) for k in range(n + 1)]

    def tendon_moments(self, phase, theta, theta_touchdown):
        """The stance leg's tendon moments (N m, 6, extensor positive; problem.TENDON_JOINTS):
        k m (theta - theta_touchdown) on R's joints while R holds the ground, else zero.
        Symbolic or numeric theta (9)."""
        out = [0.0] * NU
        if phase.points:
            for joint, k in self.settings.tendons.items():
                j = JOINTS.index(f"{joint}_R")
                out[j] = k * self.mass * (theta[3 + j] - theta_touchdown[3 + j])
        return ca.vertcat(*out)

    def _node(self, phase, x, thdd, u, f, spring=0.0):
        """Equations of motion, contact acceleration, friction cone and ground clearance at
        one collocation point (state x, accelerations, active moments u (N m/kg), forces f
        (BW), tendon moments `spring` (N m))."""
        rows, m, g = self.rows, self.mass, 9.81
        th, thd, tau = x[:NX], x[NX:], m * u + spring
        residual = (self.js.mass(th) @ thdd + self.js.bias(th, thd) - self.js.gravity(th)
                    - self.js.passive(th) + ca.vertcat(0, 0, 0, tau))
        if phase.rows:
            Jc, drift, vel = self.contact(phase.rows, th, thd)
            residual -= Jc.T @ (m * g * f)
            held = held_rows(phase.rows, phase.sliding)
            rows.add((Jc @ thdd + drift)[held])
            total_n = ca.sum1(ca.vertcat(*[f[k] for k, (_, a) in enumerate(phase.rows) if a == "n"]))
            for k, (_, a) in enumerate(phase.rows):
                if a == "t" and k in held:
                    rows.add(ca.vertcat(self.mu * total_n - f[k], self.mu * total_n + f[k]), 0.0, np.inf)
                elif a == "t":  # kinetic friction against the slip, whose sign s holds
                    rows.add(f[k] + self.slip * self.mu * total_n)
                    rows.add(self.slip * vel[k], 0.0, np.inf)
        rows.add(residual / m)
        free = [p for p in self.js.points if p not in phase.points]
        rows.add(ca.vertcat(*[self.height(p, th) for p in free]), 0.0, np.inf)

    def _transition(self, i):
        """Phase i-1 -> i: an impact where a point is added, else a release (force zero)."""
        before, after = self.phases[i - 1], self.phases[i]
        X0, X1, rows = self.X[i - 1][:, -1], self.X[i][:, 0], self.rows
        th, v_minus, v_plus = X0[:NX], X0[NX:], X1[NX:]
        rows.add(X1[:NX] - th)
        added = self.added(i)
        if added:
            for p in added:
                rows.add(self.height(p, th))
                rows.add(self.normal_velocity(p, th, v_minus), -np.inf, 0.0)
            self._impact(after.rows, th, v_minus, v_plus, self.P[i - 1])
        else:
            rows.add(v_plus - v_minus)
            if before.sliding:  # the slide ends when the point's slip reaches zero
                rows.add(self.contact(((before.sliding, "t"),), th, v_minus)[2])
            dropped = [k for k, (p, a) in enumerate(before.rows)
                       if a == "n" and p not in after.points]
            rows.add(self.F[i - 1][dropped, -1])

    def _impact(self, contact_rows, th, v_minus, v_plus, P, sliding=""):
        """M (theta'+ - theta'-) = J_c^T p, J_c theta'+ = 0 on the held rows, and the friction
        cone (sticking), or the sliding mode's rows (`sliding`: the point that slides)."""
        m = self.mass
        Jc, _, _ = self.contact(contact_rows, th, v_plus)
        M = self.js.mass(th)
        self.rows.add((M @ (v_plus - v_minus) - Jc.T @ (m * P)) / m)
        self.rows.add((Jc @ v_plus)[held_rows(contact_rows, sliding)])
        if sliding:
            self._sliding_impulse(contact_rows.index((sliding, "t")), contact_rows.index((sliding, "n")),
                                  self.contact(((sliding, "t"),), th, v_minus)[2],
                                  self.contact(((sliding, "t"),), th, v_plus)[2], P)
        else:  # sticking, under either law: the impulse inside the friction cone
            total_n = ca.sum1(ca.vertcat(*[P[k] for k, (_, a) in enumerate(contact_rows) if a == "n"]))
            for k, (_, a) in enumerate(contact_rows):
                if a == "t":
                    self.rows.add(ca.vertcat(self.mu * total_n - P[k], self.mu * total_n + P[k]),
                                  0.0, np.inf)
        T_c = 0.5 * (ca.bilin(M, v_minus, v_minus) - ca.bilin(M, v_plus, v_plus))
        self.terms["impacts"] += T_c
        self.terms["balance"] -= T_c

    def _sliding_impulse(self, t, n, slip_minus, slip_plus, P):
        """Coulomb's sliding mode: p_t = -s mu p_n, p_n >= 0, s v_t >= 0 before and after (the
        slip keeps its sign through the impact, so the Darboux-Keller process never sticks)."""
        self.rows.add(P[t] + self.slip * self.mu * P[n])
        self.rows.add(ca.vertcat(P[n], self.slip * slip_minus, self.slip * slip_plus), 0.0, np.inf)

    def _touchdown(self):
        """L's touchdown at the flight's end, its impact and periodicity with the start."""
        end, start, rows = self.X[-1][:, -1], self.X[0][:, 0], self.rows
        th, v_minus = end[:NX], end[NX:]
        for p in dict.fromkeys(p for p, _ in self.touchdown_rows):
            rows.add(self.height(p, th))
            rows.add(self.normal_velocity(p, th, v_minus), -np.inf, 0.0)
        sliding = self.phases[0].sliding and other_leg(self.phases[0].sliding)
        self._impact(self.touchdown_rows, th, v_minus, self.V_td, self.P_td, sliding)
        step = self.speed * self.period
        shift = ca.vertcat(step * ca.cos(self.slope), step * ca.sin(self.slope), ca.DM.zeros(7))
        rows.add(swap_legs(th) - shift - start[:NX])
        rows.add(swap_legs(self.V_td) - start[NX:])
        rows.add(start[0])

    def _objective(self):
        """The scene's objective per distance (scaled by 100 / (m g)^2 for effort, 1 / (m g) for
        the work objectives, so that IPOPT sees values of order one), and the smoothing term
        (problem.SMOOTHING)."""
        s, m, terms = self.settings, self.mass, self.terms
        distance = self.speed * self.period
        effort = terms["effort"] / distance * 100.0 / (m * 9.81) ** 2
        if s.objective == "effort":
            f = effort
        else:
            work = terms["positive"] if s.objective == "work" else \
                metabolic(terms["positive"], terms["negative"])
            f = work / distance / (m * 9.81) + WORK_REGULARISATION * effort
        return (f + s.impact_weight * terms["impacts"] / distance / (m * 9.81)
                + SMOOTHING * terms["smoothing"] / distance)

    def variant(self, **changes) -> StrideNLP:
        """The NLP of the same body and IPOPT options with settings changed (e.g. touchdown=
        "slide"), built once and kept."""
        key = tuple(sorted(changes.items()))
        if not hasattr(self, "_variants"):
            self._variants: dict = {}
        if key not in self._variants:
            self._variants[key] = StrideNLP(self.js, replace(self.settings, **changes), self.ipopt)
        return self._variants[key]

    # -- solve -----------------------------------------------------------------------
    def _with_power_split(self, guess: dict) -> dict:
        """The guess with the power split (S_*) of its own moments and rates where it has none
        (a solution of an objective without the split, as a warm start)."""
        missing = [i for i, p in enumerate(self.phases) if self.S and f"S_{p.name}" not in guess]
        if not missing:
            return guess
        guess = dict(guess)
        for i in missing:
            name = self.phases[i].name
            power = -np.asarray(guess[f"U_{name}"]) * np.asarray(guess[f"X_{name}"])[NX + 3:]
            guess[f"S_{name}"] = np.vstack([np.maximum(power, 0), np.maximum(-power, 0)])
        return guess

    @property
    def layout(self) -> tuple:
        """What a warm start needs to match: this NLP itself (its serial number: another body
        or objective has the same blocks and rows), its block names and number of rows."""
        return self.serial, tuple(self.blocks.names), len(self.lbg)

    def solve(self, guess: dict, speed: float, slope: float = 0.0, mu: float = 0.8,
              cadence: float | None = None) -> Solved:
        """Solve from a guess (blocks by name, or a previous Solved's blocks); `cadence`
        (steps/min) imposes the half-period 60 / cadence."""
        return self._run(self.solver, {"x0": self.blocks.join(self._with_power_split(guess))},
                         speed, slope, mu, cadence)

    def resolve(self, previous: Solved, speed: float, slope: float = 0.0, mu: float = 0.8,
                cadence: float | None = None) -> Solved:
        """Solve from a solution of this same NLP (its layout) at neighbouring parameters, with
        its multipliers (IPOPT's warm start, WARM_START; the solver built on first use, with the
        cold solver's derivative functions: 0.2 s instead of 2.7 s at 22 nodes); from
        its primal values alone (`solve`) when that fails."""
        if previous.layout != self.layout or previous.lam_x is None:
            raise ValueError("resolve: the previous solution is not one of this NLP's (solve from its blocks)")
        if self._warm_solver is None:  # the cold solver's derivatives, not derived again
            start = time.perf_counter()
            shared = {k: self.solver.get_function(f"nlp_{f}")
                      for k, f in (("grad_f", "grad_f"), ("jac_g", "jac_g"), ("hess_lag", "hess_l"))}
            self._warm_solver = ca.nlpsol("stride_warm", "ipopt", self.problem, {
                "ipopt": {**self.options, **WARM_START}, "print_time": False, **shared})
            self.build_s += time.perf_counter() - start
        got = self._run(self._warm_solver, {"x0": previous.x, "lam_x0": previous.lam_x,
                                            "lam_g0": previous.lam_g}, speed, slope, mu, cadence)
        return got if got.success else self.solve(previous.blocks, speed, slope, mu, cadence)

    def _run(self, solver, start: dict, speed, slope, mu, cadence) -> Solved:
        """One IPOPT run of `solver` from `start` (x0 and maybe multipliers)."""
        lbg, ubg = self.lbg.copy(), self.ubg.copy()
        k = sum(len(e) for e in self.rows.lower[:self.period_row])
        if cadence is not None:
            lbg[k] = ubg[k] = 60.0 / cadence
        b = self.blocks
        clock = time.perf_counter()
        out = solver(**start, p=np.array([speed, slope, mu]), lbx=np.concatenate(b.lower),
                     ubx=np.concatenate(b.upper), lbg=lbg, ubg=ubg)
        seconds = time.perf_counter() - clock
        stats = solver.stats()
        x = np.asarray(out["x"], float).ravel()
        return Solved(blocks=b.split(x), success=bool(stats["success"]),
                      status=str(stats["return_status"]), iterations=int(stats["iter_count"]),
                      solve_s=seconds, objective=float(out["f"]), x=x,
                      lam_g=np.asarray(out["lam_g"], float).ravel(),
                      parameters={"speed": speed, "slope": slope, "mu": mu, "cadence": cadence},
                      lam_x=np.asarray(out["lam_x"], float).ravel(), layout=self.layout)


_BUILT: dict[str, StrideNLP] = {}  # the last NLPS_KEPT NLPs built, by what they hold
NLPS_KEPT = 4  # a compare band alternates a few bodies and objectives; each NLP holds its solver


def build(body, settings: StrideSettings) -> StrideNLP:
    """The stride NLP of a body (mechanics.body.Body) and settings, built once per process and
    kept while it is among the last NLPS_KEPT asked for (keyed by everything it holds: the body
    and the settings)."""
    key = hashlib.sha256(pickle.dumps((body, settings))).hexdigest()
    nlp = _BUILT.pop(key, None) or StrideNLP(JointSpace(body), settings)
    _BUILT[key] = nlp  # the most recent last
    while len(_BUILT) > NLPS_KEPT:
        _BUILT.pop(next(iter(_BUILT)))
    return nlp
