"""The impact at foot strike, by projection onto the admissible motion space.

With Phi_q the Jacobian of the body and contact constraints, M the constant mass matrix,

    lambda = -(Phi_q M^-1 Phi_q^T)^-1 Phi_q q'-      q'+ = q'- + M^-1 Phi_q^T lambda
    T_c = 1/2 (Phi_q q'-)^T (Phi_q M^-1 Phi_q^T)^-1 (Phi_q q'-)    (= 1/2 q'-^T P_c^T M P_c q'-)

The contact rows of lambda are the ground's impulse on the foot point (N s): tangential
along the ground (forward positive), normal to it (pushing positive).

Flat foot: heel and forefoot held in both directions is one row too many (the foot's
rigidity already holds the distance between them along the ground). The forefoot's
tangential row is dropped, which leaves the constrained subspace, T_c, q'+, both normal
impulses and the total tangential impulse unchanged and exact. How the tangential impulse
splits between heel and forefoot is not determined by rigid-body impact; it is reported in
proportion to the normal impulses (the split that needs the least friction) and flagged.

Critical friction coefficient: `mu_c` = |tangential| / normal of the total contact impulse
(the impulse ratio); `mu_c_momentum` = the same ratio of the total linear-momentum change
M_com (q'+ - q'-) through the centre-of-mass Jacobian (the ground is the only impulsive
external force). They agree to rounding; both are reported as a check.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import casadi as ca
import numpy as np

from .compiled import Compiled
from .model import STATE, STRIKES, Model, landmarks
from .errors import InputError
# Ill-conditioned beyond this: results lose more than 10 of 16 digits.
CONDITION_LIMIT = 1e10
GRAPHS = ("SX", "MX")
# Relative tolerance of the validity checks: an optimum on a constraint (mu_c = friction,
# normal impulse = 0) is valid, not a rounding error away from invalid.
RTOL = 1e-6


def ground_axes(slope: float):
    """Tangent (forward, along the ground) and normal (up, out of the ground) unit vectors."""
    return np.array([np.cos(slope), np.sin(slope)]), np.array([-np.sin(slope), np.cos(slope)])


def projection(model: Model, q, qd, contact_jacobian):
    """The projection impact map at (q, q'-) for the given contact rows (SX in, SX out)."""
    Phi_b = model.constraint_jacobian(q)
    Phi = ca.vertcat(Phi_b, ca.DM(contact_jacobian))
    M_inv = ca.DM(model.M_inv)
    G = Phi @ M_inv @ Phi.T
    b = Phi @ qd
    lam = -ca.solve(G, b)
    qd_plus = qd + M_inv @ (Phi.T @ lam)
    return {"G": G, "lambda": lam, "qd_plus": qd_plus, "T_c": -0.5 * ca.dot(lam, b),
            "n_body": Phi_b.shape[0]}


def impact_function(model: Model, strike: str, slope: float = 0.0, outputs=None,
                    graph: str = "SX") -> ca.Function:
    """CasADi Function of the touchdown state x (model.STATE, SI) -> every impact indicator.

    Outputs: T, T_c, T_a (J); qd_minus, qd_plus (natural coordinates, m/s); impulse
    ([t, n] per strike point, N s); impulse_total ([t, n]); mu_signed (total t / total n);
    mu_momentum_signed; dv_trunk, dv_com ([x, z] m/s; dv_trunk is zero for a model without a
    trunk); approach (normal velocity of each strike point, m/s, < 0 when it approaches);
    clearance (height of the other foot point above the ground, m); G (Phi_q M^-1 Phi_q^T).
    `outputs` keeps only the named ones (the generated code then holds only what they need).
    `graph`: "SX" (scalar expressions, fast to evaluate) or "MX" (matrix expressions with a
    linear-solver node, smaller graphs).
    """
    points = STRIKES[strike]
    t, n = ground_axes(slope)
    if graph not in GRAPHS:
        raise InputError(f"graph {graph!r}: expected one of {', '.join(GRAPHS)}")
    x = getattr(ca, graph).sym("x", len(STATE))
    q, qd = model.state(x, points[0])
    rows = model.contact_rows(points, slope, tangential=points[:1] if model.tangential else ())
    imp = projection(model, q, qd, rows)
    lam = imp["lambda"][imp["n_body"]:]
    if not model.tangential:  # the impact acts along the normal only
        lam = ca.vertcat(0, lam)
    if strike == "flat":
        total_t, normals = lam[0], ca.vertcat(lam[1], lam[2])
        total_n = normals[0] + normals[1]
        impulse = ca.vertcat(total_t * normals[0] / total_n, normals[0],
                             total_t * normals[1] / total_n, normals[1])
    else:
        total_t, total_n = lam[0], lam[1]
        impulse = lam
    dqd = imp["qd_plus"] - qd
    momentum = ca.DM(model.momentum_matrix) @ dqd
    trunk = ca.DM(model.com_matrix(model.trunk)) @ dqd if model.trunk else ca.DM.zeros(2)
    other = "heel" if points == ("forefoot",) else "forefoot"
    indicators = {
        "T": model.kinetic_energy(qd),
        "T_c": imp["T_c"],
        "T_a": model.kinetic_energy(imp["qd_plus"]),
        "qd_minus": qd,
        "qd_plus": imp["qd_plus"],
        "impulse": impulse,
        "impulse_total": ca.vertcat(total_t, total_n),
        "mu_signed": total_t / total_n,
        "mu_momentum_signed": ca.dot(momentum, t) / ca.dot(momentum, n),
        "dv_trunk": trunk,
        "dv_com": momentum / model.mass,
        "approach": ca.vertcat(*[ca.dot(qd[model.cols(p)], n) for p in points]),
        "clearance": ca.dot(landmarks(x, model.body, points[0])[other][0], n),
        "G": imp["G"],
    }
    if outputs is not None:
        unknown = set(outputs) - set(indicators)
        if unknown:
            raise InputError(f"unknown impact outputs {sorted(unknown)}: expected {list(indicators)}")
        indicators = {k: indicators[k] for k in outputs}
    return ca.Function(f"impact_{strike}", [x], list(indicators.values()), ["x"], list(indicators))


@dataclass(frozen=True)
class ImpactResult:
    """Indicators of one foot strike. SI units; impulses are the ground's on the foot."""

    strike: str
    T: float  # J, kinetic energy before the impact
    T_c: float  # J, constrained motion space kinetic energy: absorbed by the impact
    T_a: float  # J, kinetic energy after the impact
    impulse: dict[str, tuple[float, float]]  # contact -> (tangential, normal), N s
    impulse_determined: dict[str, tuple[bool, bool]]  # False where rigid-body impact leaves it open
    impulse_total: tuple[float, float]  # (tangential, normal), N s
    mu_c: float | None  # critical friction coefficient |total t| / total n; None if n <= 0
    mu_c_momentum: float | None  # the same from the linear-momentum change (a check)
    dv_trunk: tuple[float, float] | None  # m/s, velocity change of the trunk's centre of mass
    dv_com: tuple[float, float]  # m/s, velocity change of the whole-body centre of mass
    qd_minus: np.ndarray  # natural-coordinate velocities before, m/s
    qd_plus: np.ndarray  # and after
    condition: float  # condition number of Phi_q M^-1 Phi_q^T
    friction: float  # the ground's friction coefficient used for `valid`
    valid: bool  # every assumption of the impact model holds
    warnings: tuple[str, ...]

    def to_dict(self) -> dict:
        """JSON-ready dictionary (lists instead of arrays)."""
        out = asdict(self)
        for key in ("qd_minus", "qd_plus"):
            out[key] = [float(v) for v in out[key]]
        out["impulse"] = {k: list(v) for k, v in self.impulse.items()}
        out["impulse_determined"] = {k: list(v) for k, v in self.impulse_determined.items()}
        for key in ("impulse_total", "dv_com", "dv_trunk"):
            out[key] = None if out[key] is None else list(out[key])
        out["warnings"] = list(self.warnings)
        return out


class Impact:
    """The impact map of one model, strike and ground, numeric and symbolic.

    `Impact(model, "heel").function` is the CasADi Function (differentiable);
    `Impact(...)(x)` evaluates it and checks every assumption, returning an ImpactResult.
    """

    def __init__(self, model: Model, strike: str, slope: float = 0.0, friction: float = 0.8,
                 compiled: bool = False, graph: str = "SX"):
        if strike not in STRIKES:
            raise InputError(f"unknown strike {strike!r}: expected one of {', '.join(STRIKES)}")
        self.model, self.strike, self.slope, self.friction = model, strike, slope, friction
        self.compiled, self.graph = compiled, graph
        self.function = impact_function(model, strike, slope, graph=graph)
        self._compiled = Compiled(self.function) if compiled else None

    def evaluate(self, x) -> dict[str, np.ndarray]:
        """Every output of `function` at x, unchecked (the fast path; compiled if asked)."""
        if self._compiled is not None:
            return self._compiled(x)
        return {k: v.full() for k, v in zip(self.function.name_out(), self.function.call([x]))}

    def __call__(self, x) -> ImpactResult:
        x = np.asarray(x, float).reshape(-1)
        if x.shape != (len(STATE),) or not np.all(np.isfinite(x)):
            raise InputError(f"the touchdown state needs {len(STATE)} finite values {STATE}, got {x}")
        raw = self.evaluate(x)
        condition = float(np.linalg.cond(raw.pop("G")))
        out = {k: np.asarray(v, float).ravel() for k, v in raw.items()}
        out.update({k: float(v[0]) for k, v in out.items() if v.size == 1})
        points = STRIKES[self.strike]
        if not condition < CONDITION_LIMIT:
            raise InputError(f"{self.strike} strike: the constraint Jacobian is singular at this "
                             f"posture (condition number {condition:.1e} of Phi_q M^-1 Phi_q^T)")
        warnings = []
        if self.strike == "flat" and abs(out["clearance"]) > 1e-6:
            raise InputError(f"flat strike needs the sole on the ground: the forefoot is "
                             f"{out['clearance'] * 1e3:.1f} mm above it (adjust the ankle angle)")
        if self.strike != "flat" and out["clearance"] < 0:
            other = "heel" if points == ("forefoot",) else "forefoot"
            warnings.append(f"the {other} is {-out['clearance'] * 1e3:.1f} mm below the ground")
        for p, v in zip(points, np.atleast_1d(out["approach"])):
            if v >= 0:
                warnings.append(f"the {p} does not approach the ground (normal velocity {v:.3f} m/s)")
        impulse = out["impulse"].reshape(-1, 2)
        scale = max(float(np.max(np.abs(impulse))), 1e-300)
        for p, (_, normal) in zip(points, impulse):
            if normal < -RTOL * scale:
                warnings.append(f"the ground pulls the {p} (normal impulse {normal:.4f} N s)")
        total_t, total_n = out["impulse_total"]
        pushes = total_n > RTOL * max(abs(total_t), 1e-300)
        mu_c = abs(out["mu_signed"]) if pushes else None
        mu_c_momentum = abs(out["mu_momentum_signed"]) if pushes else None
        if not pushes:
            warnings.append("mu_c is undefined: the ground does not push (total normal impulse "
                            f"{total_n:.3g} N s)")
        elif mu_c > self.friction * (1 + RTOL):
            warnings.append(f"the foot slips: mu_c {mu_c:.3f} exceeds the friction {self.friction:g}")
        if self.strike == "flat":
            warnings.append("flat foot: the tangential split between heel and forefoot is not "
                            "determined (shown in proportion to the normal impulses; the total is exact)")
        determined = {p: (self.strike != "flat", True) for p in points}
        return ImpactResult(
            strike=self.strike,
            T=out["T"], T_c=out["T_c"], T_a=out["T_a"],
            impulse={p: (float(t), float(n)) for p, (t, n) in zip(points, impulse)},
            impulse_determined=determined,
            impulse_total=tuple(float(v) for v in out["impulse_total"]),
            mu_c=mu_c, mu_c_momentum=mu_c_momentum,
            dv_trunk=tuple(float(v) for v in out["dv_trunk"]) if self.model.trunk else None,
            dv_com=tuple(float(v) for v in out["dv_com"]),
            qd_minus=out["qd_minus"], qd_plus=out["qd_plus"],
            condition=condition, friction=self.friction,
            valid=not any(w for w in warnings if not w.startswith("flat foot")),
            warnings=tuple(warnings))


def angular_momentum_impact(model: Model, q, qd, point: str) -> np.ndarray:
    """Post-impact velocities by conservation of angular momentum (seed eq. 3), numeric.

    For a single contact point C held at the impact: C's velocity becomes zero, the whole
    system's angular momentum about C is conserved, and so is, about each hinge J between C
    and the free end, that of the bodies beyond J (free hinges transmit no impulsive moment).
    Uses the segments' mass, centre of mass and inertia directly, not the mass matrix.
    """
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    Phi_b = np.asarray(model.constraint_jacobian(q), float)
    groups = _point_groups(model)
    contact_body = next(b for b in model.bodies if point in b.base + b.fixed)
    rows = [Phi_b, model.scatter(np.eye(2), [point])]
    rows.append(_momentum_row(model, q, q[model.cols(point)], model.segments))
    for joint, far in _hinges(model, groups, contact_body.segment):
        rows.append(_momentum_row(model, q, q[model.cols(joint)], far))
    A = np.vstack(rows)
    rhs = np.concatenate([np.zeros(Phi_b.shape[0] + 2), A[Phi_b.shape[0] + 2:] @ qd])
    if np.linalg.matrix_rank(A) < model.n:
        raise InputError("angular-momentum map: the hinges do not determine the motion "
                         "(this method covers open chains with one contact point)")
    return np.linalg.solve(A, rhs)


def _cross_row(arm) -> np.ndarray:
    """Row r such that r @ v = arm x v (planar cross product)."""
    return np.array([[-arm[1], arm[0]]])


def _momentum_row(model: Model, q, origin, segments) -> np.ndarray:
    """(1 x n) map from q' to the angular momentum of `segments` about `origin` (kg m^2/s)."""
    row = np.zeros((1, model.n))
    for seg in segments:
        s = model.body[seg]
        C = model.com_matrix(seg)
        row += s.mass * _cross_row(C @ q - origin) @ C
        body = next((b for b in model.bodies if b.segment == seg), None)
        if body is not None and s.inertia_com > 0:
            ri, rj = (q[model.cols(p)] for p in body.base)
            d = rj - ri
            P = model.scatter(np.hstack([-np.eye(2), np.eye(2)]), body.base)  # q' -> r_j' - r_i'
            row += s.inertia_com / (d @ d) * _cross_row(d) @ P
    return row


def _point_groups(model: Model) -> dict[str, str]:
    """Representative point of each point, merging coincident points (union-find)."""
    parent = {p.name: p.name for p in model.points}

    def find(p):
        while parent[p] != p:
            p = parent[p]
        return p

    for a, c in model.coincident:
        parent[find(a)] = find(c)
    return {p: find(p) for p in parent}


def _hinges(model: Model, groups, contact_segment):
    """(hinge point, segments of one branch beyond it seen from the contact), for every
    branch of every hinge: a chain has one branch beyond each hinge, a tree may have more
    (trunk and swing leg beyond the stance hip)."""
    touches = {b.segment: {groups[p] for p in b.base + b.fixed} for b in model.bodies}
    touches.update({pm.segment: {groups[pm.point]} for pm in model.point_masses})
    rigid = {b.segment for b in model.bodies}
    hinges = [g for g in set(groups.values())
              if sum(g in touches[s] for s in rigid) >= 2]

    def component(start, g, allowed):
        reached, frontier = {start}, [start]
        while frontier:
            seg = frontier.pop()
            for other in allowed:
                if other not in reached and (touches[seg] & touches[other]) - {g}:
                    reached.add(other)
                    frontier.append(other)
        return reached

    for g in sorted(hinges):
        near = component(contact_segment, g, touches)
        rest = [s for s in touches if s not in near]
        while rest:
            branch = component(rest[0], g, rest)
            if branch & rigid:  # a lone point mass at the hinge has no moment about it
                yield g, sorted(branch)
            rest = [s for s in rest if s not in branch]
