"""The landing: finite motion between impacts, contact events, the impact sequence.

Between impacts the natural coordinates follow M q'' = Q + Phi_q^T lambda with Phi the body
constraints, the locked joints and the active contacts (each held in both directions; on a
flat foot the forefoot's tangential row is implied by the heel's, as at the impact). With
G = Phi_q M^-1 Phi_q^T (the impact's matrix):

    lambda = G^-1 (gamma - Phi_q M^-1 Q)     q'' = M^-1 (Q + Phi_q^T lambda)
    gamma = -(Phi_q q')_q q' - 2 a Phi_q q' - a^2 Phi        (Baumgarte, a = BAUMGARTE / s)

Contact rows of lambda are the ground's force on the foot point (N, tangential, normal).
Q holds gravity and the joint torques: free hinges (none), spring-damper (tau = -k (theta -
theta_0) - c theta', theta_0 the touchdown angle: a holding law on the touchdown posture), or
locked (a constraint). Events: a foot point reaching the ground (an impact, by the projection,
with the new contact set), a contact whose normal force would pull (released: a contact can
only push). The landing ends when heel and forefoot are both down, or at `t_max`.

Energy bookkeeping: T + V_gravity + V_springs + E_damped + sum of T_c stays equal to its value
before the first impact, to the integration tolerance; `energy_error` is its largest drift.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .compiled import Compiled
from .impact import ground_axes
from .model import STATE, STRIKES, Model
from .errors import InputError

GRAVITY = 9.81  # m/s^2
BAUMGARTE = 50.0  # 1/s, critically damped constraint stabilisation
JOINT_MODELS = ("free", "spring-damper", "locked")
# Fixed-step explicit schemes: classical Runge-Kutta (4th order) and the midpoint rule (2nd)
INTEGRATORS = ("rk4", "midpoint")
# Joints: (name, parent segment, child segment); the hip only where the trunk is a rigid body.
JOINTS = (("hip", "trunk", "thigh"), ("knee", "thigh", "shank"), ("ankle", "shank", "foot"),
          ("swing_hip", "trunk", "swing_thigh"), ("swing_knee", "swing_thigh", "swing_shank"),
          ("swing_ankle", "swing_shank", "swing_foot"))


@dataclass(frozen=True)
class Joints:
    """The joint model of a landing: free hinges, passive springs and dampers, or locked."""

    model: str = "free"
    stiffness: dict[str, float] = field(default_factory=dict)  # N m / rad per joint
    damping: dict[str, float] = field(default_factory=dict)  # N m s / rad per joint
    locked: tuple[str, ...] = ()  # with model "locked": the joints held at their touchdown angle


@dataclass(frozen=True)
class ImpactEvent:
    time: float  # s after the first touchdown
    contact: str  # the point that struck
    active: tuple[str, ...]  # contact set after the impact
    T_c: float  # J
    dv_trunk: tuple[float, float] | None  # m/s
    impulse: tuple[float, float]  # total (tangential, normal), N s
    mu_c: float | None  # |t| / n of the impulse; None when the ground does not push


@dataclass(frozen=True)
class Landing:
    """A simulated landing: time histories, impacts and the checks of its assumptions."""

    t: np.ndarray  # s
    q: np.ndarray  # (len(t), n) natural coordinates, m
    qd: np.ndarray  # m/s
    T: np.ndarray  # J
    energy: np.ndarray  # J, T + V + springs + damped + absorbed: constant up to drift
    force: np.ndarray  # (len(t), 2): total contact force (tangential, normal), N; nan in flight
    active: list  # contact set at each sample
    impacts: list[ImpactEvent]
    releases: list[tuple[float, str, float]]  # (time, point, normal force N < 0): contacts let go
    T_c_total: float  # J
    mu_c_max: float  # largest |f_t| / f_n where the ground pushes (impacts and contact phases)
    no_slip_held: bool  # mu_c stayed within the ground's friction everywhere
    slip_at: list[float]  # times where it did not
    energy_error: float  # J
    drift: float  # largest constraint violation, m
    ended: str  # why the simulation stopped
    warnings: list[str]

    def to_dict(self) -> dict:
        return {"impacts": [{"time": e.time, "contact": e.contact, "active": list(e.active),
                             "T_c": e.T_c, "dv_trunk": list(e.dv_trunk) if e.dv_trunk else None,
                             "impulse": list(e.impulse), "mu_c": e.mu_c} for e in self.impacts],
                "T_c_total": self.T_c_total, "mu_c_max": self.mu_c_max,
                "no_slip_held": self.no_slip_held, "slip_at": self.slip_at,
                "releases": [{"time": t, "contact": p, "normal_force": f} for t, p, f in self.releases],
                "energy_error": self.energy_error, "drift": self.drift, "ended": self.ended,
                "warnings": self.warnings,
                "duration": float(self.t[-1])}


class LandingModel:
    """The landing equations of one model, joint model and ground, compiled per contact set."""

    def __init__(self, model: Model, joints: Joints = Joints(), slope: float = 0.0,
                 compiled: bool = True, integrator: str = "rk4"):
        if not {"heel", "forefoot"} <= set(model.index):
            raise InputError(f"model {model.kind!r} has no foot to land on (it is impact-only)")
        if integrator not in INTEGRATORS:
            raise InputError(f"integrator {integrator!r}: expected one of {', '.join(INTEGRATORS)}")
        self.model, self.joints, self.slope, self.integrator = model, joints, slope, integrator
        self.t_axis, self.n_axis = ground_axes(slope)
        rigid = {b.segment: b for b in model.bodies}
        self.hinges = [(name, rigid[p], rigid[c]) for name, p, c in JOINTS
                       if p in rigid and c in rigid]
        if joints.model not in JOINT_MODELS:
            raise InputError(f"joint model {joints.model!r}: expected one of {', '.join(JOINT_MODELS)}")
        self.compiled = compiled
        self._functions = {}
        q = ca.SX.sym("q", model.n)
        self.gravity = model.momentum_matrix.T @ np.array([0.0, -GRAVITY])  # constant Q
        self._angles = ca.Function("joint_angles", [q], [ca.vertcat(*[self._angle(q, p, c)
                                                                      for _, p, c in self.hinges])])

    # -- pieces ----------------------------------------------------------------------
    def _direction(self, q, body):
        i, j = body.base
        return q[self.model.cols(j)] - q[self.model.cols(i)]

    def _angle(self, q, parent, child):
        """Relative angle of child to parent base directions (rad), smooth away from +-pi."""
        dp, dc = self._direction(q, parent), self._direction(q, child)
        return ca.atan2(dp[0] * dc[1] - dp[1] * dc[0], ca.dot(dp, dc))

    def joint_angles(self, q) -> np.ndarray:
        return np.asarray(self._angles(q), float).ravel()

    def _constraints(self, q, active, s_anchor, rest):
        """Body, locked-joint and contact constraints (SX)."""
        rows = [self.model.constraints(q)]
        if self.joints.model == "locked":
            for k, (name, p, c) in enumerate(self.hinges):
                if name in self.joints.locked:
                    rows.append(self._angle(q, p, c) - rest[k])
        for k, point in enumerate(active):
            r = q[self.model.cols(point)]
            if k == 0:
                rows.append(ca.dot(r, ca.DM(self.t_axis)) - s_anchor)
            rows.append(ca.dot(r, ca.DM(self.n_axis)))
        return ca.vertcat(*rows)

    def _torques(self, q, qd, rest):
        """Generalised joint forces (spring-damper) and the damping power (W)."""
        Q, power = ca.SX.zeros(self.model.n), 0
        if self.joints.model != "spring-damper":
            return Q, power
        theta = self._angles(q)
        rate = ca.jtimes(theta, q, qd)
        J = ca.jacobian(theta, q)
        for k, (name, _, _) in enumerate(self.hinges):
            stiff = self.joints.stiffness.get(name, 0.0)
            damp = self.joints.damping.get(name, 0.0)
            tau = -stiff * (theta[k] - rest[k]) - damp * rate[k]
            Q += J[k, :].T * tau
            power += damp * rate[k] ** 2
        return Q, power

    def _spring_energy(self, q, rest):
        """Elastic energy of the joint springs (J, SX)."""
        if self.joints.model != "spring-damper":
            return 0
        theta = self._angles(q)
        return sum(0.5 * self.joints.stiffness.get(name, 0.0) * (theta[k] - rest[k]) ** 2
                   for k, (name, _, _) in enumerate(self.hinges))

    def rhs(self, active: tuple[str, ...]) -> ca.Function:
        """(q, q', s_anchor, rest) -> (q', q'', damping power, contact force [t, n] total,
        normal force per held point, constraint residual, mechanical energy), symbolic."""
        key = ("rhs",) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(self.hinges))
            phi = self._constraints(q, active, s_anchor, rest)
            Phi = ca.jacobian(phi, q)
            M_inv = ca.DM(m.M_inv)
            Q_joint, power = self._torques(q, qd, rest)
            Q = ca.DM(self.gravity) + Q_joint
            phid = Phi @ qd
            gamma = -ca.jtimes(phid, q, qd) - 2 * BAUMGARTE * phid - BAUMGARTE**2 * phi
            lam = ca.solve(Phi @ M_inv @ Phi.T, gamma - Phi @ (M_inv @ Q))
            qdd = M_inv @ (Q + Phi.T @ lam)
            contact = lam[phi.shape[0] - (len(active) + 1):] if active else ca.SX.zeros(0)
            normal = contact[1:] if active else ca.SX.zeros(1)
            force = ca.vertcat(contact[0], ca.sum1(normal)) if active else ca.SX.zeros(2)
            energy = m.kinetic_energy(qd) + GRAVITY * ca.dot(ca.DM(m.momentum_matrix[1]), q) \
                + self._spring_energy(q, rest)
            self._functions[key] = ca.Function(
                "rhs", [q, qd, s_anchor, rest],
                [qd, qdd, power, force, normal, ca.norm_inf(phi), energy],
                ["q", "qd", "s_anchor", "rest"],
                ["qd_out", "qdd", "power", "force", "normal", "residual", "energy"])
        return self._functions[key]

    def rk4(self, active, x, h, s_anchor, rest):
        """One step of [q, q', E_damped] by the model's integrator (symbolic or numeric)."""
        n, rhs = self.model.n, self.rhs(active)

        def f(state):
            out = rhs(state[:n], state[n:2 * n], s_anchor, rest)
            return ca.vertcat(out[0], out[1], out[2])

        if self.integrator == "midpoint":
            return x + h * f(x + h / 2 * f(x))
        k1 = f(x)
        k2 = f(x + h / 2 * k1)
        k3 = f(x + h / 2 * k2)
        k4 = f(x + h * k3)
        return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)

    def heights(self, q):
        """Height of heel and forefoot above the ground (m)."""
        return ca.vertcat(*[ca.dot(q[self.model.cols(p)], ca.DM(self.n_axis))
                            for p in ("heel", "forefoot")])

    def impact_map(self, active) -> ca.Function:
        """(q, q'-, rest) -> (q'+, T_c, total impulse [t, n]) with contact set `active`."""
        key = ("impact",) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            rest = ca.SX.sym("rest", len(self.hinges))
            phi = self._constraints(q, active, ca.SX.sym("s"), rest)
            Phi = ca.jacobian(phi, q)
            M_inv = ca.DM(m.M_inv)
            b = Phi @ qd
            lam = -ca.solve(Phi @ M_inv @ Phi.T, b)
            contact = lam[phi.shape[0] - (len(active) + 1):]
            self._functions[key] = ca.Function(
                "impact_map", [q, qd, rest],
                [qd + M_inv @ (Phi.T @ lam), -0.5 * ca.dot(lam, b),
                 ca.vertcat(contact[0], ca.sum1(contact[1:]))],
                ["q", "qd", "rest"], ["qd_plus", "T_c", "impulse"])
        return self._functions[key]

    def functions(self, active: tuple[str, ...]):
        """(step, forces), compiled, for a contact set: one RK4 step with the foot heights
        after it, and the forces, residual and energy at a state. Built once per set."""
        key = ("numeric",) + tuple(active)
        if key in self._functions:
            return self._functions[key]
        m = self.model
        x, h = ca.SX.sym("x", 2 * m.n + 1), ca.SX.sym("h")
        s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(self.hinges))
        x_next = self.rk4(active, x, h, s_anchor, rest)
        step = ca.Function("step", [x, h, s_anchor, rest], [x_next, self.heights(x_next[:m.n])],
                           ["x", "h", "s_anchor", "rest"], ["x_next", "heights"])
        q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
        out = self.rhs(active)(q=q, qd=qd, s_anchor=s_anchor, rest=rest)
        forces = ca.Function("forces", [q, qd, s_anchor, rest],
                             [out["force"], out["normal"], out["residual"], out["energy"],
                              self.heights(q)],
                             ["q", "qd", "s_anchor", "rest"],
                             ["force", "normal", "residual", "energy", "heights"])
        wrap = Compiled if self.compiled else _Interpreted
        self._functions[key] = (wrap(step), wrap(forces))
        return self._functions[key]


class _Interpreted:
    """The same call interface as Compiled, for a CasADi Function run by CasADi."""

    def __init__(self, function):
        self.function = function

    def __call__(self, *args):
        return {k: v.full().ravel() if v.size2() == 1 else v.full()
                for k, v in zip(self.function.name_out(), self.function.call(list(args)))}


def simulate(lm: LandingModel, strike: str, q0, qd0, friction: float, dt: float = 2e-4,
             t_max: float = 0.2, impact_map=None) -> Landing:
    """Follow the landing from the touchdown (q0, qd0 just before the first impact).

    `impact_map(q, qd, active) -> (qd_plus, T_c, impulse_total)` applies an impact with a
    contact set (landing.impact_for by default).
    """
    m = lm.model
    impact_map = impact_map or (lambda q, qd, active: impact_for(lm, q, qd, active))
    q, qd = np.asarray(q0, float), np.asarray(qd0, float)
    rest = lm.joint_angles(q)
    start = lm.functions(())[1](q, qd, 0.0, rest)
    E0 = float(start["energy"][0])
    for k, p in enumerate(("heel", "forefoot")):
        if p not in STRIKES[strike] and start["heights"][k] < -1e-9:
            raise InputError(f"{strike} strike: the {p} is {-start['heights'][k] * 1e3:.1f} mm below "
                             "the ground at touchdown")
    active = ()
    impacts, releases, slip_at, warnings = [], [], [], []
    absorbed, damped, t = 0.0, 0.0, 0.0
    record = {"t": [], "q": [], "qd": [], "T": [], "energy": [], "force": [], "active": []}
    drift, mu_max = 0.0, 0.0
    s_anchor = 0.0
    pending = list(STRIKES[strike])

    def strike_now(q, qd, points, time):
        nonlocal active, absorbed, s_anchor, mu_max
        new = tuple(active) + tuple(p for p in points if p not in active)
        if not active:
            s_anchor = float(q[m.cols(new[0])] @ lm.t_axis)
        qd_plus, T_c, total = impact_map(q, qd, new)
        dv = (m.com_matrix(m.trunk) @ (qd_plus - qd)) if m.trunk else None
        mu = abs(total[0]) / total[1] if total[1] > 0 else None  # undefined when not pushed
        if mu is None or mu > friction:
            slip_at.append(time)
        else:
            mu_max = max(mu_max, mu)
        impacts.append(ImpactEvent(time, "+".join(points), new, T_c,
                                   tuple(map(float, dv)) if dv is not None else None,
                                   (float(total[0]), float(total[1])), mu))
        absorbed += T_c
        active = new
        return qd_plus

    def sample(q, qd, force, mechanical):
        record["t"].append(t)
        record["q"].append(q.copy())
        record["qd"].append(qd.copy())
        record["T"].append(0.5 * qd @ m.M @ qd)
        record["energy"].append(mechanical + damped + absorbed)
        record["force"].append(force)
        record["active"].append(active)

    sample(q, qd, np.full(2, np.nan), E0)  # just before the first impact
    qd = strike_now(q, qd, pending, 0.0)
    # a foot point can strike only after it has been above the ground since its last contact
    armed = {p: p not in active for p in ("heel", "forefoot")}
    ended = "duration reached"
    while True:
        step, forces = lm.functions(active)
        out = forces(q, qd, s_anchor, rest)
        force, normals = out["force"], out["normal"]
        drift = max(drift, float(out["residual"][0]))
        for k, p in enumerate(("heel", "forefoot")):
            armed[p] = armed[p] or (p not in active and out["heights"][k] > 1e-9)
        pulling = active and np.any(normals < -1e-9 * max(1.0, float(np.max(np.abs(normals)))))
        if set(active) == {"heel", "forefoot"}:
            sample(q, qd, force, float(out["energy"][0]))
            ended = "heel and forefoot both down"
            if pulling:
                warnings.append("with both points down the ground would pull "
                                f"{' and '.join(p for p, n in zip(active, normals) if n < 0)}: "
                                "it would lift again")
            break
        if pulling:
            pulled = [p for p, n in zip(active, normals) if n < 0]
            releases.append((t, "+".join(pulled), float(min(normals))))
            active = tuple(p for p in active if p not in pulled)
            if active:  # the first held point carries the tangential row
                s_anchor = float(q[m.cols(active[0])] @ lm.t_axis)
            if len(releases) > 20:
                ended = "contact chatter: more than 20 releases"
                warnings.append(ended)
                break
            continue
        if active and force[1] > 0:
            mu = abs(force[0]) / force[1]
            mu_max = max(mu_max, mu)
            if mu > friction:
                slip_at.append(t)
        sample(q, qd, force if active else np.full(2, np.nan), float(out["energy"][0]))
        if t >= t_max - 1e-12:
            break
        x = np.concatenate([q, qd, [damped]])
        h = min(dt, t_max - t)
        res = step(x, h, s_anchor, rest)
        x_next, heights = res["x_next"], res["heights"]
        hits = [k for k, p in enumerate(("heel", "forefoot"))
                if p not in active and armed[p] and heights[k] <= 0.0]
        if hits:
            h = _event_step(step, x, h, s_anchor, rest, hits)
            x_next = step(x, h, s_anchor, rest)["x_next"]
        t += h
        q, qd, damped = x_next[:m.n], x_next[m.n:2 * m.n], float(x_next[-1])
        if hits:
            out = forces(q, qd, s_anchor, rest)
            sample(q, qd, np.full(2, np.nan), float(out["energy"][0]))
            points = [("heel", "forefoot")[k] for k in hits]
            for p in points:
                armed[p] = False
            qd = strike_now(q, qd, points, t)
    energy = np.array(record["energy"])
    return Landing(t=np.array(record["t"]), q=np.array(record["q"]), qd=np.array(record["qd"]),
                   T=np.array(record["T"]), energy=energy, force=np.array(record["force"]),
                   active=record["active"], impacts=impacts, releases=releases,
                   T_c_total=absorbed, mu_c_max=mu_max, no_slip_held=not slip_at,
                   slip_at=slip_at, energy_error=float(np.max(np.abs(energy - E0))),
                   drift=drift, ended=ended, warnings=warnings)


def _event_step(step, x, h, s_anchor, rest, hits, tol=1e-13):
    """The step length at which the first of `hits` reaches the ground (secant + bisection)."""
    def height(s):
        return min(step(x, s, s_anchor, rest)["heights"][k] for k in hits)

    lo, hi = 0.0, h
    g_lo, g_hi = height(0.0), height(h)
    for _ in range(60):
        s = hi - g_hi * (hi - lo) / (g_hi - g_lo) if g_hi != g_lo else 0.5 * (lo + hi)
        if not lo < s < hi:
            s = 0.5 * (lo + hi)
        g = height(s)
        if abs(g) < tol or hi - lo < 1e-15:
            return s
        if g > 0:
            lo, g_lo = s, g
        else:
            hi, g_hi = s, g
    return hi


def landing_function(lm: LandingModel, strike: str, steps: int = 60) -> ca.Function:
    """The two-impact landing as a CasADi Function (differentiable).

    (x, t_e) -> T_c_total, T_c (both impacts), residual, force_t, force_n: x the touchdown state
    (model.STATE), t_e the time (s) of the second impact. The strike point is held from the
    first impact; `steps` RK4 steps of t_e / steps integrate to t_e, where `residual` is the
    other point's height (zero at the event) and `approach` its normal velocity then (m/s,
    negative when it strikes); force_t, force_n are the contact force (N) and
    height the other point's height (m) after each step. `absorbed_function` solves
    residual = 0 for t_e.
    """
    if strike not in ("heel", "forefoot"):
        raise InputError("the two-impact landing starts with a heel or forefoot strike")
    m = lm.model
    point, other = strike, "heel" if strike == "forefoot" else "forefoot"
    xs = ca.SX.sym("x", len(STATE))
    q0, qd0 = m.state(xs, point)
    touchdown = ca.Function("touchdown", [xs], [q0, qd0, lm._angles(q0),
                                                ca.dot(q0[m.cols(point)], ca.DM(lm.t_axis))])
    n = 2 * m.n + 1
    xk, h = ca.SX.sym("xk", n), ca.SX.sym("h")
    s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(lm.hinges))
    x_next = lm.rk4((point,), xk, h, s_anchor, rest)
    forces = lm.rhs((point,))(x_next[:m.n], x_next[m.n:2 * m.n], s_anchor, rest)[3]
    height = ca.dot(x_next[m.cols(other)], ca.DM(lm.n_axis))
    step = ca.Function("step", [xk, ca.vertcat(h, s_anchor, rest)],
                       [x_next, ca.vertcat(forces, height)])
    run = step.mapaccum("run", steps, [0], [0])

    x = ca.MX.sym("x", len(STATE))
    t_e = ca.MX.sym("t_e")
    q, qd, rest_mx, s_mx = touchdown(x)
    qd1, T_c1, _ = lm.impact_map((point,))(q, qd, rest_mx)
    params = ca.repmat(ca.vertcat(t_e / steps, s_mx, rest_mx), 1, steps)
    states, f = run(ca.vertcat(q, qd1, 0), params)
    end = states[:, -1]
    q_e, qd_e = end[:m.n], end[m.n:2 * m.n]
    residual = ca.dot(q_e[m.cols(other)], ca.DM(lm.n_axis))
    _, T_c2, _ = lm.impact_map((point, other))(q_e, qd_e, rest_mx)
    approach = ca.dot(qd_e[m.cols(other)], ca.DM(lm.n_axis))
    return ca.Function("landing", [x, t_e],
                       [T_c1 + T_c2, ca.vertcat(T_c1, T_c2), residual, approach, f[0, :].T,
                        f[1, :].T, f[2, :].T],
                       ["x", "t_e"], ["T_c_total", "T_c", "residual", "approach", "force_t",
                                      "force_n", "height"])


def absorbed_function(lm: LandingModel, strike: str, t_guess: float, steps: int = 60) -> ca.Function:
    """x -> (T_c_total, t_e): the summed absorbed energy of the two-impact landing, with the
    second impact's time found by Newton's method from `t_guess` (differentiable by the
    implicit function theorem)."""
    landing = landing_function(lm, strike, steps)
    t_e, x = ca.MX.sym("t_e"), ca.MX.sym("x", len(STATE))
    event = ca.rootfinder("event", "newton", ca.Function("g", [t_e, x], [landing(x, t_e)[2]]),
                          {"abstol": 1e-13, "max_iter": 50})
    t_star = event(t_guess, x)
    return ca.Function("absorbed", [x], [landing(x, t_star)[0], t_star], ["x"], ["T_c_total", "t_e"])


def impact_for(lm: LandingModel, q, qd, active):
    """Projection impact with contact set `active` (numeric): (q'+, T_c, total impulse)."""
    out = lm.impact_map(tuple(active))(q, qd, lm.joint_angles(q))
    return tuple(np.asarray(v, float).ravel() if k != 1 else float(v) for k, v in enumerate(out))


def simulate_state(lm: LandingModel, strike: str, x, friction: float, dt: float,
                   duration: float) -> Landing:
    """Simulate the landing from a touchdown state x (model.STATE, SI)."""
    q, qd = lm.model.state_numeric(x, STRIKES[strike][0])
    return simulate(lm, strike, q, qd, friction, dt, duration)


def history_rows(landing: Landing, model: Model):
    """Time histories as CSV rows: time, energies, contact forces, mu_c, active set, q."""
    names = [f"{p.name}_{axis}" for p in model.points for axis in ("x", "z")]
    yield ["t_s", "T_J", "energy_J", "f_t_N", "f_n_N", "mu_c", "active", *names]
    for k, t in enumerate(landing.t):
        f_t, f_n = landing.force[k]
        mu = abs(f_t) / f_n if f_n > 0 else float("nan")
        yield [t, landing.T[k], landing.energy[k], f_t, f_n, mu, "+".join(landing.active[k]),
               *landing.q[k]]
