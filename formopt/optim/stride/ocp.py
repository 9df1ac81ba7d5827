"""The half stride as an optimal control problem, apart from its transcription (collocation.py):
per phase a node model (an actuation model, a contact model), the transitions between phases,
the touchdown with the periodicity, and the cost terms.

Node model (per phase, at every node; x = (theta, theta'), a = theta'', u the actuation's
controls, f the contact forces, theta_td the touchdown state, p = (speed, slope, mu)):

    M(theta) a + c(theta, theta') - g(theta) - tau_pass(theta) + [0; tau(z, u)] - J_c^T m g f = 0

with the contact model's rows (contact.RigidContact) and, for the work objectives, the power
split P_j = P_j+ - P_j- (W/kg, P+- >= 0; problem.py says why), and the actuation's own rows
(the muscles' activation dynamics and Hill equilibrium; actuation.py). Its integrands
(`INTEGRANDS`): effort sum tau_active^2, the split's sums, the joint-level metabolic power
(costs.joint_metabolic_rate; zero unless the objective is joint-metabolic), the held contacts' power (`ground`),
the power the budget balances (`balance`: active joints, passive joint moments, tendons and contacts), a slide's
friction power, each active joint's power (6), the passive joint moments' (`passive`), the tendons' and the contacts' power,
and the actuation's own (actuation.OWN_INTEGRANDS: the muscles' activation cost, metabolic rate
(W), volume-weighted squared tendon-force rates (the force-rate term), plain squared tendon-force
rates (their regularisation) and squared reserves; with moment dynamics the moments' squared rates).

Transitions (phase i-1 -> i): `Impact` where phase i adds a point (it reaches the ground moving
into it; contact.RigidContact.impact), `Release` where it drops one (the dropped point's normal
force zero at phase i-1's end, but for torque sources on Hermite-Simpson: `Release` says why;
the end of a slide: its slip zero). The touchdown of L at the flight's end is an `Impact` too;
periodicity: that post-impact state, legs swapped and moved back one step along the ground, is
the start (`shift`), and x_hip = 0 at the start.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from ...mechanics.joint_space import JOINTS, THETA, JointSpace, swap_legs
from . import costs
from .actuation import OWN_INTEGRANDS, Torques, actuation
from .contact import RigidContact, height, normal_velocity
from .layout import Rows
from .problem import Phase, StrideSettings, other_leg

NX, NU = len(THETA), len(JOINTS)
INTEGRANDS = ("effort", "positive", "negative", "joint_metabolic", "ground", "balance", "slide", *[f"power_{j}" for j in JOINTS],
              "passive", "spring", "contact", *OWN_INTEGRANDS)


def shift(step, slope):
    """The periodicity's shift of theta (9): one step (m) along the ground of slope `slope`."""
    return ca.vertcat(step * ca.cos(slope), step * ca.sin(slope), ca.DM.zeros(NX - 2))


def periodicity(theta_end, v_plus, start, step, slope):
    """The touchdown state, legs swapped and moved back by `shift`, against the start (x =
    (theta, theta'), 18): zero for a periodic half stride (symbolic or numeric)."""
    return ca.vertcat(swap_legs(theta_end) - shift(step, slope) - start[:NX], swap_legs(v_plus) - start[NX:])


@dataclass(frozen=True)
class NodeModel:
    """A phase's node model: its actuation and contact, and whether the leading leg (R)
    holds the ground (the tendons engage)."""

    phase: Phase
    actuation: Torques
    contact: RigidContact
    split: bool  # the power split's slack variables (work objectives)
    joint_metabolic: bool = False  # the joint-level metabolic power (objective joint-metabolic)

    def __call__(self, js: JointSpace, x, a, u, f, s, z, theta_td, p):
        """(rows, {integrand: value}) at one node (module docstring); z the actuation's states."""
        slope, mu = p[1], p[2]
        theta, thetad = x[:NX], x[NX:]
        m = self.actuation.mass
        rows = Rows()
        active = self.actuation.active(z, u)
        self.actuation.rows(rows, theta, thetad, z, u)
        spring = self.actuation.passive(theta, theta_td, bool(self.phase.points))
        passive = self.actuation.joint_passive(js, theta)  # tau_pass (mechanics.joint_space)
        ground_force = self.contact.node(rows, theta, thetad, a, f, slope, mu, m)
        rows.add((js.mass(theta) @ a + js.bias(theta, thetad) - js.gravity(theta) - passive
                  + ca.vertcat(0, 0, 0, active + spring) - ground_force) / m)
        power = -active * thetad[3:]  # W, extensor moment times extension rate
        contact, held, slide = self.contact.power(theta, thetad, f, slope, m)
        out = {"effort": ca.sumsqr(active), "positive": 0.0, "negative": 0.0, "ground": held,
               "joint_metabolic": costs.joint_metabolic_rate(active, thetad[3:], m) if self.joint_metabolic else 0.0,
               "slide": -slide, "passive": ca.dot(passive, thetad), "spring": ca.dot(spring, thetad[3:]),
               "contact": contact, **{f"power_{j}": power[k] for k, j in enumerate(JOINTS)},
               **self.actuation.integrands(theta, thetad, z, u)}
        out["balance"] = ca.sum1(power) + out["passive"] - out["spring"] + contact
        if self.split:
            rows.add(power / m - (s[:NU] - s[NU:]))
            out["positive"], out["negative"] = m * ca.sum1(s[:NU]), m * ca.sum1(s[NU:])
        return rows, out


