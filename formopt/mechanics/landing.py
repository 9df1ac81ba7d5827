"""The landing: finite motion between impacts, contact events, the impact sequence.

Between impacts the natural coordinates follow M q'' = Q + F^T lambda with Phi the body
constraints, the locked joints and the active contacts, and F = Phi except where a point
slides. With G = Phi_q M^-1 F_q^T (the impact's matrix when nothing slides):

    lambda = G^-1 (gamma - Phi_q M^-1 Q)     q'' = M^-1 (Q + F_q^T lambda)
    gamma = -(Phi_q q')_q q' - 2 a Phi_q q' - a^2 Phi        (Baumgarte, a = BAUMGARTE / s)

A held (sticking) point keeps both rows, the first held point carrying the tangential one (on
a flat foot the forefoot's tangential row is implied by the heel's, as at the impact). A
sliding point in direction s keeps its normal row, and kinetic friction f_t = -mu s f_n
turns that row's force direction into n - mu s t (F's row). Contact rows of lambda are the
ground's force on the foot point (N, tangential, normal).

The contact law (contact.LAWS) decides what the foot points do:
- no-slip: held from the impact on (the ground's friction is only checked: `slip_at`);
- frictionless: every point slides with mu = 0;
- coulomb: the impact's mode (contact.coulomb, one point; contact.velocity_level, two)
  decides whether the point leaves it stuck or sliding; a sliding point sticks when its
  tangential velocity reaches zero (an event), a stuck point slides when holding it would
  need |f_t| > mu f_n, in the direction -sign(f_t).

Q holds gravity and the joint torques: free hinges (none), spring-damper (tau = -k (theta -
theta_0) - c theta', theta_0 the touchdown angle: a holding law on the touchdown posture), or
locked (a constraint). Events: a foot point reaching the ground (an impact, with the new
contact set), a contact whose normal force would pull (released: a contact can only push),
a sliding point coming to rest. The landing ends when heel and forefoot are both down, or
at `t_max`.

Energy bookkeeping: T + V_gravity + V_springs + E_dissipated (dampers and sliding friction)
+ sum of T_c stays equal to its value before the first impact, to the integration
tolerance; `energy_error` is its largest drift.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from . import contact
from .compiled import Compiled
from .errors import InputError
from .model import STATE, STRIKES, Model, check_state, ground_axes

GRAVITY = 9.81  # m/s^2
BAUMGARTE = 50.0  # 1/s, critically damped constraint stabilisation
JOINT_MODELS = ("free", "spring-damper", "locked")
# Fixed-step explicit schemes: classical Runge-Kutta (4th order) and the midpoint rule (2nd)
INTEGRATORS = ("rk4", "midpoint")
MAX_SWITCHES = 50  # contact changes (releases, stick-slip) before a landing counts as chatter
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
    mode: str  # contact.MODES: how the foot leaves the impact (stick or slide)
    slip: float  # m/s, tangential velocity of the first held point after the impact


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
    slide: np.ndarray  # sliding direction at each sample: +1 forward, -1 backward, 0 held
    impacts: list[ImpactEvent]
    releases: list[tuple[float, str, float]]  # (time, point, normal force N < 0): contacts let go
    T_c_total: float  # J
    mu_c_max: float  # largest |f_t| / f_n where the ground pushes (impacts and contact phases)
    no_slip_held: bool  # the contact law's friction held: no-slip never needed more than mu
    slip_at: list[float]  # times where it did (no-slip law only: the others let the foot slide)
    law: str  # the contact law (contact.LAWS)
    energy_error: float  # J
    drift: float  # largest constraint violation, m
    ended: str  # why the simulation stopped
    warnings: list[str]

    def to_dict(self) -> dict:
        return {"impacts": [{"time": e.time, "contact": e.contact, "active": list(e.active),
                             "T_c": e.T_c, "dv_trunk": list(e.dv_trunk) if e.dv_trunk else None,
                             "impulse": list(e.impulse), "mu_c": e.mu_c, "mode": e.mode,
                             "slip": e.slip} for e in self.impacts],
                "law": self.law, "sliding_ms": self.sliding_time * 1e3,
                "T_c_total": self.T_c_total, "mu_c_max": self.mu_c_max,
                "no_slip_held": self.no_slip_held, "slip_at": self.slip_at,
                "releases": [{"time": t, "contact": p, "normal_force": f} for t, p, f in self.releases],
                "energy_error": self.energy_error, "drift": self.drift, "ended": self.ended,
                "warnings": self.warnings,
                "duration": float(self.t[-1])}

    @property
    def sliding_time(self) -> float:
        """Time (s) during which a held foot point slid on the ground."""
        if len(self.t) < 2:
            return 0.0
        return float(np.sum(np.diff(self.t)[self.slide[:-1] != 0]))


class LandingModel:
    """The landing equations of one model, joint model and ground, compiled per contact set."""

    def __init__(self, model: Model, joints: Joints = Joints(), slope: float = 0.0,
                 compiled: bool = True, integrator: str = "rk4", law: str = "no-slip"):
        if not {"heel", "forefoot"} <= set(model.index):
            raise InputError(f"model {model.kind!r} has no foot to land on (it is impact-only)")
        if integrator not in INTEGRATORS:
            raise InputError(f"integrator {integrator!r}: expected one of {', '.join(INTEGRATORS)}")
        if law not in contact.LAWS:
            raise InputError(f"contact law {law!r}: expected one of {', '.join(contact.LAWS)}")
        self.model, self.joints, self.slope, self.integrator = model, joints, slope, integrator
        self.law = law
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

    def _constraints(self, q, active, s_anchor, rest, sliding=False):
        """Body, locked-joint and contact constraints (SX); a sliding foot has no tangential row."""
        rows = [self.model.constraints(q)]
        if self.joints.model == "locked":
            for k, (name, p, c) in enumerate(self.hinges):
                if name in self.joints.locked:
                    rows.append(self._angle(q, p, c) - rest[k])
        for k, point in enumerate(active):
            r = q[self.model.cols(point)]
            if k == 0 and not sliding:
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

    def rhs(self, active: tuple[str, ...], sliding: bool = False) -> ca.Function:
        """(q, q', s_anchor, rest, friction) -> (q', q'', dissipated power, contact force
        [t, n] total, normal force per held point, tangential velocity of the first held
        point, constraint residual, mechanical energy), symbolic. `friction` is mu s of a
        sliding foot (unused when it is held)."""
        key = ("rhs", sliding) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(self.hinges))
            mu_s = ca.SX.sym("friction")
            phi = self._constraints(q, active, s_anchor, rest, sliding)
            Phi = ca.jacobian(phi, q)
            tangents = [self._row(p, self.t_axis) for p in active]
            F = Phi
            if sliding and active:  # kinetic friction -mu s f_n on each sliding point
                F = ca.vertcat(Phi[:-len(active), :],
                               Phi[-len(active):, :] - mu_s * ca.vertcat(*tangents))
            M_inv = ca.DM(m.M_inv)
            Q_joint, power = self._torques(q, qd, rest)
            Q = ca.DM(self.gravity) + Q_joint
            phid = Phi @ qd
            gamma = -ca.jtimes(phid, q, qd) - 2 * BAUMGARTE * phid - BAUMGARTE**2 * phi
            lam = ca.solve(Phi @ M_inv @ F.T, gamma - Phi @ (M_inv @ Q))
            qdd = M_inv @ (Q + F.T @ lam)
            slip = tangents[0] @ qd if active else ca.SX(0)
            if not active:
                normal, force = ca.SX.zeros(1), ca.SX.zeros(2)
            elif sliding:
                normal = lam[-len(active):]
                force = ca.vertcat(-mu_s * ca.sum1(normal), ca.sum1(normal))
                power += sum(mu_s * normal[k] * (tangents[k] @ qd) for k in range(len(active)))
            else:
                contact_rows = lam[-(len(active) + 1):]
                normal = contact_rows[1:]
                force = ca.vertcat(contact_rows[0], ca.sum1(normal))
            energy = m.kinetic_energy(qd) + GRAVITY * ca.dot(ca.DM(m.momentum_matrix[1]), q) \
                + self._spring_energy(q, rest)
            self._functions[key] = ca.Function(
                "rhs", [q, qd, s_anchor, rest, mu_s],
                [qd, qdd, power, force, normal, slip, ca.norm_inf(phi), energy],
                ["q", "qd", "s_anchor", "rest", "friction"],
                ["qd_out", "qdd", "power", "force", "normal", "slip", "residual", "energy"])
        return self._functions[key]

    def _row(self, point, axis) -> ca.DM:
        """(1 x n) row taking q (or q') to `point`'s component along `axis`."""
        return ca.DM(self.model.scatter(np.asarray(axis)[None, :], [point]))

    def advance(self, active, x, h, s_anchor, rest, sliding=False, mu_s=0.0):
        """One step of [q, q', E_dissipated] by the model's integrator (rk4 or midpoint),
        symbolic or numeric."""
        n, rhs = self.model.n, self.rhs(active, sliding)

        def f(state):
            out = rhs(state[:n], state[n:2 * n], s_anchor, rest, mu_s)
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
        """(q, q'-, rest, mu) -> (q'+, T_c, total impulse [t, n], mode, slip) of an impact
        with contact set `active` under the model's law, in the contact space of rows
        [t of the first point, n of each] (contact.py): no-slip, frictionless, or Coulomb
        (Darboux-Keller for one point, the velocity-level law for two). Locked joints stop
        first (q' projected on the body's admissible motion, W M q'); T_c = T- - T+ counts
        both. mode: contact.MODES; slip: the first point's tangential velocity after it (m/s)."""
        key = ("impact",) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            rest, mu = ca.SX.sym("rest", len(self.hinges)), ca.SX.sym("mu")
            Phi_b = ca.jacobian(self._constraints(q, (), 0, rest), q)
            W = contact.admissible_inverse_inertia(ca.DM(m.M_inv), Phi_b)
            qd_b = W @ (ca.DM(m.M) @ qd)  # locked joints stop first (a no-op when none are)
            C = ca.vertcat(self._row(active[0], self.t_axis),
                           *[self._row(p, self.n_axis) for p in active])
            W_c, v0 = C @ W @ C.T, C @ qd_b
            if self.law == "no-slip":
                p, mode = contact.no_slip(W_c, v0), contact.STICK
            elif self.law == "frictionless":
                p, mode = contact.frictionless(W_c, v0), contact.SLIDE
            elif len(active) == 1:
                p, mode, _ = contact.coulomb(W_c, v0, mu)
            else:
                p, mode, _ = contact.velocity_level(W_c, v0, mu)
            qd_plus = qd_b + W @ C.T @ p
            self._functions[key] = ca.Function(
                "impact_map", [q, qd, rest, mu],
                [qd_plus, m.kinetic_energy(qd) - m.kinetic_energy(qd_plus),
                 ca.vertcat(p[0], ca.sum1(p[1:])), mode,
                 (C @ qd_plus)[0]],
                ["q", "qd", "rest", "mu"], ["qd_plus", "T_c", "impulse", "mode", "slip"])
        return self._functions[key]

    def functions(self, active: tuple[str, ...], sliding: bool = False):
        """(step, forces), compiled, for a contact set held or sliding: one integrator step
        with the event values after it (heel and forefoot heights, m; the first held point's
        tangential velocity, m/s), and the forces, residual and energy at a state."""
        key = ("numeric", sliding) + tuple(active)
        if key in self._functions:
            return self._functions[key]
        m = self.model
        x, h = ca.SX.sym("x", 2 * m.n + 1), ca.SX.sym("h")
        s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(self.hinges))
        mu_s = ca.SX.sym("friction")
        x_next = self.advance(active, x, h, s_anchor, rest, sliding, mu_s)
        q_next, qd_next = x_next[:m.n], x_next[m.n:2 * m.n]
        slip = self._row(active[0], self.t_axis) @ qd_next if active else ca.SX(0)
        step = ca.Function("step", [x, h, s_anchor, rest, mu_s],
                           [x_next, ca.vertcat(self.heights(q_next), slip)],
                           ["x", "h", "s_anchor", "rest", "friction"], ["x_next", "events"])
        q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
        out = self.rhs(active, sliding)(q=q, qd=qd, s_anchor=s_anchor, rest=rest, friction=mu_s)
        forces = ca.Function("forces", [q, qd, s_anchor, rest, mu_s],
                             [out["force"], out["normal"], out["residual"], out["energy"],
                              self.heights(q)],
                             ["q", "qd", "s_anchor", "rest", "friction"],
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
             t_max: float = 0.2) -> Landing:
    """Follow the landing from the touchdown (q0, qd0 just before the first impact), under
    the model's contact law with the ground's friction coefficient `friction`."""
    m = lm.model
    q, qd = np.asarray(q0, float), np.asarray(qd0, float)
    rest = lm.joint_angles(q)
    start = lm.functions(())[1](q, qd, 0.0, rest, 0.0)
    E0 = float(start["energy"][0])
    for k, p in enumerate(("heel", "forefoot")):
        if p not in STRIKES[strike] and start["heights"][k] < -1e-9:
            raise InputError(f"{strike} strike: the {p} is {-start['heights'][k] * 1e3:.1f} mm below "
                             "the ground at touchdown")
    mu = 0.0 if lm.law == "frictionless" else friction
    active, slide = (), 0  # contact set; sliding direction of the held foot (0: held)
    impacts, releases, slip_at, warnings = [], [], [], []
    absorbed, dissipated, t = 0.0, 0.0, 0.0
    record = {"t": [], "q": [], "qd": [], "T": [], "energy": [], "force": [], "active": [],
              "slide": []}
    drift, mu_max, switches = 0.0, 0.0, 0
    s_anchor = 0.0

    def anchor(q):
        return float(q[m.cols(active[0])] @ lm.t_axis)

    def strike_now(q, qd, points, time):
        nonlocal active, absorbed, s_anchor, mu_max, slide
        new = tuple(active) + tuple(p for p in points if p not in active)
        out = lm.impact_map(new)(q, qd, rest, friction)
        qd_plus, T_c, total = (np.asarray(v, float).ravel() for v in out[:3])
        mode, slip = int(out[3]), float(out[4])
        T_c = float(T_c[0])
        dv = (m.com_matrix(m.trunk) @ (qd_plus - qd)) if m.trunk else None
        mu_c = abs(total[0]) / total[1] if total[1] > 0 else None  # undefined when not pushed
        if lm.law == "no-slip" and (mu_c is None or mu_c > friction):
            slip_at.append(time)
        if mu_c is not None:
            mu_max = max(mu_max, mu_c)
        impacts.append(ImpactEvent(time, "+".join(points), new, T_c,
                                   tuple(map(float, dv)) if dv is not None else None,
                                   (float(total[0]), float(total[1])), mu_c,
                                   contact.MODES[mode], slip))
        absorbed += T_c
        active = new
        slide = 0 if mode == contact.STICK else (1 if slip >= 0 else -1)
        s_anchor = anchor(q)
        return qd_plus

    def sample(q, qd, force, mechanical):
        record["t"].append(t)
        record["q"].append(q.copy())
        record["qd"].append(qd.copy())
        record["T"].append(0.5 * qd @ m.M @ qd)
        record["energy"].append(mechanical + dissipated + absorbed)
        record["force"].append(force)
        record["active"].append(active)
        record["slide"].append(slide)

    sample(q, qd, np.full(2, np.nan), E0)  # just before the first impact
    qd = strike_now(q, qd, list(STRIKES[strike]), 0.0)
    # a foot point can strike only after it has been above the ground since its last contact
    armed = {p: p not in active for p in ("heel", "forefoot")}
    ended = "duration reached"
    while True:
        step, forces = lm.functions(active, slide != 0)
        out = forces(q, qd, s_anchor, rest, mu * slide)
        force, normals = out["force"], out["normal"]
        drift = max(drift, float(out["residual"][0]))
        for k, p in enumerate(("heel", "forefoot")):
            armed[p] = armed[p] or (p not in active and out["heights"][k] > 1e-9)
        # a point at or below the ground moving into it strikes, armed or not (one released
        # where it stood, and never lifted, would otherwise pass through the floor)
        sinking = [p for k, p in enumerate(("heel", "forefoot")) if p not in active
                   and out["heights"][k] <= 1e-9 and qd[m.cols(p)] @ lm.n_axis < 0]
        if sinking and switches <= MAX_SWITCHES:
            switches += 1
            for p in sinking:
                armed[p] = False
            qd = strike_now(q, qd, sinking, t)
            continue
        pulling = active and np.any(normals < -1e-9 * max(1.0, float(np.max(np.abs(normals)))))
        if set(active) == {"heel", "forefoot"}:
            sample(q, qd, force, float(out["energy"][0]))
            ended = "heel and forefoot both down"
            if pulling:
                warnings.append("with both points down the ground would pull "
                                f"{' and '.join(p for p, n in zip(active, normals) if n < 0)}: "
                                "it would lift again")
            break
        if pulling or (lm.law == "coulomb" and active and not slide
                       and abs(force[0]) > friction * force[1]):
            switches += 1
            if switches > MAX_SWITCHES:
                ended = f"contact chatter: more than {MAX_SWITCHES} contact changes" + (
                    " (held, the ground would pull the point; let go, it sinks: the no-slip "
                    "law has no motion here, \"coulomb\" may)" if lm.law == "no-slip" else "")
                warnings.append(ended)
                break
            if pulling:
                pulled = [p for p, n in zip(active, normals) if n < 0]
                releases.append((t, "+".join(pulled), float(min(normals))))
                active = tuple(p for p in active if p not in pulled)
                slide = slide if active else 0
            else:  # holding the point needs more friction than the ground has: it slides
                slide = -1 if force[0] > 0 else 1
            if active:  # the first held point carries the tangential row
                s_anchor = anchor(q)
            continue
        if active and force[1] > 0:
            mu_c = abs(force[0]) / force[1]
            mu_max = max(mu_max, mu_c)
            if lm.law == "no-slip" and mu_c > friction:
                slip_at.append(t)
        sample(q, qd, force if active else np.full(2, np.nan), float(out["energy"][0]))
        if t >= t_max - 1e-12:
            break
        x = np.concatenate([q, qd, [dissipated]])
        args = (s_anchor, rest, mu * slide)
        h = min(dt, t_max - t)
        events = step(x, h, *args)["events"]
        hits = [k for k, p in enumerate(("heel", "forefoot"))
                if p not in active and armed[p] and events[k] <= 0.0]
        stops = lm.law == "coulomb" and slide != 0 and slide * events[2] <= 0.0
        if hits or stops:  # the earliest event ends the step
            candidates = [(_event_step(step, x, h, args, lambda e, hits=hits: min(e[k] for k in hits)), "hit")
                          ] if hits else []
            if stops:
                candidates.append((_event_step(step, x, h, args, lambda e, s=slide: s * e[2]), "stop"))
            h, what = min(candidates)
        x_next = step(x, h, *args)["x_next"]
        t += h
        q, qd, dissipated = x_next[:m.n], x_next[m.n:2 * m.n], float(x_next[-1])
        if hits and what == "hit":
            out = forces(q, qd, s_anchor, rest, mu * slide)
            sample(q, qd, np.full(2, np.nan), float(out["energy"][0]))
            points = [("heel", "forefoot")[k] for k in hits]
            for p in points:
                armed[p] = False
            qd = strike_now(q, qd, points, t)
        elif stops:  # the sliding point comes to rest: it sticks where it is
            slide, s_anchor = 0, anchor(q)
    energy = np.array(record["energy"])
    return Landing(t=np.array(record["t"]), q=np.array(record["q"]), qd=np.array(record["qd"]),
                   T=np.array(record["T"]), energy=energy, force=np.array(record["force"]),
                   active=record["active"], slide=np.array(record["slide"]), impacts=impacts,
                   releases=releases, T_c_total=absorbed, mu_c_max=mu_max,
                   no_slip_held=not slip_at, slip_at=slip_at, law=lm.law,
                   energy_error=float(np.max(np.abs(energy - E0))), drift=drift, ended=ended,
                   warnings=warnings)


def _event_step(step, x, h, args, value, tol=1e-13):
    """The step length in (0, h] at which value(events after the step) reaches zero from
    above (secant + bisection)."""
    def g(s):
        return value(step(x, s, *args)["events"])

    lo, hi = 0.0, h
    g_lo, g_hi = g(0.0), g(h)
    for _ in range(60):
        s = hi - g_hi * (hi - lo) / (g_hi - g_lo) if g_hi != g_lo else 0.5 * (lo + hi)
        if not lo < s < hi:
            s = 0.5 * (lo + hi)
        v = g(s)
        if abs(v) < tol or hi - lo < 1e-15:
            return s
        if v > 0:
            lo, g_lo = s, v
        else:
            hi, g_hi = s, v
    return hi


def landing_function(lm: LandingModel, strike: str, steps: int = 60) -> ca.Function:
    """The two-impact landing as a CasADi Function (differentiable).

    (x, t_e) -> T_c_total, T_c (both impacts), residual, force_t, force_n: x the touchdown state
    (model.STATE), t_e the time (s) of the second impact. The strike point is held from the
    first impact; `steps` RK4 steps of t_e / steps integrate to t_e, where `residual` is the
    other point's height (zero at the event) and `approach` its normal velocity then (m/s,
    negative when it strikes); force_t, force_n are the contact force (N) and
    height the other point's height (m) after each step. `absorbed_function` solves
    residual = 0 for t_e. The strike point is held throughout: the no-slip law only.
    """
    if strike not in ("heel", "forefoot"):
        raise InputError("the two-impact landing starts with a heel or forefoot strike")
    if lm.law != "no-slip":
        raise InputError(f"the differentiable landing holds the strike point (no-slip), not "
                         f"{lm.law!r}: a sliding contact phase has events an NLP cannot follow")
    m = lm.model
    point, other = strike, "heel" if strike == "forefoot" else "forefoot"
    xs = ca.SX.sym("x", len(STATE))
    q0, qd0 = m.state(xs, point)
    touchdown = ca.Function("touchdown", [xs], [q0, qd0, lm._angles(q0),
                                                ca.dot(q0[m.cols(point)], ca.DM(lm.t_axis))])
    n = 2 * m.n + 1
    xk, h = ca.SX.sym("xk", n), ca.SX.sym("h")
    s_anchor, rest = ca.SX.sym("s_anchor"), ca.SX.sym("rest", len(lm.hinges))
    x_next = lm.advance((point,), xk, h, s_anchor, rest)
    forces = lm.rhs((point,))(x_next[:m.n], x_next[m.n:2 * m.n], s_anchor, rest, 0)[3]
    height = ca.dot(x_next[m.cols(other)], ca.DM(lm.n_axis))
    step = ca.Function("step", [xk, ca.vertcat(h, s_anchor, rest)],
                       [x_next, ca.vertcat(forces, height)])
    run = step.mapaccum("run", steps, [0], [0])

    x = ca.MX.sym("x", len(STATE))
    t_e = ca.MX.sym("t_e")
    q, qd, rest_mx, s_mx = touchdown(x)
    qd1, T_c1 = lm.impact_map((point,))(q, qd, rest_mx, 0)[:2]
    params = ca.repmat(ca.vertcat(t_e / steps, s_mx, rest_mx), 1, steps)
    states, f = run(ca.vertcat(q, qd1, 0), params)
    end = states[:, -1]
    q_e, qd_e = end[:m.n], end[m.n:2 * m.n]
    residual = ca.dot(q_e[m.cols(other)], ca.DM(lm.n_axis))
    T_c2 = lm.impact_map((point, other))(q_e, qd_e, rest_mx, 0)[1]
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


def simulate_state(lm: LandingModel, strike: str, x, friction: float, dt: float,
                   duration: float) -> Landing:
    """Simulate the landing from a touchdown state x (model.STATE, SI)."""
    q, qd = lm.model.state_numeric(check_state(x), STRIKES[strike][0])
    return simulate(lm, strike, q, qd, friction, dt, duration)


def history_rows(landing: Landing, model: Model):
    """Time histories as CSV rows: time, energies, contact forces, mu_c, active set, sliding
    direction (+1 forward, -1 backward, 0 held), q."""
    names = [f"{p.name}_{axis}" for p in model.points for axis in ("x", "z")]
    yield ["t_s", "T_J", "energy_J", "f_t_N", "f_n_N", "mu_c", "active", "slide", *names]
    for k, t in enumerate(landing.t):
        f_t, f_n = landing.force[k]
        mu = abs(f_t) / f_n if f_n > 0 else float("nan")
        yield [t, landing.T[k], landing.energy[k], f_t, f_n, mu, "+".join(landing.active[k]),
               int(landing.slide[k]), *landing.q[k]]
