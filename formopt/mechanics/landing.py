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

Q holds gravity and the joint moments (`Joints`): free hinges (none); spring-damper
(M = M_0 + k (phi - phi_0) + c phi', phi the flexion angle, phi_0 its touchdown value, M_0 the
moment already held at touchdown); torque (M(t) from a table); or locked (a constraint).
Joint moments are the muscles' internal moments, extensor (hip, knee) and plantarflexor
(ankle) positive, the sign of RBDS's processed knee and ankle moments. Events: a foot point
reaching the ground (an impact, with the new
contact set), a contact whose normal force would pull (released: a contact can only push),
a sliding point coming to rest. The landing ends when heel and forefoot are both down, or
at `t_max`.

Energy bookkeeping: T + V_gravity + V_springs + E_joints (the work the dampers and the
moments take from the body) + E_friction + sum of T_c stays equal to its value before the
first impact, to the integration tolerance; `energy_error` is its largest drift. A landing
whose balance drifts by more than DIVERGED of its touchdown kinetic energy, or whose state
stops being finite, raises `Diverged`: it is not a result.

Integrators (`INTEGRATORS`): "adaptive" (Dormand & Prince 1980, 5th order with an embedded
4th-order error estimate; the step shrinks where the joints are stiff, so stiff dampers stay
stable, and grows up to dt between events), or the fixed-step "rk4" and "midpoint".
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
JOINT_MODELS = ("free", "spring-damper", "locked", "torque")
# Error-controlled Dormand-Prince 5(4), or fixed steps: classical Runge-Kutta (4th order) and
# the midpoint rule (2nd)
INTEGRATORS = ("adaptive", "rk4", "midpoint")
TOLERANCE = 1e-8  # adaptive: largest local error per step, absolute and relative (m, m/s, J)
DIVERGED = 1e-4  # energy-balance drift, relative to the touchdown kinetic energy, that is a divergence
SINK = 1e-7  # m: how far below the ground a point let go where it stood strikes again
MIN_STEP = 1e-9  # s: an adaptive step shorter than this is a divergence
MAX_SWITCHES = 50  # contact changes (releases, stick-slip) before a landing counts as chatter
# Joints: (name, parent segment, child segment); the hip only where the trunk is a rigid body.
JOINTS = (("hip", "trunk", "thigh"), ("knee", "thigh", "shank"), ("ankle", "shank", "foot"),
          ("swing_hip", "trunk", "swing_thigh"), ("swing_knee", "swing_thigh", "swing_shank"),
          ("swing_ankle", "swing_shank", "swing_foot"))
# Joints that carry a runner, per kg of body mass: RBDS001 (Fukuchi et al. 2017) at 3.5 m/s,
# measured by problems/joint_stiffness.py from the data set's own inverse dynamics. Stiffness:
# the slope of moment against angle from touchdown to peak knee flexion (r > 0.99); preload: the
# moment at touchdown (the knee's is a flexor moment, the hamstrings still braking the swing).
# Damping cannot be identified from those curves (the fit gives c < 0); 6.8e-4 N m s/(kg deg)
# (0.05 N m s/deg for the paper's 73 kg, about a tenth of the knee's critical damping) is the
# smallest round value with which no shipped landing's contact pulls. The hip has none: in
# early stance it extends under an extensor moment, no spring.
RUNNING_JOINTS = {"stiffness": {"knee": 0.13, "ankle": 0.083},  # N m / (kg deg)
                  "damping": {"knee": 6.8e-4, "ankle": 6.8e-4},  # N m s / (kg deg)
                  "preload": {"knee": -0.52, "ankle": 0.086}}  # N m / kg, extensor positive
# What a scene may set, per kg: stiffness 1 N m/(kg deg), three times the knee of sprinters
# (17-24 N m/deg, Kuitunen, Komi & Kyrolainen 2002); damping 0.02 N m s/(kg deg), the
# critical damping of the paper's shank and foot about the knee at that stiffness (beyond it
# the joint is locked over a landing: use model "locked"); preload 5 N m/kg, above any stance
# moment of running (RBDS001 peaks at 2.8 knee, 2.5 ankle at 3.5 m/s).
JOINT_LIMITS = {"stiffness": 1.0, "damping": 0.02, "preload": 5.0}
# d(flexion)/d(hinge angle): hip and knee flex clockwise (x forward, z up), the ankle
# dorsiflexes counter-clockwise (tests/mechanics/test_joint_moments.py checks it on the model).
FLEXION = {"hip": -1.0, "knee": -1.0, "ankle": 1.0, "swing_hip": -1.0, "swing_knee": -1.0,
           "swing_ankle": 1.0}
