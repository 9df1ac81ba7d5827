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

import copy
import math
from dataclasses import asdict, dataclass, field
from enum import Enum
from typing import Any

import casadi as ca
import numpy as np

from . import contact
from .compiled import Compiled
from .errors import InputError
from .model import STATE, STRIKES, Model, check_state, ground_axes, landmarks, xy

# Ill-conditioned beyond this: results lose more than 10 of 16 digits.
CONDITION_LIMIT = 1e10
GRAPHS = ("SX", "MX")
# Relative tolerance of the validity checks: an optimum on a constraint (mu_c = friction,
# normal impulse = 0) is valid, not a rounding error away from invalid.
RTOL = 1e-6
LEVEL_TOL_M = 1e-9  # m: the other point this far below the ground is on it (a sole put level, round-off)
INPUTS = ("x", "friction", "slope")  # impact_function's inputs


def projection(model: Model, q, qd, contact_jacobian):
    """The projection impact map at (q, q'-) for the given contact rows (SX/MX in and out)."""
    Phi_b = model.constraint_jacobian(q)
    Phi = ca.vertcat(Phi_b, contact_jacobian)
    M_inv = ca.DM(model.M_inv)
    G = Phi @ M_inv @ Phi.T
    b = Phi @ qd
    lam = -ca.solve(G, b)
    qd_plus = qd + M_inv @ (Phi.T @ lam)
    return {"G": G, "lambda": lam, "qd_plus": qd_plus, "T_c": -0.5 * ca.dot(lam, b),
            "n_body": Phi_b.shape[0]}


def impact_function(model: Model, strike: str, outputs=None, graph: str = "SX",
                    law: str = "no-slip") -> ca.Function:
    """CasADi Function (x, friction, slope) -> every impact indicator: x the touchdown state
    (model.STATE, SI), friction the ground's Coulomb coefficient, slope the ground's angle
    (rad, positive uphill). One graph serves every ground; an input left out is NaN (every
    caller says which ground it uses).

    Outputs under the contact law `law` (contact.LAWS; Coulomb with `friction`): T, T_c, T_a
    (J); qd_minus, qd_plus (natural coordinates, m/s); impulse ([t, n] per strike point, N s);
    impulse_total ([t, n]); mu_signed (total t / total n); mu_momentum_signed (the same from
    the linear-momentum change, eq. 8's check); dv_trunk, dv_com ([x, z] m/s; dv_trunk is zero
    for a model without a trunk); slip (tangential velocity of the strike point after the
    impact, m/s; zero under no-slip). Law-independent: approach (normal velocity of each
    strike point, m/s, < 0 when it approaches); clearance (height of the other foot point, m);
    G (Phi_q M^-1 Phi_q^T of the no-slip contact); mu_posture (eq. 7, signed; zero for a flat
    strike, where it is not defined); mode (Coulomb's contact.MODES, -1 under other laws).
    For every law L of contact.LAWS also T_c_L, impulse_L, slip_L, dv_trunk_L, dv_com_L, and
    mode_coulomb. The strike point's contact space (NaN for a flat strike or a normal-only
    model): W_c (2 x 2, m/s per N s), v_contact (its pre-impact [t, n] velocity, m/s), and
    dv_trunk_per_impulse, dv_com_per_impulse (2 x 2: dv = D p). `outputs` keeps only the
    named ones (the generated code then holds only what they need). `graph`: "SX" (scalar
    expressions, fast to evaluate) or "MX" (matrix expressions with a linear-solver node,
    smaller graphs).

    Coulomb at a flat strike: heel and forefoot share one tangential motion and have no
    single normal-impulse clock, so the impact takes the velocity-level law
    (contact.velocity_level), which equals Darboux-Keller for one point outside a reversed
    slide; its mode is stick or slide.
    """
    if graph not in GRAPHS:
        raise InputError(f"graph {graph!r}: expected one of {', '.join(GRAPHS)}")
    if law not in contact.LAWS:
        raise InputError(f"contact law {law!r}: expected one of {', '.join(contact.LAWS)}")
    sym = getattr(ca, graph)
    x, friction, slope = sym.sym("x", len(STATE)), sym.sym("friction"), sym.sym("slope")
    indicators = _indicators(model, strike, law, x, friction, slope)
    if outputs is not None:
        unknown = set(outputs) - set(indicators)
        if unknown:
            raise InputError(f"unknown impact outputs {sorted(unknown)}: expected {list(indicators)}")
        indicators = {k: indicators[k] for k in outputs}
    return ca.Function(f"impact_{strike}", [x, friction, slope], list(indicators.values()),
                       list(INPUTS), list(indicators), {"default_in": [0.0, math.nan, math.nan]})


