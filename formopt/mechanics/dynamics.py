"""The finite motion of a natural-coordinate model: mass matrix, forces, constraints, energies.

In natural coordinates q (n,) the mass matrix M is constant and the motion between impacts is

    M q'' = Q(q, q', t) + F_q^T lambda          Phi(q) = 0

with Phi the body constraints, the locked joints and the rows of the contact set, and F = Phi
except where a point slides. With G = Phi_q M^-1 F_q^T (the impact's matrix when nothing
slides) the accelerations and multipliers are

    lambda = G^-1 (gamma - Phi_q M^-1 Q)        q'' = M^-1 (Q + F_q^T lambda)
    gamma  = -(Phi_q q')_q q' - 2 a Phi_q q' - a^2 Phi        (Baumgarte, a = BAUMGARTE)

Contact sets: a tuple of foot points (`heel`, `forefoot`). A held (sticking) set keeps a
normal row per point and one tangential row, carried by the first point (on a flat foot the
forefoot's tangential row is implied by the heel's, as at the impact), its place on the ground
`s_anchor` (m, along the ground). A sliding set keeps the normal rows only, and kinetic
friction f_t = -mu s f_n turns each normal row's force direction into n - mu s t (F's row),
`friction` = mu s (s = +1 sliding forward, -1 backward). The contact rows of lambda are the
ground's force on the foot points (N): [t of the first point, n of each] held, [n of each]
sliding.

Q = Q_g + Q_joints + J^T tau: gravity Q_g = A_z^T (-m g) (A the momentum matrix, constant), the
joint model's moments (`Joints`: spring-damper, a moment table, locked as a constraint) and
applied joint moments tau (N m, one per hinge, the muscles' internal moments: extensor (hip,
knee) and plantarflexor (ankle) positive, the sign of RBDS's processed moments), each through
J = d(hinge angle)/dq. The functions of `Dynamics.motion` are what a collocation scheme calls;
the landing (landing.py) integrates them between events.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .errors import InputError
from .model import Model, ground_axes

GRAVITY = 9.81  # m/s^2
BAUMGARTE = 50.0  # 1/s, critically damped constraint stabilisation
JOINT_MODELS = ("free", "spring-damper", "locked", "torque")
# Joints: (name, parent segment, child segment); the hip only where the trunk is a rigid body.
JOINTS = (("hip", "trunk", "thigh"), ("knee", "thigh", "shank"), ("ankle", "shank", "foot"),
          ("swing_hip", "trunk", "swing_thigh"), ("swing_knee", "swing_thigh", "swing_shank"),
          ("swing_ankle", "swing_shank", "swing_foot"))
# d(flexion)/d(hinge angle), the hinge angle being the child's direction relative to the
# parent's, counter-clockwise (x forward, z up): the knee flexes clockwise; the hip (the thigh
# relative to the trunk) flexes and the ankle dorsiflexes counter-clockwise
# (tests/mechanics/test_joint_moments.py checks each on the model).
# A joint moment M (extensor / plantarflexor positive) is the hinge torque -FLEXION M.
FLEXION = {"hip": 1.0, "knee": -1.0, "ankle": 1.0, "swing_hip": 1.0, "swing_knee": -1.0,
           "swing_ankle": 1.0}
FEET = ("heel", "forefoot")  # the contact points, in the order of `heights`


@dataclass(frozen=True)
class Joints:
    """The joint model: free hinges, springs and dampers, moments over time, or locked.
    Moments are extensor (hip, knee) / plantarflexor (ankle) positive; stiffness and damping
    resist flexion (hip, knee) and dorsiflexion (ankle)."""

    model: str = "free"
    stiffness: dict[str, float] = field(default_factory=dict)  # N m / rad per joint
    damping: dict[str, float] = field(default_factory=dict)  # N m s / rad per joint
    locked: tuple[str, ...] = ()  # with model "locked": the joints held at their touchdown angle
    preload: dict[str, float] = field(default_factory=dict)  # N m held at touchdown (spring-damper)
    times: tuple[float, ...] = ()  # s after touchdown, increasing (torque)
    moments: dict[str, tuple[float, ...]] = field(default_factory=dict)  # N m at `times` (torque)


FREE = Joints()  # free hinges: no joint moments

class Dynamics:
    """The finite motion of one model, joint model and ground, as CasADi expressions.

    Every landing function takes the joint vector `joint` (4 h,, h = len(hinges)):
    [theta_0 (rad, the hinge angles the springs and locks refer to), k (N m/rad),
    c (N m s/rad), tau_0 (N m, the preload as a hinge torque)], parameters rather than
    constants so that one compiled function serves every joint setting.
    """

    def __init__(self, model: Model, joints: Joints = FREE, slope: float = 0.0):
        if joints.model not in JOINT_MODELS:
            raise InputError(f"joint model {joints.model!r}: expected one of {', '.join(JOINT_MODELS)}")
        self.model, self.joints, self.slope = model, joints, slope
        self.t_axis, self.n_axis = ground_axes(slope)
        rigid = {b.segment: b for b in model.bodies}
        self.hinges = [(name, rigid[p], rigid[c]) for name, p, c in JOINTS
                       if p in rigid and c in rigid]
        self._functions: dict = {}
        q = ca.SX.sym("q", model.n)
        self.gravity = model.momentum_matrix.T @ np.array([0.0, -GRAVITY])  # constant Q_g, N
        self._angles = ca.Function("joint_angles", [q], [ca.vertcat(*[self._angle(q, p, c)
                                                                      for _, p, c in self.hinges])])

    # -- geometry ----------------------------------------------------------------------
    def _direction(self, q, body):
        i, j = body.base
        return q[self.model.cols(j)] - q[self.model.cols(i)]

    def _angle(self, q, parent, child):
        """Relative angle of child to parent base directions (rad), smooth away from +-pi:
        theta = atan2(d_p x d_c, d_p . d_c)."""
        dp, dc = self._direction(q, parent), self._direction(q, child)
        return ca.atan2(dp[0] * dc[1] - dp[1] * dc[0], ca.dot(dp, dc))

    def hinge_angles(self, q):
        """The hinge angles theta(q) (h,), rad, counter-clockwise child against parent; any q."""
        return self._angles(q)

    def joint_angles(self, q) -> np.ndarray:
        """The hinge angles at a numeric q (h,), rad."""
        return np.asarray(self._angles(q), float).ravel()

    def contact_row(self, point: str, axis) -> ca.DM:
        """(1, n) row taking q (or q') to `point`'s component along `axis` (m or m/s)."""
        return ca.DM(self.model.scatter(np.asarray(axis)[None, :], [point]))

    def heights(self, q):
        """Height of heel and forefoot above the ground (2,), m."""
        return ca.vertcat(*[ca.dot(q[self.model.cols(p)], ca.DM(self.n_axis)) for p in FEET])

    def constraints(self, q, active: tuple[str, ...], s_anchor, joint, sliding: bool = False):
        """Phi(q): the body's constraints, the locked joints (theta - theta_0) and the contact
        rows of `active` (m; rad for a lock): t of the first point minus `s_anchor` when held,
        then n of each point. A sliding set has no tangential row."""
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

    # -- forces and energies -----------------------------------------------------------
    def joint_parameters(self, q) -> np.ndarray:
        """The joint vector (4 h,) numeric, with theta_0 the hinge angles at q (the touchdown)."""
        return np.concatenate([self.joint_angles(q) if self.hinges else [], self.spring_parameters()])

    def spring_parameters(self) -> np.ndarray:
        """[k, c, tau_0] per hinge (3 h,), zero unless the joints are springs and dampers."""
        j, names = self.joints, [name for name, _, _ in self.hinges]
        if j.model != "spring-damper":
            return np.zeros(3 * len(names))
        return np.array([j.stiffness.get(n, 0.0) for n in names]
                        + [j.damping.get(n, 0.0) for n in names]
                        + [-FLEXION[n] * j.preload.get(n, 0.0) for n in names])

    def joint_forces(self, q, qd, joint, t):
        """Generalised forces of the joint model J^T tau (n,), N, and the power the joints take
        from the body (W).

        tau = tau_0 - k (theta - theta_0) - c theta' (spring-damper; its conservative part is
        in `spring_energy`, the power counts the damper, c theta'^2) or tau = -s M(t) (torque,
        s = FLEXION, M from the joint table; power -tau theta')."""
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

    def moment_forces(self, q, qd, moments):
        """Generalised forces of applied joint moments (n,), N, and the power they take from
        the body (W): Q = J^T tau, tau = -FLEXION M (M extensor / plantarflexor positive, N m,
        one per hinge), power = -tau . theta'."""
        if not self.hinges:
            return ca.SX.zeros(self.model.n), 0
        theta = self._angles(q)
        tau = ca.DM([-FLEXION[name] for name, _, _ in self.hinges]) * moments
        return ca.jacobian(theta, q).T @ tau, -ca.dot(tau, ca.jtimes(theta, q, qd))

    def spring_energy(self, q, joint):
        """Elastic energy of the joint springs with their preload (J): V = k/2 (theta -
        theta_0)^2 - tau_0 (theta - theta_0), zero at theta_0, -dV/dtheta the spring's torque."""
        if self.joints.model != "spring-damper":
            return 0
        theta_0, stiff, _, tau_0 = ca.vertsplit(joint, len(self.hinges))
        theta = self._angles(q)
        return ca.sum1(0.5 * stiff * (theta - theta_0) ** 2 - tau_0 * (theta - theta_0))

    def energy(self, q, qd, joint):
        """Mechanical energy T + V_gravity + V_springs (J): 1/2 q'^T M q' + g A_z q + V."""
        m = self.model
        return m.kinetic_energy(qd) + GRAVITY * ca.dot(ca.DM(m.momentum_matrix[1]), q) \
            + self.spring_energy(q, joint)

    # -- the motion --------------------------------------------------------------------
    def motion(self, active: tuple[str, ...] = (), sliding: bool = False) -> ca.Function:
        """The motion with contact set `active` (held, or sliding), a CasADi Function (SX).

        Inputs: q (n,) m; qd (n,) m/s; s_anchor (m, the held tangential row's place);
        joint (4 h,); friction (mu s, sliding sets only); t (s, drives the torque table);
        moments (h,) N m, applied joint moments (zero for the landing).
        Outputs: qd_out = q'; qdd (n,) m/s^2; lambda (the multipliers, N: body rows, locks,
        then the contact rows); power (W) the joints and friction take from the body; force
        [t, n] the total contact force (N; zero in flight); normal (N per point); slip (m/s,
        the first point's tangential velocity); residual = |Phi|_inf (m); energy (J, `energy`).
        """
        key = ("motion", sliding) + tuple(active)
        if key not in self._functions:
            m = self.model
            q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
            s_anchor, joint = ca.SX.sym("s_anchor"), ca.SX.sym("joint", 4 * len(self.hinges))
            mu_s, t, moments = ca.SX.sym("friction"), ca.SX.sym("t"), ca.SX.sym("moments", len(self.hinges))
            phi = self.constraints(q, active, s_anchor, joint, sliding)
            Phi = ca.jacobian(phi, q)
            tangents = [self.contact_row(p, self.t_axis) for p in active]
            F = Phi
            if sliding and active:  # kinetic friction -mu s f_n on each sliding point
                F = ca.vertcat(Phi[:-len(active), :],
                               Phi[-len(active):, :] - mu_s * ca.vertcat(*tangents))
            M_inv = ca.DM(m.M_inv)
            Q_joint, power = self.joint_forces(q, qd, joint, t)
            Q_applied, applied_power = self.moment_forces(q, qd, moments)
            Q = ca.DM(self.gravity) + Q_joint + Q_applied
            power += applied_power
            phid = Phi @ qd
            gamma = -ca.jtimes(phid, q, qd) - 2 * BAUMGARTE * phid - BAUMGARTE**2 * phi
            lam = ca.solve(Phi @ M_inv @ F.T, gamma - Phi @ (M_inv @ Q))
            qdd = M_inv @ (Q + F.T @ lam)
            force, normal, friction_power = self._contact_forces(lam, qd, active, sliding, mu_s, tangents)
            slip = tangents[0] @ qd if active else ca.SX(0)
            self._functions[key] = ca.Function(
                "motion", [q, qd, s_anchor, joint, mu_s, t, moments],
                [qd, qdd, lam, power + friction_power, force, normal, slip, ca.norm_inf(phi),
                 self.energy(q, qd, joint)],
                ["q", "qd", "s_anchor", "joint", "friction", "t", "moments"],
                ["qd_out", "qdd", "lambda", "power", "force", "normal", "slip", "residual", "energy"])
        return self._functions[key]

    @staticmethod
    def _contact_forces(lam, qd, active, sliding, mu_s, tangents):
        """The contact rows of lambda as (total force [t, n], normal per point, friction power):
        sliding, f_t = -mu s sum f_n and the friction takes mu s f_n (t . q') per point."""
        if not active:
            return ca.SX.zeros(2), ca.SX.zeros(1), 0
        if sliding:
            normal = lam[-len(active):]
            power = sum(mu_s * normal[k] * (tangents[k] @ qd) for k in range(len(active)))
            return ca.vertcat(-mu_s * ca.sum1(normal), ca.sum1(normal)), normal, power
        contact_rows = lam[-(len(active) + 1):]
        normal = contact_rows[1:]
        return ca.vertcat(contact_rows[0], ca.sum1(normal)), normal, 0
