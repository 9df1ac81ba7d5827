"""The full planar body in joint coordinates, from the natural-coordinate model.

theta = [x_hip, z_hip, trunk, hip_R, knee_R, ankle_R, hip_L, knee_L, ankle_L] (m, rad): the hip's
position, the trunk's forward lean and the joint angles of design.md section 2 (hip and knee
flexion, ankle dorsiflexion positive). Leg R is the model's stance leg (thigh, shank, foot), leg
L its swing leg (swing_*). The natural coordinates q(theta) follow from the segment kinematics
of mechanics.model (`landmarks`: the same conventions), so every body constraint holds
identically and, with J = dq/dtheta and M the model's constant mass matrix (Lagrange),

    M(theta) theta'' + J^T M (dJ/dt) theta' = J^T Q_g + tau_pass(theta) - S tau + J_c^T f

M(theta) = J^T M J, Q_g = momentum_matrix^T [0, -g]; tau the six joint moments (N m, extensor
(hip, knee) and plantarflexor (ankle) positive, the landing's convention: FLEXION in
mechanics.landing), so the generalised force on a flexion angle is -tau; J_c the contact
points' rows [t; n] of a ground of slope `slope` (rad); f the ground's force (N).

Passive joint moments tau_pass(theta) (`passive_moments`): the elastic moments of the relaxed
leg that Riener & Edrich (1999, J Biomech 32:539) measured on ten healthy subjects, with the
two-joint muscles' coupling (the knee's moment depends on the hip and the ankle, the hip's and
the ankle's on the knee): double exponentials in degrees (their hip and knee flexion and ankle
PLANTARflexion positive, moments positive in the direction of the positive angle), as published
for an adult, not scaled with the body (Miller et al. 2012 used them so in a sprinting model).
A smooth field, not a wall: 6.4 N m of plantarflexion at a neutral ankle with the knee straight,
42 N m at 20 deg of dorsiflexion, 22 N m of knee flexion 5 deg into hyperextension. The coupling
is not a potential's (d tau_hip / d knee != d tau_knee / d hip): a stride's passive work
(result.py's `passive_J`) need not be zero. Elastic only, no damping: the forward check stays
at 0.02-0.03 rad (docs/concepts/stride.md, "The joints' passive moments"). The ranges `RANGES`
are those of running (Novacheck 1998); a solve bounds the angles at RANGES +- `LIMIT_MARGIN`
(5 deg: at 15 deg the loaded ankle reaches 44 deg of dorsiflexion).
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from .body import Body
from .model import Model, Swing, build_model, landmarks

GRAVITY = 9.81  # m/s^2
THETA = ("x_hip", "z_hip", "trunk", "hip_R", "knee_R", "ankle_R", "hip_L", "knee_L", "ankle_L")
JOINTS = ("hip_R", "knee_R", "ankle_R", "hip_L", "knee_L", "ankle_L")
LEGS = ("R", "L")
# model point of each named foot point; the landmarks are those of model.build_model's full body
POINTS = {"heel_R": "heel", "forefoot_R": "forefoot", "heel_L": "swing_heel",
          "forefoot_L": "swing_forefoot"}
# ranges of motion of the flexion angles (rad): hip flexion, knee flexion, ankle dorsiflexion
RANGES = {"hip": (math.radians(-40.0), math.radians(110.0)),
          "knee": (math.radians(0.0), math.radians(140.0)),
          "ankle": (math.radians(-50.0), math.radians(30.0))}
LIMIT_MARGIN = math.radians(5.0)  # rad, how far beyond RANGES a solve may go
# The range walls (`limits`): the joint capsule's and ligaments' moments beyond RANGES, without
# the muscles' passive force, for a body whose muscles hold their own (the stride's muscle rung:
# Riener & Edrich's relaxed-leg moments include the muscles' passive elasticity, which the Hill
# units' parallel elements model already). A smooth exponential wall on each flexion angle phi,
# K [exp((phi_min - phi) / w) - exp((phi - phi_max) / w)], K = 1 N m, w = 5 deg: 0.14 N m inside
# the range 10 deg away from a limit, 2.7 N m at 5 deg beyond it (the exponential limit of
# Riener & Edrich 1999 and Anderson & Pandy 1999; the values chosen so the wall matters only
# beyond the range; the stride's passive moments before 2026-11-27).
WALL_K = 1.0  # N m
WALL_WIDTH = math.radians(5.0)  # rad


def passive_moments(angles):
    """One leg's passive moments (N m; on hip flexion, knee flexion, ankle dorsiflexion) at its
    flexion angles (hip, knee, ankle dorsiflexion; rad), Riener & Edrich (1999) (module
    docstring), with h, k the hip's and knee's flexion and p the ankle's plantarflexion (deg):

        hip   = exp(1.4655 - 0.0034 k - 0.0750 h) - exp(1.3403 - 0.0226 k + 0.0305 h) + 8.072
        knee  = exp(1.800 - 0.0460 p - 0.0352 k + 0.0217 h) - exp(-3.971 - 0.0004 p + 0.0495 k
                - 0.0128 h) - 4.820 + exp(2.220 - 0.150 k)
        ankle = -[exp(2.1016 - 0.0843 p - 0.0176 k) - exp(-7.9763 + 0.1949 p + 0.0008 k) - 1.792]

    (the last a plantarflexion moment, negated onto dorsiflexion). Elastic only: no damping."""
    h, k, p = (180.0 / math.pi * angles[0], 180.0 / math.pi * angles[1], -180.0 / math.pi * angles[2])
    hip = ca.exp(1.4655 - 0.0034 * k - 0.0750 * h) - ca.exp(1.3403 - 0.0226 * k + 0.0305 * h) + 8.072
    knee = (ca.exp(1.800 - 0.0460 * p - 0.0352 * k + 0.0217 * h)
            - ca.exp(-3.971 - 0.0004 * p + 0.0495 * k - 0.0128 * h) - 4.820 + ca.exp(2.220 - 0.150 * k))
    plantar = ca.exp(2.1016 - 0.0843 * p - 0.0176 * k) - ca.exp(-7.9763 + 0.1949 * p + 0.0008 * k) - 1.792
    return hip, knee, -plantar


def range_wall(phi, low: float, high: float):
    """The range wall's moment (N m) on a flexion angle phi (rad) with the range (low, high):
    WALL_K [exp((low - phi) / WALL_WIDTH) - exp((phi - high) / WALL_WIDTH)]."""
    return WALL_K * (ca.exp((low - phi) / WALL_WIDTH) - ca.exp((phi - high) / WALL_WIDTH))


def swap_legs(theta):
    """theta (or theta') with the legs exchanged: R <-> L (any array-like or SX of length 9)."""
    return ca.vertcat(theta[0:3], theta[6:9], theta[3:6]) if isinstance(theta, (ca.SX, ca.MX)) \
        else np.concatenate([theta[0:3], theta[6:9], theta[3:6]])


class JointSpace:
    """The full body's dynamics in joint coordinates (CasADi Functions of SX).

    Functions (theta (9), theta' (9), slope (rad) where needed):
    q(theta) (n natural coordinates), J(theta) (n x 9), mass(theta) (9 x 9), bias(theta, theta')
    (J^T M dJ/dt theta'), gravity(theta) (J^T Q_g), passive(theta) (generalised passive
    moments, 9), kinetic(theta, theta'), potential(theta) (J, zero at z = 0),
    point(theta, theta', slope) per foot point -> (position (2), [t, n] velocity (2), [t; n]
    Jacobian (2 x 9), [t; n] of dJ/dt theta' (2)), com(theta) (2, m).
    """

    def __init__(self, body: Body):
        self.body = body
        self.model: Model = build_model(body, "full-body", swing=Swing(0, 0, 0, 0, 0, 0))
        self.mass_total = self.model.mass
        th, thd = ca.SX.sym("theta", len(THETA)), ca.SX.sym("thetad", len(THETA))
        world = self._world(th)
        q = ca.vertcat(*[world[p.landmark] for p in self.model.points])
        J = ca.jacobian(q, th)
        M = ca.DM(self.model.M)
        qd = J @ thd
        Jd_thd = ca.jtimes(qd, th, thd)  # (dJ/dt) theta'
        Q_g = ca.DM(self.model.momentum_matrix.T @ np.array([0.0, -GRAVITY]))
        com = ca.DM(self.model.momentum_matrix) @ q / self.mass_total
        self.q = ca.Function("q", [th], [q], ["theta"], ["q"])
        self.J = ca.Function("J", [th], [J], ["theta"], ["J"])
        self.mass = ca.Function("mass", [th], [J.T @ M @ J], ["theta"], ["M"])
        self.bias = ca.Function("bias", [th, thd], [J.T @ (M @ Jd_thd)], ["theta", "thetad"], ["c"])
        self.gravity = ca.Function("gravity", [th], [J.T @ Q_g], ["theta"], ["g"])
        self.kinetic = ca.Function("kinetic", [th, thd], [0.5 * ca.dot(qd, M @ qd)])
        self.potential = ca.Function("potential", [th], [GRAVITY * self.mass_total * com[1]])
        self.com = ca.Function("com", [th], [com])
        self.passive = ca.Function("passive", [th], [ca.vertcat(0, 0, 0, *[
            m for k in (3, 6) for m in passive_moments(th[k:k + 3])])], ["theta"], ["tau"])
        self.limits = ca.Function("limits", [th], [ca.vertcat(0, 0, 0, *[
            range_wall(th[3 + k], *RANGES[j[:-2]]) for k, j in enumerate(JOINTS)])], ["theta"], ["tau"])
        slope = ca.SX.sym("slope")
        t, n = ca.vertcat(ca.cos(slope), ca.sin(slope)), ca.vertcat(-ca.sin(slope), ca.cos(slope))
        axes = ca.horzcat(t, n).T
        self.points = {}
        for name, landmark in POINTS.items():
            r = world[landmark]
            Jp = ca.jacobian(r, th)
            v = Jp @ thd
            self.points[name] = ca.Function(
                name, [th, thd, slope], [r, axes @ v, axes @ Jp, axes @ ca.jtimes(v, th, thd)],
                ["theta", "thetad", "slope"], ["position", "velocity", "jacobian", "drift"])
        self.landmarks = ca.Function("landmarks", [th], [ca.horzcat(*world.values())])
        self.landmark_names = tuple(world)

    def _world(self, theta) -> dict:
        """World positions (SX, m) of every landmark: model.landmarks with the hip at theta[0:2]."""
        s = dict(zip(THETA, ca.vertsplit(theta)))
        x = ca.vertcat(s["trunk"], s["hip_R"], s["knee_R"], s["ankle_R"], *([0] * 6))
        swing = Swing(s["hip_L"], s["knee_L"], s["ankle_L"], 0, 0, 0)
        hip = ca.vertcat(s["x_hip"], s["z_hip"])
        return {k: p + hip for k, (p, _) in landmarks(x, self.model.body, "hip", swing).items()}

    def segment_rates(self, theta, thetad) -> tuple[np.ndarray, Swing]:
        """model.STATE of a numeric joint state (stance leg = R), for the natural model's own
        velocity kinematics: [trunk, hip, knee, ankle (rad), hip velocity (m/s), absolute
        segment rates (rad/s) of trunk, thigh, shank, foot], and the swing leg's Swing."""
        th, w = np.asarray(theta, float), np.asarray(thetad, float)
        rates = {"trunk": -w[2]}
        for leg, k in (("R", 3), ("L", 6)):
            thigh = w[k] - w[2]
            shank = thigh - w[k + 1]
            rates[leg] = (thigh, shank, shank + w[k + 2])
        x = np.array([th[2], th[3], th[4], th[5], w[0], w[1], rates["trunk"], *rates["R"]])
        return x, Swing(th[6], th[7], th[8], *rates["L"])