def on_ground(function: ca.Function, friction: float, slope: float) -> ca.Function:
    """`function` (impact_function's) as a Function of the touchdown state x alone on a fixed
    ground (friction, slope rad): for mapped and compiled batches that take x only."""
    check_ground(friction, slope)
    x = ca.SX.sym("x", function.size1_in(0)) if function.is_a("SXFunction") else \
        ca.MX.sym("x", function.size1_in(0))
    return ca.Function(function.name(), [x], function.call([x, friction, slope]), ["x"],
                       function.name_out())


def _laws(model: Model, strike: str, q, qd, imp, friction, slope) -> tuple[dict, dict, ca.SX]:
    """Each contact law's (impulse, qd_plus, T_c, slip, mode) of the strike at (q, qd), with
    `imp` its no-slip projection; the strike point's contact space (W_c, v_contact and the
    velocity changes per impulse: NaN for a flat strike or a normal-only model) and the
    posture's friction ratio W_c[0,1] / W_c[0,0] (mu_posture; 0 without a tangential row)."""
    points = STRIKES[strike]
    t, _ = ground_axes(slope)
    lam = imp["lambda"][imp["n_body"]:]
    if not model.tangential:  # normal only: the guide holds the rest (see _momentum_impulse)
        lam = ca.vertcat(0, lam)
    no_slip_impulse = _split(lam) if strike == "flat" else lam
    # the contact laws, in impulse space of the strike points' rows (contact.py)
    W = contact.admissible_inverse_inertia(ca.DM(model.M_inv), model.constraint_jacobian(q))
    normal_rows = model.contact_rows(points, slope, tangential=())
    laws = {"no-slip": (no_slip_impulse, imp["qd_plus"], imp["T_c"],
                        _slip(model, points, imp["qd_plus"], t), ca.DM(-1))}
    W_n, v_n = normal_rows @ W @ normal_rows.T, normal_rows @ qd
    p_n = -ca.solve(W_n, v_n)
    qd_frictionless = qd + W @ normal_rows.T @ p_n
    laws["frictionless"] = (ca.vertcat(*[ca.vertcat(0, p_n[k]) for k in range(len(points))]),
                            qd_frictionless, contact.absorbed(W_n, v_n, p_n),
                            _slip(model, points, qd_frictionless, t), ca.DM(-1))
    momentum_matrix = ca.DM(model.momentum_matrix)
    trunk_matrix = ca.DM(model.com_matrix(model.trunk)) if model.trunk else ca.DM.zeros(2, model.n)
    # the strike point's contact space, for a law built outside (an NLP's fixed Coulomb mode)
    space = {"W_c": ca.DM.nan(2, 2), "v_contact": ca.DM.nan(2, 1),
             "dv_trunk_per_impulse": ca.DM.nan(2, 2), "dv_com_per_impulse": ca.DM.nan(2, 2)}
    if strike != "flat" and model.tangential:
        C = model.contact_rows(points, slope)
        W_c, v0 = C @ W @ C.T, C @ qd
        space = {"W_c": W_c, "v_contact": v0, "dv_trunk_per_impulse": trunk_matrix @ W @ C.T,
                 "dv_com_per_impulse": momentum_matrix @ W @ C.T / model.mass}
        p, mode, slip = contact.coulomb(W_c, v0, friction)
        laws["coulomb"] = (p, qd + W @ C.T @ p, contact.absorbed(W_c, v0, p), slip, mode)
        mu_posture = W_c[0, 1] / W_c[0, 0]
    elif strike != "flat":  # normal only: every law is the frictionless one
        laws["coulomb"] = laws["frictionless"]
        mu_posture = ca.DM(0)
    else:  # two contacts of one rigid foot: the velocity-level law
        C = model.contact_rows(points, slope, tangential=points[:1])
        W_c, v0 = C @ W @ C.T, C @ qd
        p, mode, slip = contact.velocity_level(W_c, v0, friction)
        laws["coulomb"] = (_split(p), qd + W @ C.T @ p, contact.absorbed(W_c, v0, p), slip, mode)
        mu_posture = ca.DM(0)
    return laws, space, mu_posture


