"""Contact models of the stride: the ground's rows of a phase at a node, and the impact that
adds them.

`RigidContact` holds a phase's contact rows ((point, "t" | "n"), ...; none in flight) on rigid
ground of slope `slope`, with forces f (body weights, one per row, normal >= 0). At a node, with
J_c the rows' Jacobian (r x 9) and v_c = J_c theta' their velocities:

    generalised force   J_c^T m g f                          (enters M theta'' + c = ...)
    held rows           J_c theta'' + dJ_c/dt theta' = 0     (all but a sliding point's "t")
    sticking            mu sum f_n - f_t >= 0,  mu sum f_n + f_t >= 0
    sliding (point s)   f_t = -s mu sum f_n,  s v_t >= 0      (kinetic friction against the slip)
    clearance           every foot point not held at or above the ground; while the stance
                        leg holds it, the swing leg's points at least `clearance` above it

`impact` gives the rows of a rigid impact that adds contact rows (the projection of
mechanics.impact in joint coordinates):

    M(theta) (theta'+ - theta'-) = J_c^T m p,   J_c theta'+ = 0 (held rows),   p_n >= 0,
    sticking: the impulse in the friction cone; sliding: p_t = -s mu p_n, s v_t >= 0 before
    and after (the slip keeps its sign through the impact, so the Darboux-Keller process never
    sticks),

and its absorbed energy T_c = 1/2 (theta'-^T M theta'- - theta'+^T M theta'+).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ...mechanics.joint_space import GRAVITY, JointSpace
from .layout import Rows, held_rows

FORCE_LIMIT = 8.0  # body weights: a contact row's force bound (running peaks at 2.5-3)
FRICTION_FORCE = 5.0  # body weights, a tangential force's bound either way
# The swing foot's least height (m) while the other foot holds the ground (StrideSettings.clearance;
# in flight it descends to its touchdown, >= 0 there). Without it the optimal strides passed the
# swing foot about 1 mm above the ground at mid-swing, which makes swinging the leg cheap. 1 cm
# is a floor below any runner's: walking, where the swing foot passes lowest, keeps a minimum toe
# clearance of 13 mm in young adults (Winter 1991, The biomechanics and motor control of human
# gait, p. 9), 1.9 +- 0.5 cm (Moosabhoy & Gard 2006, Gait Posture 24:493) and 11 +- 6 mm
# (Schulz 2011, J Biomech 44:1277); a running swing passes higher (no published running minimum
# was found; RBDS001's heel and metatarsal markers pass 3.4 cm above the treadmill at 2.5 m/s
# and 8.0 cm at 3.5 m/s while the other foot is loaded, medians over 79 and 86 steps:
# problems/swing_clearance.py). A floor that holds the swing foot off the ground, not a
# runner's swing: docs/concepts/muscles.md measures what raising it does (1-10 cm move the
# muscles' cadence by 1-5 steps/min).
CLEARANCE = 0.01


class RigidContact:
    """The contact rows of one phase (module docstring); `sliding` names the point whose "t"
    row carries kinetic friction -s mu f_n (s = `slip`, +1 forward or -1 back); the swing
    leg's points (`swing`: the leg with no point held, none in flight) stay `clearance` (m)
    above the ground."""

    def __init__(self, js: JointSpace, rows: tuple, sliding: str = "", slip: int = 1, clearance: float = 0.0):
        self.js, self.rows, self.sliding, self.slip = js, tuple(rows), sliding, slip
        self.points = tuple(dict.fromkeys(p for p, _ in rows))
        self.held = held_rows(self.rows, sliding)
        self.free = tuple(p for p in js.points if p not in self.points)
        legs = {p[-1] for p in self.points}
        self.swing = tuple(p for p in self.free if legs and p[-1] not in legs)
        self.clearance = clearance

    def force_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(lower, upper) of the forces (body weights, a column per row): normal >= 0."""
        lo = np.array([[0.0 if a == "n" else -FRICTION_FORCE] for _, a in self.rows]).reshape(-1, 1)
        return lo, np.full((len(self.rows), 1), FORCE_LIMIT)

    def kinematics(self, theta, thetad, slope):
        """(J_c (r x 9), dJ_c/dt theta' (r), v_c (r)) of the rows."""
        return rows_kinematics(self.js, self.rows, theta, thetad, slope)

    def node(self, rows: Rows, theta, thetad, thetadd, f, slope, mu, mass):
        """Add the node's contact rows (module docstring) to `rows`; the generalised force
        J_c^T m g f (9)."""
        for point in self.free:
            rows.add(height(self.js, point, theta, slope), self.clearance if point in self.swing else 0.0, np.inf)
        if not self.rows:
            return ca.DM.zeros(thetad.shape[0])
        J, drift, v = self.kinematics(theta, thetad, slope)
        rows.add((J @ thetadd + drift)[self.held])
        total_n = normal_sum(self.rows, f)
        for k, (point, axis) in enumerate(self.rows):
            if axis == "t" and point != self.sliding:
                rows.add(ca.vertcat(mu * total_n - f[k], mu * total_n + f[k]), 0.0, np.inf)
            elif axis == "t":
                rows.add(f[k] + self.slip * mu * total_n)
                rows.add(self.slip * v[k], 0.0, np.inf)
        return J.T @ (mass * GRAVITY * f)

    def power(self, theta, thetad, f, slope, mass):
        """(the power (W) of the ground's forces on all rows, on the held rows, and the sliding
        point's friction power): held points do not move, so the second is the transcription's
        drift; the third is what a slide dissipates."""
        if not self.rows:
            return 0.0, 0.0, 0.0
        v = self.kinematics(theta, thetad, slope)[2]
        weight = mass * GRAVITY
        slide = weight * f[self.rows.index((self.sliding, "t"))] * v[self.rows.index((self.sliding, "t"))] \
            if self.sliding else 0.0
        return weight * ca.dot(f, v), weight * ca.dot(f[self.held], v[self.held]), slide

    def impact(self, rows: Rows, theta, v_minus, v_plus, p, slope, mu, mass):
        """Add the rows of the impact that makes these rows hold (module docstring), the
        impulse p (N s per kg, one per row); T_c (J)."""
        J = self.kinematics(theta, v_plus, slope)[0]
        M = self.js.mass(theta)
        rows.add((M @ (v_plus - v_minus) - J.T @ (mass * p)) / mass)
        rows.add((J @ v_plus)[self.held])
        if self.sliding:
            t, n = self.rows.index((self.sliding, "t")), self.rows.index((self.sliding, "n"))
            slip = [rows_kinematics(self.js, ((self.sliding, "t"),), theta, v, slope)[2] for v in (v_minus, v_plus)]
            rows.add(p[t] + self.slip * mu * p[n])
            rows.add(ca.vertcat(p[n], self.slip * slip[0], self.slip * slip[1]), 0.0, np.inf)
        else:
            total_n = normal_sum(self.rows, p)
            for k, (_, axis) in enumerate(self.rows):
                if axis == "t":
                    rows.add(ca.vertcat(mu * total_n - p[k], mu * total_n + p[k]), 0.0, np.inf)
        return 0.5 * (ca.bilin(M, v_minus, v_minus) - ca.bilin(M, v_plus, v_plus))

    def impulse_bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(lower, upper) of an impact's impulses (N s per kg): normal >= 0."""
        lo = np.array([[0.0 if a == "n" else -np.inf] for _, a in self.rows]).reshape(-1, 1)
        return lo, np.full((len(self.rows), 1), np.inf)


def rows_kinematics(js: JointSpace, rows, theta, thetad, slope):
    """(Jacobian rows (r x 9), their dJ/dt theta' (r), velocities (r)) of contact rows."""
    jac, drift, vel = [], [], []
    for point, axis in rows:
        _, v, J, d = js.points[point](theta, thetad, slope)
        a = 0 if axis == "t" else 1
        jac.append(J[a, :])
        drift.append(d[a])
        vel.append(v[a])
    return ca.vertcat(*jac), ca.vertcat(*drift), ca.vertcat(*vel)


def height(js: JointSpace, point: str, theta, slope):
    """The point's height (m) above the ground of slope `slope`."""
    r = js.points[point](theta, ca.DM.zeros(theta.shape[0]), slope)[0]
    return -ca.sin(slope) * r[0] + ca.cos(slope) * r[1]


def normal_velocity(js: JointSpace, point: str, theta, thetad, slope):
    """The point's velocity (m/s) along the ground's normal."""
    return js.points[point](theta, thetad, slope)[1][1]


def normal_sum(rows, values):
    """The sum of `values` over the normal rows."""
    return ca.sum1(ca.vertcat(*[values[k] for k, (_, a) in enumerate(rows) if a == "n"]))
