"""Planar multibody model in natural coordinates (García de Jalón & Bayo, 1994).

The coordinates q are the planar positions (x, z) of a few named points. A rigid body is
described by two base points i, j; any other point of the body (its centre of mass, a joint)
is the fixed linear combination

    r = (1 - a/L) r_i + (a/L) r_j + (b/L) R90 (r_j - r_i)

with (a, b) its coordinates in a frame at r_i whose x axis points to r_j, L = |r_j - r_i|
and R90 the counter-clockwise quarter turn. Hence the mass matrix is constant:

    M_body = m C(a_c, b_c)^T C(a_c, b_c) + (J_c / L^2) [[I, -I], [-I, I]]

(m the mass, (a_c, b_c) the centre of mass, J_c the inertia about it). Constraints: the base
distance (|r_j - r_i|^2 - L^2), each fixed point (two linear rows), each pair of coincident
points (two linear rows). A point mass adds m I2 to its point.

The kinematic state at touchdown (`STATE`) is mapped to (q, q') by segment kinematics
(body.py frames); the strike point is placed at the origin, on the ground.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from .body import Body
from .errors import InputError
from .limits import ANGLE_LIMIT, RATE_LIMIT, SPEED_LIMIT

# The touchdown state vector, SI: joint and trunk angles (rad; design.md section 2), the hip
# velocity (m/s, x forward, z up) and absolute segment angular velocities (rad/s, CCW).
STATE = ("trunk", "hip", "knee", "ankle", "hip_vx", "hip_vz",
         "omega_trunk", "omega_thigh", "omega_shank", "omega_foot")
# What a touchdown state may hold (SI, limits.py): beyond it a result is an overflow, not a runner.
STATE_LIMITS = tuple(ANGLE_LIMIT if k < 4 else SPEED_LIMIT if k < 6 else RATE_LIMIT
                     for k in range(len(STATE)))
STATE_UNITS = ("rad",) * 4 + ("m/s",) * 2 + ("rad/s",) * 4
STRIKES = {"heel": ("heel",), "forefoot": ("forefoot",), "flat": ("heel", "forefoot")}
MODELS = ("effective-mass", "shank-foot", "leg", "leg-trunk", "full-body")

R90 = np.array([[0.0, -1.0], [1.0, 0.0]])


@dataclass(frozen=True)
class Point:
    """A coordinate point: `landmark` of the body frames (body.py) that carry it."""

    name: str
    landmark: str


@dataclass(frozen=True)
class RigidBody:
    """A segment described by two base points and any number of points fixed in it."""

    segment: str
    base: tuple[str, str]
    fixed: tuple[str, ...] = ()


@dataclass(frozen=True)
class PointMass:
    """A segment whose whole mass sits at one point (no inertia), e.g. the trunk at the hip."""

    segment: str
    point: str


@dataclass(frozen=True)
class Swing:
    """The swing leg's touchdown posture (joint angles, rad) and absolute rates (rad/s)."""

    hip: float
    knee: float
    ankle: float
    omega_thigh: float
    omega_shank: float
    omega_foot: float


CHAIN = (("shank", "thigh", "knee"), ("foot", "shank", "ankle"),
         ("swing_shank", "swing_thigh", "swing_knee"), ("swing_foot", "swing_shank", "swing_ankle"))


def check_state(x) -> np.ndarray:
    """x as a float array of len(STATE), or an InputError naming the first bad entry."""
    x = np.asarray(x, float).reshape(-1)
    if x.shape != (len(STATE),):
        raise InputError(f"a touchdown state has {len(STATE)} values {STATE}, not {x.size}")
    for name, value, limit, unit in zip(STATE, x, STATE_LIMITS, STATE_UNITS):
        if not abs(value) <= limit:  # also NaN
            raise InputError(f"touchdown {name} = {value:.4g} {unit} is outside "
                             f"[-{limit:.4g}, {limit:.4g}] {unit} (model.STATE_LIMITS)")
    return x