@dataclass(frozen=True)
class Impact:
    """Phase `after` (or the touchdown, after = None) starts with the impact of the points its
    contact model adds; `contact` holds after it; each point approaches the ground at least at
    `approach` (m/s, StrideSettings.approach_speed)."""

    points: tuple[str, ...]
    contact: RigidContact
    approach: float = 0.0

    def rows(self, rows: Rows, js, theta, v_minus, v_plus, impulse, p, mass):
        """The points on the ground moving into it, the impact's rows; T_c (J)."""
        for point in self.points:
            rows.add(height(js, point, theta, p[1]))
            rows.add(normal_velocity(js, point, theta, v_minus, p[1]), -np.inf, -self.approach)
        return self.contact.impact(rows, theta, v_minus, v_plus, impulse, p[1], p[2], mass)


@dataclass(frozen=True)
class Release:
    """Phase `before` ends when its dropped points leave the ground (heel-off, toe-off), or
    when its sliding point's slip reaches zero; `dropped`: the rows whose normal force is zero
    at its end. Where the moments are states (muscles, moment dynamics: StrideSettings.moment_time)
    and on the trapezoid, every dropped point's; with torque sources on Hermite-Simpson none: there the force is the controls' at
    one instant, a row the continuous problem meets by a jump of the moments (a rigid contact
    lets go with any f_n >= 0 when the moments change so that the point rises: the next phase
    holds it at or above the ground) and the transcription only by a layer one interval wide
    that costs O(h): the optimum converged as O(h) (objective 0.1625 / 0.1461 / 0.1382 at 20 /
    40 / 80 intervals, RBDS001, 3.5 m/s, 130 steps/min; problems/stride_mesh.py). The
    trapezoid keeps the row with StrideSettings.consistency_rows "exact": without it its
    coarse strides leave the ground pushing 2 body weights, which its forward check rejects
    (0.16-0.22 rad at 24-40 nodes)."""

    dropped: tuple[int, ...]  # the rows of the phase before whose force is zero at its end
    slide_end: str = ""  # the sliding point whose slip ends the phase

    def rows(self, rows: Rows, js, theta, v_minus, v_plus, force_end, p):
        rows.add(v_plus - v_minus)
        if self.slide_end:
            rows.add(js.points[self.slide_end](theta, v_minus, p[1])[1][0])
        if self.dropped:
            rows.add(force_end[list(self.dropped)])


class StrideProblem:
    """The half stride of a body and settings (module docstring): `models` (a NodeModel per
    phase), `transitions` (between phase i-1 and i, index i - 1), `touchdown` (L's impact at
    the flight's end), `cost_terms`."""

    def __init__(self, js: JointSpace, settings: StrideSettings):
        self.js, self.settings, self.mass = js, settings, js.mass_total
        self.phases = settings.phases
        act = actuation(self.mass, settings.torque_limit, settings.tendons, settings.muscles,
                        settings.moment_time > 0, settings.activation_rate_smoothing, settings.torque_velocity)
        split = costs.needs_power_split(settings)
        joint_metabolic = settings.objective == "joint-metabolic"
        self.models = [NodeModel(ph, act, RigidContact(js, ph.rows, ph.sliding, settings.slip, settings.clearance),
                                 split, joint_metabolic) for ph in self.phases]
        self.transitions = [self._transition(i) for i in range(1, len(self.phases))]
        first = self.phases[0]
        rows = tuple((other_leg(p), a) for p, a in first.rows)
        sliding = other_leg(first.sliding) if first.sliding else ""
        self.touchdown = Impact(tuple(dict.fromkeys(p for p, _ in rows)),
                                RigidContact(js, rows, sliding, settings.slip), settings.approach_speed)
        self.cost_terms = costs.terms(settings, self.mass)

    def _transition(self, i: int) -> Impact | Release:
        before, after = self.phases[i - 1], self.phases[i]
        added = tuple(p for p in after.points if p not in before.points)
        if added:
            return Impact(added, self.models[i].contact, self.settings.approach_speed)
        if not (self.models[i].actuation.states
                or (self.settings.transcription == "trapezoid" and self.settings.consistency_rows == "exact")):
            # torque sources on Hermite-Simpson, or consistency_rows not "exact": `Release` says why
            return Release((), before.sliding)
        dropped = tuple(k for k, (p, a) in enumerate(before.rows) if a == "n" and p not in after.points)
        return Release(dropped, before.sliding)

    def objective(self, integrals: dict, speed, period):
        """The objective per distance (costs.objective) of the integrals, d = speed * period."""
        return costs.objective(self.cost_terms, integrals, step_length(speed, period))


def step_length(speed, period):
    """A step (m): the distance covered in a half-period, d = v T."""
    return speed * period