# Dormand & Prince (1980) 5(4): nodes, stage coefficients, 5th- and 4th-order weights
DP_C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
DP_A = ((), (1 / 5,), (3 / 40, 9 / 40), (44 / 45, -56 / 15, 32 / 9),
        (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
        (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
        (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84))
DP_B5 = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0)
DP_B4 = (5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40)


class Diverged(RuntimeError):
    """The landing's integration broke its energy balance or left the finite numbers: the
    message says when, by how much, and what to change."""


@dataclass(frozen=True)
class Joints:
    """The joint model of a landing: free hinges, springs and dampers, moments over time, or
    locked. Moments are extensor (hip, knee) / plantarflexor (ankle) positive; stiffness and
    damping resist flexion (hip, knee) and dorsiflexion (ankle)."""

    model: str = "free"
    stiffness: dict[str, float] = field(default_factory=dict)  # N m / rad per joint
    damping: dict[str, float] = field(default_factory=dict)  # N m s / rad per joint
    locked: tuple[str, ...] = ()  # with model "locked": the joints held at their touchdown angle
    preload: dict[str, float] = field(default_factory=dict)  # N m held at touchdown (spring-damper)
    times: tuple[float, ...] = ()  # s after touchdown, increasing (torque)
    moments: dict[str, tuple[float, ...]] = field(default_factory=dict)  # N m at `times` (torque)


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
    T: np.ndarray  # J, kinetic energy
    V: np.ndarray  # J, gravitational potential energy relative to the touchdown
    spring: np.ndarray  # J, elastic energy of the joint springs (zero at touchdown)
    dissipated: np.ndarray  # J, work taken by the joints (dampers, moments) and sliding friction
    absorbed: np.ndarray  # J, T_c of the impacts so far
    energy: np.ndarray  # J, T + V + spring + dissipated + absorbed: constant up to drift
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
                "valid": self.valid, "violations": self.violations,
                "releases": [{"time": t, "contact": p, "normal_force": f} for t, p, f in self.releases],
                "energy_error": self.energy_error, "drift": self.drift, "ended": self.ended,
                "warnings": self.warnings,
                "duration": float(self.t[-1])}

    @property
    def violations(self) -> list[str]:
        """How the landing breaks its own assumptions (empty: valid): no-slip needing more
        friction than the ground has, a contact the ground would have pulled, a second point
        that never comes down within the duration."""
        found = []
        if not self.no_slip_held:
            found.append(f"no-slip needs friction {self.mu_c_max:.2f}")
        if self.releases:
            found.append(f"the ground would pull {len(self.releases)} time(s)")
        if not self.ended.startswith("heel and forefoot both down"):
            found.append(self.ended.split(":")[0])
        return found

    @property
    def valid(self) -> bool:
        return not self.violations

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

    def _constraints(self, q, active, s_anchor, joint, sliding=False):
        """Body, locked-joint and contact constraints (SX); a sliding foot has no tangential row."""
        rows = [self.model.constraints(q)]
        if self.joints.model == "locked":
            for k, (name, p, c) in enumerate(self.hinges):
                if name in self.joints.locked:
                    rows.append(self._angle(q, p, c) - joint[k])
        for k, point in enumerate(active):
            r = q[self.model.cols(point)]
            if k == 0 and not sliding:
                rows.append(ca.dot(r, ca.DM(self.t_axis)) - s_anchor)
            rows.append(ca.dot(r, ca.DM(self.n_axis)))
        return ca.vertcat(*rows)

    def joint_parameters(self, q) -> np.ndarray:
        """The joint vector every landing function takes, numeric: [theta_0 (rad, the hinge
        angles at q, the touchdown), k (N m/rad), c (N m s/rad), tau_0 (N m, the preload as a
        hinge torque)] per hinge. Parameters, not constants, so one compiled function serves
        every joint setting."""
        return np.concatenate([self.joint_angles(q) if self.hinges else [], self.spring_parameters()])

    def spring_parameters(self) -> np.ndarray:
        """[k, c, tau_0] per hinge (zero unless the joints are springs and dampers)."""
        j, names = self.joints, [name for name, _, _ in self.hinges]
        if j.model != "spring-damper":
            return np.zeros(3 * len(names))
        return np.array([j.stiffness.get(n, 0.0) for n in names]
                        + [j.damping.get(n, 0.0) for n in names]
                        + [-FLEXION[n] * j.preload.get(n, 0.0) for n in names])

    def _torques(self, q, qd, joint, t):
        """Generalised joint forces J^T tau and the power the joints take from the body (W).

        tau = tau_0 - k (theta - theta_0) - c theta' (spring-damper; its conservative part is
        in `_spring_energy`, the power counts the damper, c theta'^2) or tau = -s M(t)
        (torque, s = FLEXION; power -tau theta')."""
        Q, power = ca.SX.zeros(self.model.n), 0
        if self.joints.model not in ("spring-damper", "torque"):
            return Q, power
        theta_0, stiff, damp, tau_0 = ca.vertsplit(joint, len(self.hinges))
        theta = self._angles(q)
        rate = ca.jtimes(theta, q, qd)
        J = ca.jacobian(theta, q)
        for k, (name, _, _) in enumerate(self.hinges):
            if self.joints.model == "spring-damper":
                tau = tau_0[k] - stiff[k] * (theta[k] - theta_0[k]) - damp[k] * rate[k]
                power += damp[k] * rate[k] ** 2
            elif name in self.joints.moments:
                tau = -FLEXION[name] * ca.pw_lin(t, ca.DM(self.joints.times),
                                                 ca.DM(self.joints.moments[name]))
                power -= tau * rate[k]
            else:
                continue
            Q += J[k, :].T * tau
        return Q, power

    def _spring_energy(self, q, joint):
        """Elastic energy of the joint springs with their preload (J, SX): V = k/2 (theta -
        theta_0)^2 - tau_0 (theta - theta_0), zero at touchdown, -dV/dtheta the spring's torque."""
        if self.joints.model != "spring-damper":
            return 0
        theta_0, stiff, _, tau_0 = ca.vertsplit(joint, len(self.hinges))
        theta = self._angles(q)
        return ca.sum1(0.5 * stiff * (theta - theta_0) ** 2 - tau_0 * (theta - theta_0))

    def rhs(self, active: tuple[str, ...], sliding: bool = False) -> ca.Function:
        """(q, q', s_anchor, joint, friction, t) -> (q', q'', power taken by the joints and
        friction, contact force [t, n] total, normal force per held point, tangential
        velocity of the first held point, constraint residual, mechanical energy), symbolic.
        `friction` is mu s of a sliding foot (unused when it is held); t (s after touchdown)
        drives the torque joints' moments."""
        key = ("rhs", sliding) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            s_anchor, joint = ca.SX.sym("s_anchor"), ca.SX.sym("joint", 4 * len(self.hinges))
            mu_s, t = ca.SX.sym("friction"), ca.SX.sym("t")
            phi = self._constraints(q, active, s_anchor, joint, sliding)
            Phi = ca.jacobian(phi, q)
            tangents = [self._row(p, self.t_axis) for p in active]
            F = Phi
            if sliding and active:  # kinetic friction -mu s f_n on each sliding point
                F = ca.vertcat(Phi[:-len(active), :],
                               Phi[-len(active):, :] - mu_s * ca.vertcat(*tangents))
            M_inv = ca.DM(m.M_inv)
            Q_joint, power = self._torques(q, qd, joint, t)
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
                + self._spring_energy(q, joint)
            self._functions[key] = ca.Function(
                "rhs", [q, qd, s_anchor, joint, mu_s, t],
                [qd, qdd, power, force, normal, slip, ca.norm_inf(phi), energy],
                ["q", "qd", "s_anchor", "joint", "friction", "t"],
                ["qd_out", "qdd", "power", "force", "normal", "slip", "residual", "energy"])
        return self._functions[key]

    def _row(self, point, axis) -> ca.DM:
        """(1 x n) row taking q (or q') to `point`'s component along `axis`."""
        return ca.DM(self.model.scatter(np.asarray(axis)[None, :], [point]))

    def advance(self, active, x, h, s_anchor, joint, sliding=False, mu_s=0.0, t=0.0, scheme=None):
        """One step of [q, q', E_joints] from time t by `scheme` (default: the model's
        integrator), symbolic: (x_next, error), error the adaptive scheme's local error
        estimate in units of TOLERANCE (1 is the largest accepted), zero for fixed steps."""
        n, rhs = self.model.n, self.rhs(active, sliding)
        scheme = scheme or self.integrator

        def f(state, time):
            out = rhs(state[:n], state[n:2 * n], s_anchor, joint, mu_s, time)
            return ca.vertcat(out[0], out[1], out[2])

        if scheme == "midpoint":
            return x + h * f(x + h / 2 * f(x, t), t + h / 2), 0
        if scheme == "rk4":
            k1 = f(x, t)
            k2 = f(x + h / 2 * k1, t + h / 2)
            k3 = f(x + h / 2 * k2, t + h / 2)
            k4 = f(x + h * k3, t + h)
            return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4), 0
        k = []
        for c, a in zip(DP_C, DP_A):
            k.append(f(x + h * sum((a_i * k_i for a_i, k_i in zip(a, k)), ca.SX.zeros(x.shape)),
                       t + c * h))
        x5 = x + h * sum((b * k_i for b, k_i in zip(DP_B5, k) if b), ca.SX.zeros(x.shape))
        e = h * sum((b5 - b4) * k_i for b5, b4, k_i in zip(DP_B5, DP_B4, k))
        return x5, ca.mmax(ca.fabs(e) / (TOLERANCE * (1 + ca.fabs(x))))

    def heights(self, q):
        """Height of heel and forefoot above the ground (m)."""
        return ca.vertcat(*[ca.dot(q[self.model.cols(p)], ca.DM(self.n_axis))
                            for p in ("heel", "forefoot")])

    def impact_map(self, active) -> ca.Function:
        """(q, q'-, joint, mu) -> (q'+, T_c, total impulse [t, n], mode, slip) of an impact
        with contact set `active` under the model's law, in the contact space of rows
        [t of the first point, n of each] (contact.py): no-slip, frictionless, or Coulomb
        (Darboux-Keller for one point, the velocity-level law for two). Locked joints stop
        first (q' projected on the body's admissible motion, W M q'); T_c = T- - T+ counts
        both. mode: contact.MODES; slip: the first point's tangential velocity after it (m/s)."""
        key = ("impact",) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            joint, mu = ca.SX.sym("joint", 4 * len(self.hinges)), ca.SX.sym("mu")
            Phi_b = ca.jacobian(self._constraints(q, (), 0, joint), q)
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
                "impact_map", [q, qd, joint, mu],
                [qd_plus, m.kinetic_energy(qd) - m.kinetic_energy(qd_plus),
                 ca.vertcat(p[0], ca.sum1(p[1:])), mode,
                 (C @ qd_plus)[0]],
                ["q", "qd", "joint", "mu"], ["qd_plus", "T_c", "impulse", "mode", "slip"])
        return self._functions[key]

    def functions(self, active: tuple[str, ...], sliding: bool = False):
        """(step, forces), compiled, for a contact set held or sliding: one integrator step
        from time t with its error estimate (`advance`) and the event values after it (heel
        and forefoot heights, m; the first held point's tangential velocity, m/s), and the
        forces, residual and energy at a state."""
        key = ("numeric", sliding) + tuple(active)
        if key in self._functions:
            return self._functions[key]
        m = self.model
        x, h, t = ca.SX.sym("x", 2 * m.n + 1), ca.SX.sym("h"), ca.SX.sym("t")
        s_anchor, joint = ca.SX.sym("s_anchor"), ca.SX.sym("joint", 4 * len(self.hinges))
        mu_s = ca.SX.sym("friction")
        x_next, error = self.advance(active, x, h, s_anchor, joint, sliding, mu_s, t)
        q_next, qd_next = x_next[:m.n], x_next[m.n:2 * m.n]
        slip = self._row(active[0], self.t_axis) @ qd_next if active else ca.SX(0)
        names = ["x", "h", "s_anchor", "joint", "friction", "t"]
        step = ca.Function("step", [x, h, s_anchor, joint, mu_s, t],
                           [x_next, ca.vertcat(self.heights(q_next), slip), error],
                           names, ["x_next", "events", "error"])
        q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
        out = self.rhs(active, sliding)(q=q, qd=qd, s_anchor=s_anchor, joint=joint, friction=mu_s, t=t)
        forces = ca.Function("forces", [q, qd, s_anchor, joint, mu_s, t],
                             [out["force"], out["normal"], out["residual"], out["energy"],
                              self.heights(q)],
                             ["q", "qd", "s_anchor", "joint", "friction", "t"],
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


def simulate(lm: LandingModel, strike: str, q0, qd0, friction: float, dt: float = 1e-3,
             t_max: float = 0.2) -> Landing:
    """Follow the landing from the touchdown (q0, qd0 just before the first impact), under
    the model's contact law with the ground's friction coefficient `friction`. dt (s) is the
    fixed integrators' step and the adaptive one's largest. Raises Diverged when the energy
    balance or the finite numbers break."""
    m = lm.model
    q, qd = np.asarray(q0, float), np.asarray(qd0, float)
    joint = lm.joint_parameters(q)
    if lm.joints.model == "torque" and lm.joints.times[-1] < t_max - 1e-12:
        raise InputError(f"the joint moments end at {lm.joints.times[-1] * 1e3:g} ms, before the "
                         f"landing's {t_max * 1e3:g} ms: give them up to the landing's duration")
    start = lm.functions(())[1](q, qd, 0.0, joint, 0.0, 0.0)
    E0 = float(start["energy"][0])
    T0 = 0.5 * qd @ m.M @ qd  # J, the scale of a divergence
    remedy = (f"with integrator {lm.integrator!r} at dt {dt * 1e3:g} ms: the joints are too stiff "
              "for it; use integrator \"adaptive\" or a smaller dt_ms" if lm.integrator != "adaptive"
              else "with the adaptive integrator: check the joints' values against their limits")
    for k, p in enumerate(("heel", "forefoot")):
        if p not in STRIKES[strike] and start["heights"][k] < -1e-9:
            raise InputError(f"{strike} strike: the {p} is {-start['heights'][k] * 1e3:.1f} mm below "
                             "the ground at touchdown")
    mu = 0.0 if lm.law == "frictionless" else friction
    active, slide = (), 0  # contact set; sliding direction of the held foot (0: held)
    impacts, releases, slip_at, warnings = [], [], [], []
    absorbed, dissipated, t = 0.0, 0.0, 0.0
    record = {"t": [], "q": [], "qd": [], "T": [], "V": [], "spring": [], "dissipated": [],
              "absorbed": [], "energy": [], "force": [], "active": [], "slide": []}
    height = GRAVITY * m.momentum_matrix[1]  # q -> gravitational potential energy (J)
    V0 = float(height @ q)
    drift, mu_max, switches = 0.0, 0.0, 0
    s_anchor = 0.0

    def anchor(q):
        return float(q[m.cols(active[0])] @ lm.t_axis)

    def strike_now(q, qd, points, time):
        nonlocal active, absorbed, s_anchor, mu_max, slide
        new = tuple(active) + tuple(p for p in points if p not in active)
        out = lm.impact_map(new)(q, qd, joint, friction)
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
        error = abs(mechanical + dissipated + absorbed - E0)
        if not error <= DIVERGED * T0:  # also when not finite
            raise Diverged(f"the landing diverged at {t * 1e3:.2f} ms: the energy balance is off by "
                           f"{error:.3g} J ({error / T0:.1e} of the touchdown kinetic energy) {remedy}")
        record["t"].append(t)
        record["q"].append(q.copy())
        record["qd"].append(qd.copy())
        T, V = 0.5 * qd @ m.M @ qd, float(height @ q)
        record["T"].append(T)
        record["V"].append(V - V0)
        record["spring"].append(mechanical - T - V)
        record["dissipated"].append(dissipated)
        record["absorbed"].append(absorbed)
        record["energy"].append(mechanical + dissipated + absorbed)
        record["force"].append(force)
        record["active"].append(active)
        record["slide"].append(slide)

    sample(q, qd, np.full(2, np.nan), E0)  # just before the first impact
    qd = strike_now(q, qd, list(STRIKES[strike]), 0.0)
    # a foot point can strike only after it has been above the ground since its last contact
    armed = {p: p not in active for p in ("heel", "forefoot")}
    ended = "duration reached"
    h_next = dt
    while True:
        step, forces = lm.functions(active, slide != 0)
        out = forces(q, qd, s_anchor, joint, mu * slide, t)
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
        args = (s_anchor, joint, mu * slide, t)
        h = min(h_next, dt, t_max - t)
        taken = step(x, h, *args)
        while not taken["error"][0] <= 1.0:  # adaptive: shrink until the local error is accepted
            if h < MIN_STEP:
                raise Diverged(f"the landing diverged at {t * 1e3:.2f} ms: the adaptive step fell "
                               f"below {MIN_STEP * 1e9:g} ns (the joints are too stiff or the state "
                               "left the finite numbers)")
            error = taken["error"][0]
            h *= max(0.1, 0.9 * error ** -0.2) if np.isfinite(error) else 0.1
            taken = step(x, h, *args)
        if lm.integrator == "adaptive":  # the next step's length from this one's error
            h_next = h * min(5.0, 0.9 * max(taken["error"][0], 1e-12) ** -0.2)
        events = taken["events"]
        # an armed point strikes at the ground; one that never rose since it was let go, a
        # hair below it (SINK), so that the event has a root and the point cannot sink further
        sink = [0.0 if armed[p] else SINK for p in ("heel", "forefoot")]
        hits = [k for k, p in enumerate(("heel", "forefoot"))
                if p not in active and events[k] + sink[k] <= 0.0]
        stops = lm.law == "coulomb" and slide != 0 and slide * events[2] <= 0.0
        if hits or stops:  # the earliest event ends the step
            candidates = []
            if hits:
                first_hit = _event_step(step, x, h, args, lambda e: min(e[k] + sink[k] for k in hits))
                candidates.append((first_hit, "hit"))
            if stops:
                candidates.append((_event_step(step, x, h, args, lambda e, s=slide: s * e[2]), "stop"))
            h, what = min(candidates)
        x_next = step(x, h, *args)["x_next"]
        if not np.all(np.isfinite(x_next)):
            raise Diverged(f"the landing diverged at {t * 1e3:.2f} ms: the state is no longer finite "
                           f"{remedy}")
        t += h
        q, qd, dissipated = x_next[:m.n], x_next[m.n:2 * m.n], float(x_next[-1])
        if hits and what == "hit":
            out = forces(q, qd, s_anchor, joint, mu * slide, t)
            sample(q, qd, np.full(2, np.nan), float(out["energy"][0]))
            points = [("heel", "forefoot")[k] for k in hits]
            for p in points:
                armed[p] = False
            qd = strike_now(q, qd, points, t)
        elif stops:  # the sliding point comes to rest: it sticks where it is
            slide, s_anchor = 0, anchor(q)
    energy = np.array(record["energy"])
    return Landing(t=np.array(record["t"]), q=np.array(record["q"]), qd=np.array(record["qd"]),
                   T=np.array(record["T"]), V=np.array(record["V"]), spring=np.array(record["spring"]),
                   dissipated=np.array(record["dissipated"]), absorbed=np.array(record["absorbed"]),
                   energy=energy, force=np.array(record["force"]),
                   active=record["active"], slide=np.array(record["slide"]), impacts=impacts,
                   releases=releases, T_c_total=absorbed, mu_c_max=mu_max,
                   no_slip_held=not slip_at, slip_at=slip_at, law=lm.law,
                   energy_error=float(np.max(np.abs(energy - E0))), drift=drift, ended=ended,
                   warnings=warnings)


def _event_step(step, x, h, args, value, tol=1e-13):
    """The step length in (0, h] at which value(events after the step) reaches zero from
    above: regula falsi with the Illinois rule (the end kept twice has its value halved, so
    neither end stalls), bisection where the secant leaves the bracket."""
    def g(s):
        return value(step(x, s, *args)["events"])

    lo, hi = 0.0, h
    g_lo, g_hi = g(0.0), g(h)
    kept = 0  # +1: lo kept last time, -1: hi kept
    for _ in range(100):
        s = hi - g_hi * (hi - lo) / (g_hi - g_lo) if g_hi != g_lo else 0.5 * (lo + hi)
        if not lo < s < hi:
            s = 0.5 * (lo + hi)
        v = g(s)
        if abs(v) < tol or hi - lo < 1e-15:
            return s
        if v > 0:
            lo, g_lo = s, v
            if kept == -1:
                g_hi *= 0.5
            kept = -1
        else:
            hi, g_hi = s, v
            if kept == 1:
                g_lo *= 0.5
            kept = 1
    return hi


def landing_function(lm: LandingModel, strike: str, steps: int = 60) -> ca.Function:
    """The two-impact landing as a CasADi Function (differentiable).

    (x, t_e) -> T_c_total, T_c (both impacts), residual, force_t, force_n: x the touchdown state
    (model.STATE), t_e the time (s) of the second impact. The strike point is held from the
    first impact; `steps` fixed steps of t_e / steps (the model's fixed-step integrator; RK4
    in place of the adaptive one) integrate to t_e, where `residual` is the
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
    touchdown = ca.Function("touchdown", [xs], [q0, qd0, ca.vertcat(lm._angles(q0), lm.spring_parameters()),
                                                ca.dot(q0[m.cols(point)], ca.DM(lm.t_axis))])
    n = 2 * m.n + 1
    xk, h, t = ca.SX.sym("xk", n), ca.SX.sym("h"), ca.SX.sym("t")
    s_anchor, joint = ca.SX.sym("s_anchor"), ca.SX.sym("joint", 4 * len(lm.hinges))
    x_next = lm.advance((point,), xk, h, s_anchor, joint, t=t,
                        scheme="rk4" if lm.integrator == "adaptive" else None)[0]
    forces = lm.rhs((point,))(x_next[:m.n], x_next[m.n:2 * m.n], s_anchor, joint, 0, t + h)[3]
    height = ca.dot(x_next[m.cols(other)], ca.DM(lm.n_axis))
    step = ca.Function("step", [xk, ca.vertcat(h, t, s_anchor, joint)],
                       [x_next, ca.vertcat(forces, height)])
    run = step.mapaccum("run", steps, [0], [0])

    x = ca.MX.sym("x", len(STATE))
    t_e = ca.MX.sym("t_e")
    q, qd, joint_mx, s_mx = touchdown(x)
    qd1, T_c1 = lm.impact_map((point,))(q, qd, joint_mx, 0)[:2]
    params = ca.vertcat(ca.repmat(t_e / steps, 1, steps), ca.DM(np.arange(steps)).T * t_e / steps,
                        ca.repmat(ca.vertcat(s_mx, joint_mx), 1, steps))
    states, f = run(ca.vertcat(q, qd1, 0), params)
    end = states[:, -1]
    q_e, qd_e = end[:m.n], end[m.n:2 * m.n]
    residual = ca.dot(q_e[m.cols(other)], ca.DM(lm.n_axis))
    T_c2 = lm.impact_map((point, other))(q_e, qd_e, joint_mx, 0)[1]
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
    """Time histories as CSV rows: time, energies (kinetic, potential and spring, taken by the
    joints and friction, absorbed at impacts, their sum), contact forces, mu_c, active set,
    sliding direction (+1 forward, -1 backward, 0 held), q."""
    names = [f"{p.name}_{axis}" for p in model.points for axis in ("x", "z")]
    yield ["t_s", "T_J", "V_J", "spring_J", "dissipated_J", "absorbed_J", "energy_J", "f_t_N",
           "f_n_N", "mu_c", "active", "slide", *names]
    for k, t in enumerate(landing.t):
        f_t, f_n = landing.force[k]
        mu = abs(f_t) / f_n if f_n > 0 else float("nan")
        yield [t, landing.T[k], landing.V[k], landing.spring[k], landing.dissipated[k],
               landing.absorbed[k], landing.energy[k], f_t, f_n, mu, "+".join(landing.active[k]),
               int(landing.slide[k]), *landing.q[k]]
