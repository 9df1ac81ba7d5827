"""The landing: the impact sequence of a foot, a state machine on dynamics, integrators, events.

This is the event-driven simulation; the differentiable two-impact landing the posture NLP
calls (no-slip, fixed steps) is landing_function.py, built on the same LandingModel.

Between impacts the model follows the finite motion of dynamics.py (`Dynamics.motion`: body
constraints, locked joints, the contact set held or sliding, joint springs, dampers and
moments), integrated by integrators.py. The contact law (contact.LAWS) decides what the foot
points do:
- no-slip: held from the impact on (the ground's friction is only checked: `slip_at`);
- frictionless: every point slides with mu = 0;
- coulomb: the impact's mode (contact.coulomb, one point; contact.velocity_level, two)
  decides whether the point leaves it stuck or sliding; a sliding point sticks when its
  tangential velocity reaches zero (an event), a stuck point slides when holding it would
  need |f_t| > mu f_n, in the direction -sign(f_t).

Events: a foot point reaching the ground (an impact, with the new contact set), a contact
whose normal force would pull (released: a contact can only push), a sliding point coming to
rest. The landing ends (`Ended`) when heel and forefoot are both down, at `t_max`, or after
MAX_SWITCHES contact changes (chatter).

Energy bookkeeping: T + V_gravity + V_springs + E_joints (the work the dampers and the
moments take from the body) + E_friction + sum of T_c stays equal to its value before the
first impact, to the integration tolerance; `energy_error` is its largest drift. A landing
whose balance drifts by more than DIVERGED of its touchdown kinetic energy, or whose state
stops being finite, raises `Diverged`: it is not a result.

Integrators (integrators.INTEGRATORS): "adaptive" (Dormand & Prince 1980, 5th order with an
embedded 4th-order error estimate; the step shrinks where the joints are stiff, so stiff
dampers stay stable, and grows up to dt between events), or the fixed-step "rk4" and
"midpoint".
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import casadi as ca
import numpy as np

from . import contact, limits
from .compiled import Compiled
from .dynamics import FEET, FREE, GRAVITY, Dynamics, Joints
from .errors import InputError
from .impact import check_ground
from .integrators import DEFAULT_INTEGRATOR, INTEGRATORS, grow, locate, shrink
from .integrators import step as integrator_step
from .limits import Range
from .model import STRIKES, Model, check_state, xy

DIVERGED = 1e-4  # energy-balance drift, relative to the touchdown kinetic energy, that is a divergence
# A finished landing's numerical checks (beyond them it is not valid, Landing.unsound): the body
# and contact constraints within DRIFT_M (10 um, a hundredth of a marker's precision; the
# adaptive integrator keeps them within 1e-10 m, rk4 within 2e-6 m up to dt 5 ms, midpoint
# drifts 1.4e-5 m at dt 2 ms on landing_heel, issue 37), and the energy balance within BUDGET of
# the energy the impacts absorbed (the balance's error bounds how much of T_c_total is the
# integrator's, not the body's; 1 % is below the 6-20 % by which the segment rates' filter
# moves T_c, design.md section 6).
DRIFT_M = 1e-5
BUDGET = 0.01
SINK = 1e-7  # m: how far below the ground a point let go where it stood strikes again
MIN_STEP = 1e-9  # s: an adaptive step shorter than this is a divergence
MAX_SWITCHES = 50  # contact changes (releases, stick-slip) before a landing counts as chatter
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

class Ended(enum.StrEnum):
    """How a landing ended; the value is the text reports show (a str: JSON and CSV keep it)."""

    BOTH_DOWN = "heel and forefoot both down"
    DURATION = "duration reached"
    CHATTER = f"contact chatter: more than {MAX_SWITCHES} contact changes"
    # the same under the no-slip law, with what it means there
    HELD_CHATTER = (f"contact chatter: more than {MAX_SWITCHES} contact changes (held, the ground "
                    "would pull the point; let go, it sinks: the no-slip law has no motion here, "
                    "\"coulomb\" may)")


class Diverged(RuntimeError):
    """The landing's integration broke its energy balance or left the finite numbers: the
    message says when, by how much, and what to change."""





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
    ended: Ended  # why the simulation stopped
    warnings: list[str]

    def to_dict(self) -> dict:
        return {"impacts": [{"time": e.time, "contact": e.contact, "active": list(e.active),
                             "T_c": e.T_c, "dv_trunk": list(e.dv_trunk) if e.dv_trunk else None,
                             "impulse": list(e.impulse), "mu_c": e.mu_c, "mode": e.mode,
                             "slip": e.slip} for e in self.impacts],
                "law": self.law, "sliding_ms": self.sliding_time * 1e3,
                "T_c_total": self.T_c_total, "mu_c_max": self.mu_c_max,
                "no_slip_held": self.no_slip_held, "slip_at": self.slip_at,
                "valid": self.valid, "violations": self.violations, "unsound": self.unsound,
                "releases": [{"time": t, "contact": p, "normal_force": f} for t, p, f in self.releases],
                "energy_error": self.energy_error, "drift": self.drift, "ended": self.ended.value,
                "warnings": self.warnings,
                "duration": float(self.t[-1])}

    @property
    def violations(self) -> list[str]:
        """How the landing breaks its own assumptions (empty: valid): no-slip needing more
        friction than the ground has, a contact the ground would have pulled, a second point
        that never comes down within the duration, a numerical check that fails (`unsound`)."""
        found = [self.unsound] if self.unsound else []
        if not self.no_slip_held:
            found.append(f"no-slip needs friction {self.mu_c_max:.2f}")
        if self.releases:
            found.append(f"the ground would pull {len(self.releases)} time(s)")
        if self.ended is not Ended.BOTH_DOWN:
            found.append(self.ended.value.split(":")[0])
        return found

    @property
    def valid(self) -> bool:
        return not self.violations

    @property
    def unsound(self) -> str:
        """The numerical check that fails ("" when they hold): constraint drift within DRIFT_M,
        energy balance within BUDGET of T_c_total (at least 1 mJ)."""
        if not self.drift <= DRIFT_M:
            return f"constraint drift {self.drift:.2g} m beyond {DRIFT_M:g} m"
        if not self.energy_error <= BUDGET * max(self.T_c_total, 1e-3):
            return (f"energy balance off by {self.energy_error:.2g} J, beyond {BUDGET:.0%} of the "
                    f"{self.T_c_total:.3g} J absorbed")
        return ""

    @property
    def sliding_time(self) -> float:
        """Time (s) during which a held foot point slid on the ground."""
        if len(self.t) < 2:
            return 0.0
        return float(np.sum(np.diff(self.t)[self.slide[:-1] != 0]))


class LandingModel(Dynamics):
    """The landing equations of one model, joint model, ground, contact law and integrator:
    the dynamics (dynamics.Dynamics), the impact map per contact set, and the integrator
    step and the forces at a state per contact set, compiled (or interpreted)."""

    def __init__(self, model: Model, joints: Joints = FREE, slope: float = 0.0,
                 compiled: bool = True, integrator: str = DEFAULT_INTEGRATOR, law: str = "no-slip"):
        if not set(FEET) <= set(model.index):
            raise InputError(f"model {model.kind!r} has no foot to land on (it is impact-only)")
        if integrator not in INTEGRATORS:
            raise InputError(f"integrator {integrator!r}: expected one of {', '.join(INTEGRATORS)}")
        if law not in contact.LAWS:
            raise InputError(f"contact law {law!r}: expected one of {', '.join(contact.LAWS)}")
        super().__init__(model, joints, slope)
        self.integrator, self.law, self.compiled = integrator, law, compiled

    def advance(self, active, x, h, s_anchor, joint, sliding=False, mu_s=0.0, t=0.0, scheme=None):
        """One step of x = [q, q', E_joints] from time t by `scheme` (default: the model's
        integrator), symbolic: (x_next, error), error the adaptive scheme's local error
        estimate in units of TOLERANCE (1 is the largest accepted), zero for fixed steps.
        x' = [q', q'', power] of `motion` with no applied moments."""
        n, motion = self.model.n, self.motion(active, sliding)
        no_moments = ca.DM.zeros(len(self.hinges))

        def f(state, time):
            out = motion(state[:n], state[n:2 * n], s_anchor, joint, mu_s, time, no_moments)
            return ca.vertcat(out[0], out[1], out[3])

        return integrator_step(scheme or self.integrator, f, x, t, h)

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
            Phi_b = ca.jacobian(self.constraints(q, (), 0, joint), q)
            W = contact.admissible_inverse_inertia(ca.DM(m.M_inv), Phi_b)
            qd_b = W @ (ca.DM(m.M) @ qd)  # locked joints stop first (a no-op when none are)
            C = ca.vertcat(self.contact_row(active[0], self.t_axis),
                           *[self.contact_row(p, self.n_axis) for p in active])
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
        slip = self.contact_row(active[0], self.t_axis) @ qd_next if active else ca.SX(0)
        names = ["x", "h", "s_anchor", "joint", "friction", "t"]
        step = ca.Function("step", [x, h, s_anchor, joint, mu_s, t],
                           [x_next, ca.vertcat(self.heights(q_next), slip), error],
                           names, ["x_next", "events", "error"])
        q, qd = ca.SX.sym("q", m.n), ca.SX.sym("qd", m.n)
        out = self.motion(active, sliding)(q=q, qd=qd, s_anchor=s_anchor, joint=joint,
                                           friction=mu_s, t=t, moments=ca.DM.zeros(len(self.hinges)))
        forces = ca.Function("forces", [q, qd, s_anchor, joint, mu_s, t],
                             [out["force"], out["normal"], out["residual"], out["energy"],
                              self.heights(q)],
                             ["q", "qd", "s_anchor", "joint", "friction", "t"],
                             ["force", "normal", "residual", "energy", "heights"])
        self._functions[key] = (Compiled(step, self.compiled), Compiled(forces, self.compiled))
        return self._functions[key]


def simulate(lm: LandingModel, strike: str, q0, qd0, friction: float, dt: float = 1e-3,
             t_max: float = 0.2) -> Landing:
    """Follow the landing from the touchdown (q0, qd0 just before the first impact), under
    the model's contact law with the ground's friction coefficient `friction`. dt (s) is the
    fixed integrators' step and the adaptive one's largest. Raises Diverged when the energy
    balance or the finite numbers break."""
    return _Run(lm, strike, q0, qd0, friction, dt, t_max).run()


class _Run:
    """One landing in progress: the state (q, q', t, contact set, sliding direction, the held
    row's anchor), the bookkeeping (energies, impacts, releases) and the transitions."""

    def __init__(self, lm: LandingModel, strike, q0, qd0, friction, dt, t_max):
        m = self.m = lm.model
        self.lm, self.strike, self.friction, self.dt, self.t_max = lm, strike, friction, dt, t_max
        self.q, self.qd = np.asarray(q0, float), np.asarray(qd0, float)
        self.joint = lm.joint_parameters(self.q)
        if lm.joints.model == "torque" and lm.joints.times[-1] < t_max - 1e-12:
            raise InputError(f"the joint moments end at {lm.joints.times[-1] * 1e3:g} ms, before the "
                             f"landing's {t_max * 1e3:g} ms: give them up to the landing's duration")
        start = lm.functions(())[1](self.q, self.qd, 0.0, self.joint, 0.0, 0.0)
        self.E0 = float(start["energy"][0])
        self.T0 = 0.5 * self.qd @ m.M @ self.qd  # J, the scale of a divergence
        self.remedy = (f"with integrator {lm.integrator!r} at dt {dt * 1e3:g} ms: the joints are too "
                       "stiff for it; use integrator \"adaptive\" or a smaller dt_ms"
                       if lm.integrator != "adaptive"
                       else "with the adaptive integrator: check the joints' values against their limits")
        for k, p in enumerate(FEET):
            if p not in STRIKES[strike] and start["heights"][k] < -1e-9:
                raise InputError(f"{strike} strike: the {p} is {-start['heights'][k] * 1e3:.1f} mm "
                                 "below the ground at touchdown")
        self.mu = 0.0 if lm.law == "frictionless" else friction
        self.active: tuple[str, ...] = ()  # the contact set
        self.slide = 0  # sliding direction of the held foot (0: held)
        self.impacts: list[ImpactEvent] = []
        self.releases: list[tuple[float, str, float]] = []  # (time, points, normal force)
        self.slip_at: list[float] = []
        self.warnings: list[str] = []
        self.absorbed, self.dissipated, self.t = 0.0, 0.0, 0.0
        self.record: dict[str, list] = {k: [] for k in (
            "t", "q", "qd", "T", "V", "spring", "dissipated", "absorbed", "energy", "force", "active",
            "slide")}
        self.height = GRAVITY * m.momentum_matrix[1]  # q -> gravitational potential energy (J)
        self.V0 = float(self.height @ self.q)
        self.drift, self.mu_max, self.switches, self.s_anchor = 0.0, 0.0, 0, 0.0
        self.ended, self.h_next = Ended.DURATION, dt
        self.armed: dict[str, bool] = {}

    def run(self) -> Landing:
        """The state machine: impact, then per state strike / release / slide / finish, else
        one integrator step to the next state or event."""
        self.sample(np.full(2, np.nan), self.E0)  # just before the first impact
        self.strike_now(list(STRIKES[self.strike]), 0.0)
        # a foot point can strike only after it has been above the ground since its last contact
        self.armed = {p: p not in self.active for p in FEET}
        while True:
            step, forces = self.lm.functions(self.active, self.slide != 0)
            out = forces(self.q, self.qd, self.s_anchor, self.joint, self.mu * self.slide, self.t)
            self.drift = max(self.drift, float(out["residual"][0]))
            for k, p in enumerate(FEET):
                self.armed[p] = self.armed[p] or (p not in self.active and out["heights"][k] > 1e-9)
            if self.sinking(out["heights"]):
                continue
            normals = out["normal"]
            pulling = bool(self.active) and bool(
                np.any(normals < -1e-9 * max(1.0, float(np.max(np.abs(normals))))))
            if set(self.active) == set(FEET):
                self.both_down(out, pulling)
                break
            if self.contact_changes(out["force"], normals, pulling):
                if self.ended in (Ended.CHATTER, Ended.HELD_CHATTER):
                    break
                continue
            self.contact_phase(out)
            if self.t >= self.t_max - 1e-12:
                break
            self.integrate(step, forces)
        return self.result()

    def anchor(self) -> float:
        """The held row's place along the ground: the first active point's t coordinate (m)."""
        return float(self.q[self.m.cols(self.active[0])] @ self.lm.t_axis)

    def strike_now(self, points, time):
        """The impact of `points` joining the contact set: q' jumps, T_c is absorbed."""
        m, lm = self.m, self.lm
        new = tuple(self.active) + tuple(p for p in points if p not in self.active)
        out = lm.impact_map(new)(self.q, self.qd, self.joint, self.friction)
        qd_plus, absorbed, total = (np.asarray(v, float).ravel() for v in out[:3])
        mode, slip = int(out[3]), float(out[4])
        T_c = float(absorbed[0])
        dv = (m.com_matrix(m.trunk) @ (qd_plus - self.qd)) if m.trunk else None
        mu_c = float(abs(total[0]) / total[1]) if total[1] > 0 else None  # undefined when not pushed
        if lm.law == "no-slip" and (mu_c is None or mu_c > self.friction):
            self.slip_at.append(time)
        if mu_c is not None:
            self.mu_max = max(self.mu_max, mu_c)
        self.impacts.append(ImpactEvent(time, "+".join(points), new, T_c,
                                        xy(dv) if dv is not None else None,
                                        (float(total[0]), float(total[1])), mu_c,
                                        contact.MODES[mode], slip))
        self.absorbed += T_c
        self.active = new
        self.slide = 0 if mode == contact.STICK else (1 if slip >= 0 else -1)
        self.s_anchor = self.anchor()
        self.qd = qd_plus

    def sample(self, force, mechanical):
        """Record the state; Diverged when the energy balance is off by more than DIVERGED."""
        error = abs(mechanical + self.dissipated + self.absorbed - self.E0)
        if not error <= DIVERGED * self.T0:  # also when not finite
            raise Diverged(f"the landing diverged at {self.t * 1e3:.2f} ms: the energy balance is off "
                           f"by {error:.3g} J ({error / self.T0:.1e} of the touchdown kinetic energy) "
                           f"{self.remedy}")
        T, V = 0.5 * self.qd @ self.m.M @ self.qd, float(self.height @ self.q)
        for key, value in (("t", self.t), ("q", self.q.copy()), ("qd", self.qd.copy()), ("T", T),
                           ("V", V - self.V0), ("spring", mechanical - T - V),
                           ("dissipated", self.dissipated), ("absorbed", self.absorbed),
                           ("energy", mechanical + self.dissipated + self.absorbed),
                           ("force", force), ("active", self.active), ("slide", self.slide)):
            self.record[key].append(value)

    def sinking(self, heights) -> bool:
        """A point at or below the ground moving into it strikes, armed or not (one released
        where it stood, and never lifted, would otherwise pass through the floor)."""
        sinking = [p for k, p in enumerate(FEET) if p not in self.active
                   and heights[k] <= 1e-9 and self.qd[self.m.cols(p)] @ self.lm.n_axis < 0]
        if not sinking or self.switches > MAX_SWITCHES:
            return False
        self.switches += 1
        for p in sinking:
            self.armed[p] = False
        self.strike_now(sinking, self.t)
        return True

    def both_down(self, out, pulling):
        """Heel and forefoot both down: the landing is over."""
        self.sample(out["force"], float(out["energy"][0]))
        self.ended = Ended.BOTH_DOWN
        if pulling:
            self.warnings.append("with both points down the ground would pull " + " and ".join(
                p for p, n in zip(self.active, out["normal"]) if n < 0) + ": it would lift again")

    def contact_changes(self, force, normals, pulling) -> bool:
        """Release the points the ground would pull, or let a stuck point slide (Coulomb) when
        holding it needs |f_t| > mu f_n; past MAX_SWITCHES the landing ends in chatter."""
        slides = (self.lm.law == "coulomb" and self.active and not self.slide
                  and abs(force[0]) > self.friction * force[1])
        if not (pulling or slides):
            return False
        self.switches += 1
        if self.switches > MAX_SWITCHES:
            self.ended = Ended.HELD_CHATTER if self.lm.law == "no-slip" else Ended.CHATTER
            self.warnings.append(self.ended.value)
            return True
        if pulling:
            pulled = [p for p, n in zip(self.active, normals) if n < 0]
            self.releases.append((self.t, "+".join(pulled), float(min(normals))))
            self.active = tuple(p for p in self.active if p not in pulled)
            self.slide = self.slide if self.active else 0
        else:  # holding the point needs more friction than the ground has: it slides
            self.slide = -1 if force[0] > 0 else 1
        if self.active:  # the first held point carries the tangential row
            self.s_anchor = self.anchor()
        return True

    def contact_phase(self, out):
        """Check the held contact's friction (mu_c = |f_t| / f_n) and record the state."""
        force = out["force"]
        if self.active and force[1] > 0:
            mu_c = abs(force[0]) / force[1]
            self.mu_max = max(self.mu_max, mu_c)
            if self.lm.law == "no-slip" and mu_c > self.friction:
                self.slip_at.append(self.t)
        self.sample(force if self.active else np.full(2, np.nan), float(out["energy"][0]))

    def integrate(self, step, forces):
        """One accepted step, cut at the earliest event (a strike, a sliding point at rest)."""
        x = np.concatenate([self.q, self.qd, [self.dissipated]])
        args = (self.s_anchor, self.joint, self.mu * self.slide, self.t)
        h, taken = self.accepted_step(step, x, args)
        h, what, hits = self.earliest_event(lambda s: step(x, s, *args)["events"], h, taken["events"])
        x_next = taken["x_next"] if what is None else step(x, h, *args)["x_next"]
        if not np.all(np.isfinite(x_next)):
            raise Diverged(f"the landing diverged at {self.t * 1e3:.2f} ms: the state is no longer "
                           f"finite {self.remedy}")
        self.t += h
        n = self.m.n
        self.q, self.qd, self.dissipated = x_next[:n], x_next[n:2 * n], float(x_next[-1])
        if what == "hit":
            out = forces(self.q, self.qd, self.s_anchor, self.joint, self.mu * self.slide, self.t)
            self.sample(np.full(2, np.nan), float(out["energy"][0]))
            points = [FEET[k] for k in hits]
            for p in points:
                self.armed[p] = False
            self.strike_now(points, self.t)
        elif what == "stop":  # the sliding point comes to rest: it sticks where it is
            self.slide, self.s_anchor = 0, self.anchor()

    def earliest_event(self, events_at, h, events):
        """(step length, "hit", "stop" or None, the striking points' indices in FEET) from the
        event values after a step of h (`events`) and after a step of s (`events_at(s)`).

        An armed point strikes at the ground; one that never rose since it was let go, a hair
        below it (SINK), so that the event has a root and the point cannot sink further. A
        sliding point (Coulomb) stops when its tangential velocity reaches zero."""
        sink = [0.0 if self.armed[p] else SINK for p in FEET]
        hits = [k for k, p in enumerate(FEET) if p not in self.active and events[k] + sink[k] <= 0.0]
        stops = self.lm.law == "coulomb" and self.slide != 0 and self.slide * events[2] <= 0.0
        candidates = []
        if hits:
            candidates.append((locate(lambda s: min(events_at(s)[k] + sink[k] for k in hits), h), "hit"))
        if stops:
            candidates.append((locate(lambda s: self.slide * events_at(s)[2], h), "stop"))
        return (*min(candidates), hits) if candidates else (h, None, hits)

    def accepted_step(self, step, x, args):
        """(h, the step's outputs): the adaptive scheme shrinks h until the local error is
        accepted and sets the next step's length from it; fixed steps take min(dt, t_max - t)."""
        h = min(self.h_next, self.dt, self.t_max - self.t)
        taken = step(x, h, *args)
        while not taken["error"][0] <= 1.0:
            if h < MIN_STEP:
                raise Diverged(f"the landing diverged at {self.t * 1e3:.2f} ms: the adaptive step "
                               f"fell below {MIN_STEP * 1e9:g} ns (the joints are too stiff or the "
                               "state left the finite numbers)")
            h = shrink(h, taken["error"][0])
            taken = step(x, h, *args)
        if self.lm.integrator == "adaptive":  # the next step's length from this one's error
            self.h_next = grow(h, taken["error"][0])
        return h, taken

    def result(self) -> Landing:
        r, energy = self.record, np.array(self.record["energy"])
        return Landing(t=np.array(r["t"]), q=np.array(r["q"]), qd=np.array(r["qd"]),
                       T=np.array(r["T"]), V=np.array(r["V"]), spring=np.array(r["spring"]),
                       dissipated=np.array(r["dissipated"]), absorbed=np.array(r["absorbed"]),
                       energy=energy, force=np.array(r["force"]), active=r["active"],
                       slide=np.array(r["slide"]), impacts=self.impacts, releases=self.releases,
                       T_c_total=self.absorbed, mu_c_max=self.mu_max, no_slip_held=not self.slip_at,
                       slip_at=self.slip_at, law=self.lm.law,
                       energy_error=float(np.max(np.abs(energy - self.E0))), drift=self.drift,
                       ended=self.ended, warnings=self.warnings)


def simulate_state(lm: LandingModel, strike: str, x, friction: float, dt: float,
                   duration: float) -> Landing:
    """Simulate the landing from a touchdown state x (model.STATE, SI) on a ground of
    `friction`, with steps of `dt` (s) for at most `duration` (s); InputError for arguments
    outside mechanics.limits (a landing that could not end, or a ground that cannot be)."""
    check_ground(friction, lm.slope)
    duration = limits.check("duration", duration, limits.LANDING_DURATION_S)
    dt = limits.check("dt", dt, Range(limits.LANDING_DT_S.low, min(limits.LANDING_DT_S.high, duration), "s"))
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