def _indicators(model: Model, strike: str, law: str, x, friction, slope) -> dict:
    """Every output of impact_function as expressions of (x, friction, slope): each law's
    (`_laws`) T_c, impulse, slip and velocity changes, and the scene's law's in full."""
    points = STRIKES[strike]
    t, n = ground_axes(slope)
    q, qd = model.state(x, points[0])
    rows = model.contact_rows(points, slope, tangential=points[:1] if model.tangential else ())
    imp = projection(model, q, qd, rows)
    laws, space, mu_posture = _laws(model, strike, q, qd, imp, friction, slope)
    momentum_matrix = ca.DM(model.momentum_matrix)
    trunk_matrix = ca.DM(model.com_matrix(model.trunk)) if model.trunk else ca.DM.zeros(2, model.n)
    per_law = {}
    for name, (impulse, qd_plus, T_c, slip, mode) in laws.items():
        dqd = qd_plus - qd
        momentum = momentum_matrix @ dqd
        if not model.tangential:
            impulse = _momentum_impulse(momentum, t, n)
        per_law[name] = {"T_c": T_c, "qd_plus": qd_plus, "impulse": impulse, "slip": slip,
                         "mode": mode, "momentum": momentum, "dv_trunk": trunk_matrix @ dqd,
                         "dv_com": momentum / model.mass}
    chosen = per_law[law]
    impulse = chosen["impulse"]
    total_t = sum(impulse[2 * k] for k in range(len(points)))
    total_n = sum(impulse[2 * k + 1] for k in range(len(points)))
    other = "heel" if points == ("forefoot",) else "forefoot"
    indicators = {
        "T": model.kinetic_energy(qd),
        "T_c": chosen["T_c"],
        "T_a": model.kinetic_energy(chosen["qd_plus"]),
        "qd_minus": qd,
        "qd_plus": chosen["qd_plus"],
        "impulse": impulse,
        "impulse_total": ca.vertcat(total_t, total_n),
        "mu_signed": total_t / total_n,
        "mu_momentum_signed": ca.dot(chosen["momentum"], t) / ca.dot(chosen["momentum"], n),
        "dv_trunk": chosen["dv_trunk"],
        "dv_com": chosen["dv_com"],
        "slip": chosen["slip"],
        "mode": chosen["mode"],
        "approach": ca.vertcat(*[ca.dot(qd[model.cols(p)], n) for p in points]),
        "clearance": ca.dot(landmarks(x, model.body, points[0])[other][0], n),
        "G": imp["G"],
        "mu_posture": mu_posture,
        **space,
    }
    for name, values in per_law.items():
        key = name.replace("-", "_")
        for item in ("T_c", "impulse", "slip", "dv_trunk", "dv_com"):
            indicators[f"{item}_{key}"] = values[item]
    indicators["mode_coulomb"] = per_law["coulomb"]["mode"]
    return indicators