def xy(v) -> tuple[float, float]:
    """A planar vector (2 numbers, any array shape) as the pair (x, y) of floats."""
    x, y = np.ravel(v)
    return float(x), float(y)


def ground_axes(slope):
    """Tangent (forward, along the ground) and normal (up, out of the ground) unit vectors of
    a ground of `slope` rad: numpy arrays for a number, CasADi columns for a symbol."""
    if isinstance(slope, (ca.SX, ca.MX)):
        c, s = ca.cos(slope), ca.sin(slope)
        return ca.vertcat(c, s), ca.vertcat(-s, c)
    return np.array([np.cos(slope), np.sin(slope)]), np.array([-np.sin(slope), np.cos(slope)])


def segment_angles(joints: dict) -> dict:
    """Segment angles from joint angles (rad, design.md section 2; any numbers or CasADi).

    `joints`: trunk (from the upward vertical, leaning forward positive), hip flexion, knee
    flexion, ankle dorsiflexion (0 with the foot perpendicular to the shank). Returns trunk,
    thigh and shank (from the downward vertical, distal end ahead positive) and foot (from the
    ground, toe-up positive):

        thigh = hip - trunk,  shank = thigh - knee,  foot = shank + ankle

    The inverse of `joint_angles`.
    """
    thigh = joints["hip"] - joints["trunk"]
    shank = thigh - joints["knee"]
    return {"trunk": joints["trunk"], "thigh": thigh, "shank": shank,
            "foot": shank + joints["ankle"]}


def joint_angles(segments: dict) -> dict:
    """Joint angles from segment angles (rad, design.md section 2), each joint from the two
    segments it joins that `segments` holds:

        hip = thigh + trunk,  knee = thigh - shank,  ankle = foot - shank

    The inverse of `segment_angles` (conventions there).
    """
    pairs = {"hip": ("thigh", "trunk"), "knee": ("thigh", "shank"), "ankle": ("foot", "shank")}
    out = {"trunk": segments["trunk"]} if "trunk" in segments else {}
    for joint, (a, b) in pairs.items():
        if a in segments and b in segments:
            out[joint] = segments[a] + segments[b] if joint == "hip" else segments[a] - segments[b]
    return out


def segment_kinematics(x, body: Body, swing: Swing | None = None):
    """Origin, angle, origin velocity and angular velocity of each segment frame (SX).

    The hip is at the origin here; positions are shifted afterwards. Frame angles are
    counter-clockwise (body.py): the segment angles of `segment_angles`, except the trunk's,
    which leans forward clockwise. The swing leg, when given, follows the same rules with its
    own joint angles.
    """
    s = dict(zip(STATE, ca.vertsplit(x)))
    angle = {**segment_angles(s), "trunk": -s["trunk"]}
    omega = {k: s["omega_" + k] for k in ("trunk", "thigh", "shank", "foot")}
    if swing is not None:
        own = segment_angles({"trunk": s["trunk"], "hip": swing.hip, "knee": swing.knee,
                              "ankle": swing.ankle})
        angle.update({f"swing_{k}": own[k] for k in ("thigh", "shank", "foot")})
        omega.update(swing_thigh=swing.omega_thigh, swing_shank=swing.omega_shank,
                     swing_foot=swing.omega_foot)
    hip = ca.vertcat(0, 0), ca.vertcat(s["hip_vx"], s["hip_vz"])
    frames = {"trunk": hip, "thigh": hip, "swing_thigh": hip}
    for child, parent, joint in CHAIN:
        if child in angle:
            frames[child] = _landmark(frames[parent], angle[parent], omega[parent],
                                      body[parent].landmarks[joint])
    return {k: (frames[k][0], angle[k], frames[k][1], omega[k]) for k in frames
            if k in body.segments and k in angle}


