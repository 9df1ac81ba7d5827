"""The full planar body in joint coordinates, from the natural-coordinate model.

theta = [x_hip, z_hip, trunk, hip_R, knee_R, ankle_R, hip_L, knee_L, ankle_L] (m, rad): the hip's
position, the trunk's forward lean and the joint angles of design.md section 2 (hip and knee
flexion, ankle dorsiflexion positive). Leg R is the model's stance leg (thigh, shank, foot), leg
L its swing leg (swing_*). The natural coordinates q(theta) follow from the segment kinematics
of mechanics.model (`landmarks`: the same conventions), so every body constraint holds
identically and, with J = dq/dtheta and M the model's constant mass matrix (Lagrange),

    M(theta) theta'' + J^T M (dJ/dt) theta' = J^T Q_g + tau_pass(theta, theta') - S tau + J_c^T f

M(theta) = J^T M J, Q_g = momentum_matrix^T [0, -g]; tau the six joint moments (N m, extensor
(hip, knee) and plantarflexor (ankle) positive, the landing's convention: FLEXION in
mechanics.landing), so the generalised force on a flexion angle is -tau; J_c the contact
points' rows [t; n] of a ground of slope `slope` (rad); f the ground's force (N).

Passive moments beyond the ranges of motion (`RANGES`): a smooth exponential wall,
tau_pass = K [exp((phi_min - phi) / w) - exp((phi - phi_max) / w)] on each flexion angle phi
(K = 1 N m, w = 5 deg: 0.14 N m inside the range 10 deg away from a limit, 2.7 N m at 5 deg
beyond it, where `LIMIT_MARGIN`, the hard bound of a solve, stops it: a stiffer wall makes a
light swing foot ring at a period near the collocation step). The form is the exponential limit of Riener & Edrich (1999, J Biomech 32:539) and
of Anderson & Pandy (1999); the values are ours, chosen so the wall matters only beyond the
range. The ranges are those of running (Novacheck 1998), with a margin.
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
PASSIVE_K = 1.0  # N m
PASSIVE_WIDTH = math.radians(5.0)  # rad
LIMIT_MARGIN = math.radians(5.0)  # rad, how far beyond RANGES a solve may go


def swap_legs(theta):
    """theta (or theta') with the legs exchanged: R <-> L (any array-like or SX of length 9)."""
    return ca.vertcat(theta[0:3], theta[6:9], theta[3:6]) if isinstance(theta, (ca.SX, ca.MX)) \
        else np.concatenate([theta[0:3], theta[6:9], theta[3:6]])


class JointSpace:
    """The full body's dynamics in joint coordinates (CasADi Functions of SX).

    Functions (theta (9), theta' (9), slope (rad) where needed):
    q(theta) (n natural coordinates), J(theta) (n x 9), mass(theta) (9 x 9), bias(theta, theta')
    (J^T M dJ/dt theta'), gravity(theta) (J^T Q_g), passive(theta, theta') (generalised passive
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
        self.passive = ca.Function("passive", [th], [self._passive(th)])
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

    @staticmethod
    def _passive(theta):
        """Generalised passive moments (N m, 9) of the exponential walls beyond RANGES."""
        out = [0, 0, 0]
        for k, name in enumerate(JOINTS):
            lo, hi = RANGES[name[:-2]]
            phi = theta[3 + k]
            out.append(PASSIVE_K * (ca.exp((lo - phi) / PASSIVE_WIDTH) - ca.exp((phi - hi) / PASSIVE_WIDTH)))
        return ca.vertcat(*out)

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