def _split(impulse):
    """A flat foot's impulse [t, n_heel, n_forefoot] as [t, n] per point, the tangential
    impulse shared in proportion to the normal ones (the module docstring)."""
    total_t, n_heel, n_fore = impulse[0], impulse[1], impulse[2]
    total_n = n_heel + n_fore
    return ca.vertcat(total_t * n_heel / total_n, n_heel, total_t * n_fore / total_n, n_fore)


def _slip(model: Model, points, qd_plus, t):
    """Tangential velocity (m/s) of the first strike point after the impact."""
    return ca.dot(qd_plus[model.cols(points[0])], t)


def _momentum_impulse(momentum, t, n):
    """The ground's impulse [t, n] (N s) on a model whose contact holds the normal only (the
    effective mass, guided vertically): the whole linear-momentum change, since the guide
    stands for the rest of the runner, not for the ground. On a slope it is not normal to the
    ground: a vertical impulse needs |t| / n = tan(slope)."""
    return ca.vertcat(ca.dot(momentum, t), ca.dot(momentum, n))


class Check(str, Enum):  # noqa: UP042 - not StrEnum: str(Check.X) would change
    """What a checked impact found (ImpactResult.checks, one per warning)."""

    BELOW_GROUND = "below_ground"  # the other foot point is below the ground
    NO_APPROACH = "no_approach"  # a strike point does not approach the ground
    PULL = "pull"  # the ground would have to pull a strike point
    NO_PUSH = "no_push"  # the total normal impulse does not push: mu_c undefined
    SLIP = "slip"  # no-slip needs more than the ground's friction
    FLAT_SPLIT = "flat_split"  # a flat foot's tangential split is not determined (information)


INFORMATION = frozenset({Check.FLAT_SPLIT})  # checks that do not make an impact invalid
MAX_SLOPE = math.radians(60.0)  # rad: the steepest ground a scene takes (ground.slope_deg)