def landmarks(x, body: Body, origin: str = "hip", swing: Swing | None = None) -> dict:
    """World position and velocity (SX) of every landmark of the body, with `origin` at (0, 0).

    A landmark shared by two segments (a joint) is taken from the distal one.
    """
    frames = segment_kinematics(x, body, swing)
    world = {}
    for seg in ("trunk", "thigh", "shank", "foot", "swing_thigh", "swing_shank", "swing_foot"):
        if seg in frames:
            position, angle, velocity, omega = frames[seg]
            for name, local in body[seg].landmarks.items():
                world[name] = _landmark((position, velocity), angle, omega, local)
    shift = world[origin][0]
    return {k: (p - shift, v) for k, (p, v) in world.items()}


def positions(x, body: Body, origin: str = "hip", swing: Swing | None = None) -> dict[str, np.ndarray]:
    """World positions (m, numeric) of every landmark at the touchdown state x."""
    xs = ca.SX.sym("x", len(STATE))
    world = landmarks(xs, body, origin, swing)
    f = ca.Function("positions", [xs], [p for p, _ in world.values()])
    return {k: np.asarray(v, float).ravel() for k, v in zip(world, f(np.asarray(x, float)))}


def _landmark(frame, angle, omega, local):
    """World position and velocity of a point given in a segment frame."""
    origin, velocity = frame
    rot = ca.vertcat(ca.horzcat(ca.cos(angle), -ca.sin(angle)),
                     ca.horzcat(ca.sin(angle), ca.cos(angle)))
    arm = rot @ ca.DM(local)
    return origin + arm, velocity + omega * ca.vertcat(-arm[1], arm[0])