def check_ground(friction: float, slope: float) -> None:
    """Refuse a ground the impact cannot take: friction in (0, inf), |slope| <= 60 deg (each
    a real number: a string or None is refused too)."""
    for name, value in (("friction", friction), ("slope", slope)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
            raise InputError(f"{name} = {value!r}: must be a number")
    if not (math.isfinite(friction) and friction > 0):
        raise InputError(f"friction = {friction!r}: must be a finite number > 0")
    if not abs(slope) <= MAX_SLOPE:
        raise InputError(f"slope = {slope!r} rad: must lie in [-60, 60] deg")


@dataclass(frozen=True)
class LawResult:
    """One contact law's indicators at an impact (SI; impulses the ground's on the foot)."""

    T_c: float  # J
    impulse: dict[str, tuple[float, float]]  # contact -> (tangential, normal), N s
    mode: str | None  # Coulomb's mode (contact.MODES); None for the other laws
    slip_velocity: float  # m/s, the strike point's tangential velocity after the impact
    dv_trunk: tuple[float, float] | None  # m/s; None without a trunk
    dv_com: tuple[float, float]  # m/s
    valid: bool  # the shared checks hold, the ground pushes, (no-slip) the friction suffices

    def to_dict(self) -> dict:
        """JSON-ready dictionary (lists instead of tuples)."""
        out = asdict(self)
        out["impulse"] = {k: list(v) for k, v in self.impulse.items()}
        for key in ("dv_trunk", "dv_com"):
            out[key] = None if out[key] is None else list(out[key])
        return out


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
    friction: float  # the ground's friction coefficient of this impact
    slope: float  # rad, the ground's slope of this impact (positive uphill)
    valid: bool  # every assumption of the impact model holds
    warnings: tuple[str, ...]
    checks: tuple[Check, ...]  # what each warning is (Check), in the same order
    law: str  # the contact law of the fields above (contact.LAWS)
    slip_velocity: float  # m/s, tangential velocity of the strike point after the impact
    mode: str | None  # Coulomb's mode (slide, stick, reversed slide); None otherwise
    mu_c_posture: float | None  # eq. 7, |W_tn / W_tt|; None for a flat strike
    contact_laws: dict[str, LawResult] = field(default_factory=dict)  # every law's indicators

    def to_dict(self) -> dict:
        """JSON-ready dictionary (lists instead of arrays)."""
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        for key in ("qd_minus", "qd_plus"):
            out[key] = [float(v) for v in out[key]]
        out["impulse"] = {k: list(v) for k, v in self.impulse.items()}
        out["impulse_determined"] = {k: list(v) for k, v in self.impulse_determined.items()}
        for key in ("impulse_total", "dv_com", "dv_trunk"):
            out[key] = None if out[key] is None else list(out[key])
        out["warnings"] = list(self.warnings)
        out["checks"] = [c.value for c in self.checks]
        out["contact_laws"] = {k: v.to_dict() for k, v in self.contact_laws.items()}
        return out


class Impact:
    """The impact map of one model, strike and contact law, numeric and symbolic, on a ground.

    `Impact(model, "heel", slope, friction).function` is the CasADi Function of (x, friction,
    slope) (differentiable; one graph for every ground); `Impact(...)(x)` evaluates it on the
    Impact's ground and checks every assumption, returning an ImpactResult;
    `impact.at(friction, slope)` is the same map (the same graph) on another ground.
    """

    def __init__(self, model: Model, strike: str, slope: float, friction: float,
                 compiled: bool = False, graph: str = "SX", law: str = "no-slip"):
        if strike not in STRIKES:
            raise InputError(f"unknown strike {strike!r}: expected one of {', '.join(STRIKES)}")
        check_ground(friction, slope)
        self.model, self.strike, self.slope, self.friction = model, strike, slope, friction
        self.compiled, self.graph, self.law = compiled, graph, law
        self.function = impact_function(model, strike, graph=graph, law=law)
        self._compiled = Compiled(self.function) if compiled else None

    def at(self, friction: float, slope: float) -> Impact:
        """The same impact map (its graph and compiled code shared) on another ground."""
        check_ground(friction, slope)
        other = copy.copy(self)
        other.friction, other.slope = friction, slope
        return other

    def evaluate(self, x) -> dict[str, np.ndarray]:
        """Every output of `function` at x on the Impact's ground, unchecked (the fast path;
        compiled if asked)."""
        if self._compiled is not None:
            return self._compiled(x, self.friction, self.slope)
        return {k: v.full() for k, v in zip(self.function.name_out(),
                                            self.function.call([x, self.friction, self.slope]))}

    def __call__(self, x) -> ImpactResult:
        """The checked impact at touchdown state x (model.STATE, SI)."""
        x = check_state(x)
        raw = self.evaluate(x)
        condition = float(np.linalg.cond(raw.pop("G")))
        out: dict[str, Any] = {k: np.asarray(v, float).ravel() for k, v in raw.items()}  # 1-D, or float
        out.update({k: float(v[0]) for k, v in out.items() if v.size == 1})
        points = STRIKES[self.strike]
        if not condition < CONDITION_LIMIT:
            raise InputError(f"{self.strike} strike: the constraint Jacobian is singular at this "
                             f"posture (condition number {condition:.1e} of Phi_q M^-1 Phi_q^T)")
        if self.strike == "flat" and abs(out["clearance"]) > 1e-6:
            raise InputError(f"flat strike needs the sole on the ground: the forefoot is "
                             f"{out['clearance'] * 1e3:.1f} mm above it (adjust the ankle angle)")
        shared = self._shared_checks(out, points)
        found = shared + self._pull_warnings(points, out["impulse"].reshape(-1, 2))
        total_t, total_n = out["impulse_total"]
        pushes = total_n > RTOL * max(abs(total_t), 1e-300)
        mu_c = abs(out["mu_signed"]) if pushes else None
        if not pushes:
            found.append((Check.NO_PUSH, "mu_c is undefined: the ground does not push (total "
                                         f"normal impulse {total_n:.3g} N s)"))
        elif self.law == "no-slip" and mu_c is not None and mu_c > self.friction * (1 + RTOL):
            found.append((Check.SLIP, f"the foot slips: mu_c {mu_c:.3f} exceeds the friction "
                                      f"{self.friction:g}"))
        if self.strike == "flat" and self.law != "frictionless":
            found.append((Check.FLAT_SPLIT, "flat foot: the tangential split between heel and "
                                            "forefoot is not determined (shown in proportion to "
                                            "the normal impulses; the total is exact)"))
        laws = {law: self._law_result(out, law, points, not shared) for law in contact.LAWS}
        chosen = laws[self.law]
        return ImpactResult(
            strike=self.strike, T=out["T"], T_c=out["T_c"], T_a=out["T_a"],
            impulse=chosen.impulse,
            impulse_determined={p: (self.strike != "flat" or self.law == "frictionless", True)
                                for p in points},
            impulse_total=(float(total_t), float(total_n)),
            mu_c=mu_c, mu_c_momentum=abs(out["mu_momentum_signed"]) if pushes else None,
            dv_trunk=xy(out["dv_trunk"]) if self.model.trunk else None,
            dv_com=xy(out["dv_com"]),
            qd_minus=out["qd_minus"], qd_plus=out["qd_plus"],
            condition=condition, friction=self.friction, slope=self.slope,
            valid=not any(c not in INFORMATION for c, _ in found),
            warnings=tuple(w for _, w in found), checks=tuple(c for c, _ in found),
            law=self.law, slip_velocity=out["slip"], mode=contact.MODES.get(round(out["mode"])),
            mu_c_posture=abs(out["mu_posture"]) if self.strike != "flat" else None,
            contact_laws=laws)

    def _shared_checks(self, out, points) -> list[tuple[Check, str]]:
        """The checks every law shares: the other point above the ground, each strike point
        approaching it."""
        found = []
        if self.strike != "flat" and out["clearance"] < -LEVEL_TOL_M:
            other = "heel" if points == ("forefoot",) else "forefoot"
            found.append((Check.BELOW_GROUND,
                          f"the {other} is {-out['clearance'] * 1e3:.1f} mm below the ground"))
        for p, v in zip(points, np.atleast_1d(out["approach"])):
            if v >= 0:
                found.append((Check.NO_APPROACH,
                              f"the {p} does not approach the ground (normal velocity {v:.3f} m/s)"))
        return found

    def _pull_warnings(self, points, impulse) -> list[tuple[Check, str]]:
        """A check for every strike point the ground would have to pull."""
        scale = max(float(np.max(np.abs(impulse))), 1e-300)
        return [(Check.PULL, f"the ground pulls the {p} (normal impulse {normal:.4f} N s)")
                for p, (_, normal) in zip(points, impulse) if normal < -RTOL * scale]

    def _law_result(self, out, law, points, shared_hold: bool) -> LawResult:
        """One law's indicators; valid: the shared checks hold, the ground pushes, and
        (no-slip) the friction suffices."""
        key = law.replace("-", "_")
        impulse = np.asarray(out[f"impulse_{key}"], float).reshape(-1, 2)
        valid = shared_hold and not self._pull_warnings(points, impulse)
        t, n = impulse.sum(axis=0)
        if law == "no-slip":
            valid = valid and n > 0 and abs(t) <= self.friction * n * (1 + RTOL)
        mode = contact.MODES.get(round(out["mode_coulomb"])) if law == "coulomb" else None
        return LawResult(
            T_c=float(out[f"T_c_{key}"]),
            impulse={p: (float(a), float(b)) for p, (a, b) in zip(points, impulse)},
            mode=mode if self.model.tangential else None,
            slip_velocity=float(out[f"slip_{key}"]),
            dv_trunk=xy(out[f"dv_trunk_{key}"]) if self.model.trunk else None,
            dv_com=xy(out[f"dv_com_{key}"]),
            valid=bool(valid))