class Model:
    """A planar model in natural coordinates, built from a Body and a description.

    `points` order the coordinates: q = [x_0, z_0, x_1, z_1, ...].
    """

    def __init__(self, body: Body, points, bodies, point_masses=(), coincident=(), trunk=None,
                 guides=(), tangential: bool = True, kind: str = "", swing: Swing | None = None):
        self.body = body
        self.kind = kind
        self.swing = swing
        self.points = tuple(points)
        self.bodies = tuple(bodies)
        self.point_masses = tuple(point_masses)
        self.coincident = tuple(coincident)
        # (point, direction): the point moves only along that line through the origin (where
        # the strike point is placed); `tangential`: contacts hold the tangential direction
        self.guides = tuple((p, np.asarray(d, float) / np.linalg.norm(d)) for p, d in guides)
        self.tangential = tangential
        self.index = {p.name: k for k, p in enumerate(self.points)}
        self.n = 2 * len(self.points)
        self.trunk = trunk  # segment whose velocity change is reported as dv_trunk
        self._check()
        qs = ca.SX.sym("q", self.n)
        self._jacobian = ca.Function("Phi_b_q", [qs], [ca.jacobian(self.constraints(qs), qs)])
        # strike point -> Function x -> (q, q'), built on first use
        self._state_functions: dict[str, ca.Function] = {}
        self.M = self._mass_matrix()
        self.M_inv = np.linalg.inv(self.M)

    # -- description -----------------------------------------------------------------
    def _check(self):
        names = [p.name for p in self.points]
        if len(set(names)) != len(names):
            raise InputError(f"duplicate point names in {names}")
        used = {p for b in self.bodies for p in b.base + b.fixed}
        used |= {pm.point for pm in self.point_masses} | {p for c in self.coincident for p in c}
        used |= {p for p, _ in self.guides}
        unknown = used - set(names)
        if unknown:
            raise InputError(f"the model refers to undefined points {sorted(unknown)}")
        carried = {p for b in self.bodies for p in b.base} | {pm.point for pm in self.point_masses}
        massless = [n for n in names if n not in carried]
        if massless:
            raise InputError(f"points {massless} carry no mass (the mass matrix would be singular): "
                             "make each one a base point of a body or give it a point mass")
        for b in self.bodies:
            if self._local(b, b.base[0]) == self._local(b, b.base[1]):
                raise InputError(f"{b.segment}: base points coincide, the frame is undefined")

    @property
    def segments(self) -> tuple[str, ...]:
        return tuple(b.segment for b in self.bodies) + tuple(pm.segment for pm in self.point_masses)

    def point(self, name: str) -> Point:
        return self.points[self.index[name]]

    def cols(self, name: str) -> slice:
        k = 2 * self.index[name]
        return slice(k, k + 2)

    def _local(self, b: RigidBody, point: str):
        return self.body[b.segment].landmarks[self.point(point).landmark]

    def basis(self, b: RigidBody, local) -> np.ndarray:
        """C (2x4): world position of a body-frame point from the base points [r_i; r_j]."""
        ri, rj = (np.asarray(self._local(b, p), float) for p in b.base)
        length = np.linalg.norm(rj - ri)
        u = (rj - ri) / length
        d = np.asarray(local, float) - ri
        a, c = d @ u, d @ (R90 @ u)
        eye = np.eye(2)
        return np.hstack([(1 - a / length) * eye - (c / length) * R90,
                          (a / length) * eye + (c / length) * R90])

    def scatter(self, block: np.ndarray, points) -> np.ndarray:
        """Place columns given for `points` (2 each) into a full-width matrix."""
        out = np.zeros((block.shape[0], self.n))
        for k, p in enumerate(points):
            out[:, self.cols(p)] += block[:, 2 * k:2 * k + 2]
        return out

    # -- mass ------------------------------------------------------------------------
    def _mass_matrix(self) -> np.ndarray:
        M = np.zeros((self.n, self.n))
        for b in self.bodies:
            seg = self.body[b.segment]
            C = self.scatter(self.basis(b, seg.com), b.base)
            ri, rj = (np.asarray(self._local(b, p), float) for p in b.base)
            P = self.scatter(np.eye(4), b.base)  # q -> [r_i; r_j]
            spin = np.kron(np.array([[1.0, -1.0], [-1.0, 1.0]]), np.eye(2))
            M += seg.mass * C.T @ C + seg.inertia_com / np.sum((rj - ri) ** 2) * P.T @ spin @ P
        for pm in self.point_masses:
            M[self.cols(pm.point), self.cols(pm.point)] += self.body[pm.segment].mass * np.eye(2)
        eig = np.linalg.eigvalsh(M)
        if eig[0] <= 1e-12 * max(eig[-1], 1e-300):
            raise InputError(f"the mass matrix is singular (eigenvalues {eig[0]:.3g} .. {eig[-1]:.3g}): "
                             "each segment needs a mass and an inertia about its centre of mass > 0")
        return M

    def com_matrix(self, segment: str) -> np.ndarray:
        """(2 x n) map from q (or q') to the segment's centre of mass (or its velocity)."""
        for b in self.bodies:
            if b.segment == segment:
                return self.scatter(self.basis(b, self.body[segment].com), b.base)
        for pm in self.point_masses:
            if pm.segment == segment:
                return self.scatter(np.eye(2), [pm.point])
        raise KeyError(f"the model has no segment {segment!r}")

    @property
    def momentum_matrix(self) -> np.ndarray:
        """(2 x n) map from q' to the total linear momentum (kg m/s)."""
        return sum((self.body[s].mass * self.com_matrix(s) for s in self.segments), np.zeros((2, self.n)))

    @property
    def mass(self) -> float:
        return sum(self.body[s].mass for s in self.segments)

    # -- constraints -----------------------------------------------------------------
    def constraints(self, q) -> ca.SX:
        """Body constraints phi_b(q) = 0 (distances, fixed points, coincident points)."""
        rows = []
        for b in self.bodies:
            ri, rj = (q[self.cols(p)] for p in b.base)
            li, lj = (np.asarray(self._local(b, p), float) for p in b.base)
            rows.append(ca.sumsqr(rj - ri) - float(np.sum((lj - li) ** 2)))
            for p in b.fixed:
                C = self.basis(b, self._local(b, p))
                rows.append(q[self.cols(p)] - ca.DM(C) @ ca.vertcat(ri, rj))
        for a, c in self.coincident:
            rows.append(q[self.cols(a)] - q[self.cols(c)])
        for p, d in self.guides:
            rows.append(ca.dot(q[self.cols(p)], ca.DM(R90 @ d)))
        return ca.vertcat(*rows)

    def constraint_jacobian(self, q) -> ca.SX:
        """Phi_b,q(q): the Jacobian of the body constraints, for a symbolic or numeric q."""
        return self._jacobian(q)

    def contact_rows(self, points, slope, tangential=None):
        """Constant Jacobian rows [t; n] of each contact point held on a ground of `slope` rad
        (a number: a numpy array; a CasADi symbol: the rows as expressions of it).

        `tangential` lists the points whose tangential row is kept (default: all).
        """
        t, n = ground_axes(slope)
        keep = points if tangential is None else tangential
        if not isinstance(slope, (ca.SX, ca.MX)):
            return np.vstack([self.scatter(axis[None, :], [p]) for p in points
                              for axis in ((t, n) if p in keep else (n,))])
        def row(axis, p):  # axis_x e_x + axis_z e_z at the columns of p
            return sum(axis[k] * ca.DM(self.scatter(np.eye(2)[k:k + 1], [p])) for k in range(2))
        return ca.vertcat(*[row(axis, p) for p in points for axis in ((t, n) if p in keep else (n,))])

    # -- state -----------------------------------------------------------------------
    def state(self, x, strike_point: str):
        """(q, q') as SX of the touchdown state x, with `strike_point` at the origin."""
        world = landmarks(x, self.body, strike_point, self.swing)
        guided = dict(self.guides)
        q = ca.vertcat(*[world[p.landmark][0] for p in self.points])
        velocities = []
        for p in self.points:  # a guided point moves only along its guide
            v = world[p.landmark][1]
            velocities.append(ca.DM(guided[p.name]) * ca.dot(v, ca.DM(guided[p.name]))
                              if p.name in guided else v)
        return q, ca.vertcat(*velocities)

    def state_numeric(self, x, strike_point: str) -> tuple[np.ndarray, np.ndarray]:
        """(q, q') as numpy arrays of a numeric touchdown state (the map is built once)."""
        if strike_point not in self._state_functions:
            xs = ca.SX.sym("x", len(STATE))
            self._state_functions[strike_point] = ca.Function("state", [xs], list(self.state(xs, strike_point)))
        q, qd = self._state_functions[strike_point](np.asarray(x, float))
        return np.asarray(q, float).ravel(), np.asarray(qd, float).ravel()

    def segment_angle(self, q, segment: str) -> float:
        """Absolute angle (rad, design.md conventions) of a rigid segment at numeric q."""
        b = next(b for b in self.bodies if b.segment == segment)
        li, lj = (np.asarray(self._local(b, p), float) for p in b.base)
        d = q[self.cols(b.base[1])] - q[self.cols(b.base[0])]
        local = lj - li
        return float(np.arctan2(d[1], d[0]) - np.arctan2(local[1], local[0]))

    def kinetic_energy(self, qd):
        return 0.5 * ca.bilin(ca.DM(self.M), qd, qd)


def build_model(body: Body, kind: str = "leg", strike: str = "forefoot",
                swing: Swing | None = None) -> Model:
    """A model of the stance leg, from coarse to fine.

    effective-mass (Lieberman et al. 2010, Nature 463:531): the lower limb's mass (shank and
    foot) at the strike point, which moves only vertically: one degree of freedom, the impact
    along the ground normal only (T_c = 1/2 m v_n^2). Built for one strike point.
    shank-foot: points knee, ankle, heel, forefoot (8 coordinates); shank knee->ankle, foot
    heel->forefoot with the ankle fixed in it; 4 degrees of freedom. The thigh's length still
    carries the hip's motion to the knee.
    leg (the paper's): adds the hip and the thigh hip->knee, and trunk and swing leg as one
    point mass at the hip (10 coordinates, 5 constraints, 5 degrees of freedom).
    leg-trunk: the trunk (head, arms, trunk) rigid, hip->shoulder, so its angle and
    inertia matter; the swing leg a point mass at the hip (12 coordinates, 6 degrees of freedom).
    full-body: the rigid trunk and both legs, the swing leg (the stance leg's segments) a free
    chain of thigh, shank and foot in the posture `swing` (20 coordinates, 9 degrees of freedom).
    """
    foot = RigidBody("foot", ("heel", "forefoot"), ("ankle",))
    shank = RigidBody("shank", ("knee", "ankle"))
    thigh = RigidBody("thigh", ("hip", "knee"))
    leg_points = ("hip", "knee", "ankle", "heel", "forefoot")
    swing_mass = [PointMass("swing_leg", "hip")] if "swing_leg" in body.segments else []
    if kind == "effective-mass":
        point = STRIKES[strike][0]
        return Model(body, [Point(point, point)], (), [PointMass("effective_mass", point)],
                     guides=[(point, (0.0, 1.0))], tangential=False, kind=kind)
    if kind == "shank-foot":
        return Model(body, [Point(n, n) for n in leg_points[1:]], (shank, foot), kind=kind)
    if kind == "leg":
        return Model(body, [Point(n, n) for n in leg_points], (thigh, shank, foot),
                     [PointMass("trunk", "hip"), *swing_mass], trunk="trunk", kind=kind)
    if kind == "leg-trunk":
        if "shoulder" not in body["trunk"].landmarks or body["trunk"].inertia_com <= 0:
            raise InputError("model 'leg-trunk' needs a rigid trunk: its length, centre of mass "
                             "and inertia")
        return Model(body, [Point(n, n) for n in ("shoulder", *leg_points)],
                     (RigidBody("trunk", ("hip", "shoulder")), thigh, shank, foot),
                     swing_mass, trunk="trunk", kind=kind)
    if kind == "full-body":
        if swing is None:
            raise InputError("model 'full-body' needs the swing leg's touchdown posture")
        if "shoulder" not in body["trunk"].landmarks or body["trunk"].inertia_com <= 0:
            raise InputError("model 'full-body' needs a rigid trunk: its length, centre of mass "
                             "and inertia")
        full = Body({**body.segments, **swing_segments(body)}, body.source)
        swing_points = ("swing_knee", "swing_ankle", "swing_heel", "swing_forefoot")
        bodies = (RigidBody("trunk", ("hip", "shoulder")), thigh, shank, foot,
                  RigidBody("swing_thigh", ("hip", "swing_knee")),
                  RigidBody("swing_shank", ("swing_knee", "swing_ankle")),
                  RigidBody("swing_foot", ("swing_heel", "swing_forefoot"), ("swing_ankle",)))
        return Model(full, [Point(n, n) for n in ("shoulder", *leg_points, *swing_points)], bodies,
                     trunk="trunk", kind=kind, swing=swing)
    raise InputError(f"unknown model {kind!r}: expected one of {', '.join(MODELS)}")


def swing_segments(body: Body) -> dict:
    """The swing leg: the stance leg's segments with their landmarks renamed swing_*."""
    out = {}
    for seg in ("thigh", "shank", "foot"):
        s = body[seg]
        marks = {(k if k == "hip" else f"swing_{k}"): v for k, v in s.landmarks.items()}
        out[f"swing_{seg}"] = type(s)(f"swing_{seg}", s.mass, s.com, s.inertia_com, marks)
    return out
