"""Actuation models of the stride: what moves the joints at a node (problem.ACTUATIONS, the ladder).

An actuation model has `controls` u and `states` z (per node, with bounds; z' = rates(z, u),
linear in u, collocated like the body's states; rows(...) its algebraic rows at a node, each with
its bounds: = 0, or <= 0 for the torque-velocity limit) and
gives the joint moments (N m, JOINTS order, extensor positive) that enter the equations of motion,

    tau = tau_active(z, u) + tau_passive(theta, theta_td),

with the active part's power P_j = -tau_j phi_j' (W; what W+ and W- count) apart from the
passive elements' (the budget's `spring_J`), and its own cost integrands (`OWN_INTEGRANDS`).
Symbolic (SX) or numeric arguments.

- "torque": joint torque sources (`Torques`; with StrideSettings.moment_time, moment dynamics:
  the moments states, their rates the controls);
- "torque+springs": the same with springs in parallel at the stance leg (`TorquesWithSprings`);
- "muscles": gait2d's eight Hill-type muscle-tendon units per leg (`MuscleDriven`,
  mechanics.muscles) in De Groote et al. 2016's form: states a and F (normalised tendon force),
  controls the excitation e, a' and F'/10, rows the activation dynamics and the Hill equilibrium.
"""

from __future__ import annotations

from functools import cached_property

import casadi as ca
import numpy as np

from ...mechanics import muscles as hill
from ...mechanics.joint_space import JOINTS

NU = len(JOINTS)
# |a'| (1/s) bound: the activation dynamics reach at most (e - a) / (tau_a (1/2 + 3a/2)) = 128 /s
# (a = 0.01, e = 1) and 2 / tau_d = 33 /s down; the row ties a' to them, the bound only boxes it
ACTIVATION_RATE = 200.0
RESERVE_LIMIT = 1.0  # N m/kg: the muscles' reserve moments at each joint (MuscleDriven)
MIN_FORCE_PENALTY = 5.0  # N m per unit F: the guess's least-squares split of a moment (MuscleDriven.initial)
OWN_INTEGRANDS = ("activation", "muscle_metabolic", "force_rate", "force_rate_abs", "muscle_rates", "reserves",
                  "moment_rates")  # zero for the torque sources without moment dynamics
# Moment dynamics (StrideSettings.moment_time > 0): the torque rungs' moments are states and
# their rates the controls, so a moment cannot jump (a muscle's force rises and falls over tens
# of ms, activation dynamics of 15-60 ms: mechanics.muscles); u = tau' / (m MOMENT_RATE_SCALE),
# of order one for a moment of 3 N m/kg rising in 30 ms, within +-MOMENT_RATE_LIMIT: 1000
# N m/kg/s (0 to 3 N m/kg in 3 ms), a numerical box the rate's cost keeps the optimum off.
MOMENT_RATE_SCALE = 100.0  # N m/kg/s per unit control
MOMENT_RATE_LIMIT = 10.0
# omega_max per joint (rad/s): gait2d's muscles crossing it (io/data/gait2d_muscles.csv,
# mechanics.muscles with v_max = 10 l_opt/s), sum F_max v_max / sum F_max |r|: their greatest
# power over their greatest moment (a rigid tendon's view). Lengths scale with height and forces
# cancel (mechanics.muscles.from_gait2d), so it is the same for every body; tests check it
# against the table. A model's value, not a measured joint's: RBDS001's mean cycle (the data
# set's processing) peaks at 11.2 / 10.8 rad/s at the knee / ankle at 3.5 m/s, 13.2 / 13.4 at 4.5.
# The torque rungs' torque-velocity limit (StrideSettings.torque_velocity, `Torques.rows`) and the
# joint-level metabolic cost (costs.joint_metabolic_rate) read it.
JOINT_MAX_RATE = {"hip": 22.4, "knee": 23.7, "ankle": 12.7}
# De Groote's f_V falls below zero past v_max (-0.07 to -0.17 at 1.3-1.7 w at the ankle): a muscle
# shortening that fast makes no force, it does not pull the other way, so the torque-velocity limit
# floors it smoothly at zero, (f + sqrt(f^2 + eps^2)) / 2 with this eps (within eps / 2 of max(f, 0)).
VELOCITY_FLOOR = 0.01
# The transcription's smoothing (problem.SMOOTHING) charges the activations' rates a' (1/s) times
# this scale (1/s, so in 1/s^2 as the accelerations' rad/s^2) beside the accelerations, their
# changes between nodes alike (MuscleDriven.smoothed): a' is a control tied to the
# excitation e by the activation dynamics' row, and a' alternating node to node leaves the
# trapezoid's defects unchanged, while nothing else in the objective reads e (Bhargava's energy
# reads a), so e zig-zagged between its bounds at 5-22 % of the nodes; replayed linear between the
# nodes through activation dynamics fast to rise (15 ms) and slow to fall (60 ms), a zig-zag is
# another activation, and |F'|'s searched 2.5 m/s stride (graded 80 nodes) left its replay by
# 0.171 rad (the iliopsoas's e 0.86, 0, 0.89, 0.06, ... at late stance: problems/muscle_replay.py).
# Chosen at the calibration speed (3.5 m/s, |F'|, graded 80, warm from its searched stride:
# problems/muscle_energy.py --activation-smoothing S, 2026-11-27): at 0 / 1 / 10 / 100 the forward
# check 0.038 / 0.038 / 0.009 / 0.002 rad, zig-zags at up to 17 / 16 / 5 / 0 % of a phase's
# nodes, the smoothing 0.1 / 0.1 / 0.5 / 4.3 % of the objective, 170.8 / 170.8 / 171.2 / 172.2
# steps/min: 10, the smallest power of ten that closes most of the null mode for under 1 % of
# the cost (docs/concepts/muscles.md, "The 2.5 m/s replay"). The default of
# StrideSettings.activation_rate_smoothing, which sets it (0: the first step of a stalled
# refinement's continuation, refine.continued).
ACTIVATION_RATE_SMOOTHING = 10.0


def max_rates() -> ca.DM:
    """JOINT_MAX_RATE in JOINTS order (rad/s, 6)."""
    return ca.DM([JOINT_MAX_RATE[j[:-2]] for j in JOINTS])


class Torques:
    """Joint torque sources: tau = m u, u (N m/kg, one per joint) within +-`limit`; with
    `dynamic`, moment dynamics: tau = m z, z (N m/kg) a state within +-`limit`, z' =
    MOMENT_RATE_SCALE u, u within +-MOMENT_RATE_LIMIT, its integrand `moment_rates` |tau'|^2
    ((N m/s)^2; costs.py weighs it); with `velocity`, the limit falls with the joint's rate as a
    muscle's force does (`rows`)."""

    def __init__(self, mass: float, limit: float, dynamic: bool = False, velocity: bool = False):
        self.mass, self.limit, self.dynamic, self.velocity = mass, limit, dynamic, velocity

    @property
    def controls(self) -> int:
        return NU

    def bounds(self) -> tuple[float, float]:
        """(lower, upper) of each control (N m/kg; with `dynamic` its rate's, scaled)."""
        return (-MOMENT_RATE_LIMIT, MOMENT_RATE_LIMIT) if self.dynamic else (-self.limit, self.limit)

    @property
    def states(self) -> int:
        return NU if self.dynamic else 0

    def state_bounds(self) -> tuple[float, float]:
        return (-self.limit, self.limit) if self.dynamic else (0.0, 0.0)

    def active(self, z, u):
        """The active joint moments (N m, 6) of states z or controls u (N m/kg, 6)."""
        return self.mass * (z if self.dynamic else u)

    def rates(self, U):
        """z' of the controls (a column per node): the moments' rates, or no states."""
        return MOMENT_RATE_SCALE * U if self.dynamic else U[:0, :]

    def rows(self, rows, theta, thetad, z, u) -> None:
        """With `velocity`, the torque-velocity limit at a node: each joint's extensor and flexor
        moments (per kg) within what the muscles on that side can make at their velocity,

            tau_j / limit <= g(theta'_j / w_j),   -tau_j / limit <= g(-theta'_j / w_j),

        g = f_V floored smoothly at zero (VELOCITY_FLOOR), f_V mechanics.muscles.force_velocity
        (lengthening positive: flexion lengthens the extensors), w_j = JOINT_MAX_RATE: 1 at rest,
        about 0 shortening at w_j and beyond; lengthening, f_V's 1.8 at w_j is capped by the
        moments' own box (+-limit). Smooth (no |.|), two rows per joint <= 0. Else none."""
        if not self.velocity:
            return
        tau = z if self.dynamic else u
        rate = thetad[3:] / max_rates()

        def g(v):
            f = hill.force_velocity(v)
            return 0.5 * (f + ca.sqrt(f ** 2 + VELOCITY_FLOOR ** 2))

        rows.add(ca.vertcat(tau / self.limit - g(rate), -tau / self.limit - g(-rate)), -np.inf, 0.0)

    def smoothed(self, U):
        """The rates the transcription's smoothing closes beside the accelerations (a column per
        node): none here."""
        return U[:0, :]

    def integrands(self, theta, thetad, z, u) -> dict:
        """Its own cost integrands (OWN_INTEGRANDS): with `dynamic` the moments' squared rates
        |tau'|^2 ((N m/s)^2), else none."""
        rates = ca.sumsqr(self.mass * MOMENT_RATE_SCALE * u) if self.dynamic else 0.0
        return {**dict.fromkeys(OWN_INTEGRANDS, 0.0), "moment_rates": rates}

    def swap(self, z):
        """z with the legs exchanged (the periodicity)."""
        return ca.vertcat(z[3:], z[:3]) if self.dynamic else z

    def initial(self, theta, thetad, tau) -> tuple[np.ndarray, np.ndarray]:
        """(z, u) of a guess that makes the active moments tau (N m, 6 x c) at node angles and
        rates theta, theta' (9 x c) (with `dynamic`: held, their rates zero)."""
        if self.dynamic:
            return tau / self.mass, np.zeros_like(tau)
        return np.zeros((0, tau.shape[1])), tau / self.mass

    def passive(self, theta, theta_td, stance: bool):
        """The passive elements' joint moments (N m, 6): none."""
        return ca.DM.zeros(NU)

    def joint_passive(self, js, theta):
        """The joints' generalised passive moments (N m, 9) this body feels: Riener & Edrich's
        (mechanics.joint_space.passive_moments)."""
        return js.passive(theta)


def springs(tendons: dict) -> dict:
    """The springs of a tendons mapping ({joint: N m/rad per kg}): a spring at zero is none."""
    return {joint: k for joint, k in tendons.items() if k}


class TorquesWithSprings(Torques):
    """Torque sources with a spring in parallel at the stance leg's joints (tendons):

        tau_spring_j = k_j m (phi_j - phi_j(touchdown))   while R holds the ground, else 0,

    k_j in N m/rad per kg (problem.TENDON_JOINTS, RUNNER_TENDONS), engaged unloaded at the
    touchdown and released at toe-off: what it still holds then is lost (budget's `spring_J`).
    """

    def __init__(self, mass: float, limit: float, stiffness: dict, dynamic: bool = False, velocity: bool = False):
        super().__init__(mass, limit, dynamic, velocity)
        self.stiffness = {f"{joint}_R": k for joint, k in springs(stiffness).items()}

    def passive(self, theta, theta_td, stance: bool):
        out = [0.0] * NU
        if stance:
            for joint, k in self.stiffness.items():
                j = JOINTS.index(joint)
                out[j] = k * self.mass * (theta[3 + j] - theta_td[3 + j])
        return ca.vertcat(*out)


class MuscleDriven(Torques):
    """Eight Hill-type muscle-tendon units per leg (mechanics.muscles; n = 8 per leg):

        z = [a_R, F_R, a_L, F_L]   (4n)   activations in [0.01, 1], tendon forces (F_max) in [0, 5]
        u = [e_R, b_R, g_R, e_L, b_L, g_L, r]   (6n + 6)   excitations in [0, 1], b = a'/100,
            g = F'/10, r the reserve moments (N m/kg, within +-RESERVE_LIMIT)
        z' = [100 b_R, 10 g_R, 100 b_L, 10 g_L]
        rows:  a'/100 - da/dt(e, a)/100 = 0,   Hill equilibrium(theta, theta', a, F, F') = 0
        tau = [tau_R(F_R); tau_L(F_L)] + m r,   tau_leg = -r^T F_max F (mechanics.muscles.joint_moments)

    The reserves (as OpenSim Moco's and PredSim's reserve actuators) keep the NLP feasible where
    the muscles cannot make a motion of the search (their cost, StrideSettings.reserve_weight,
    makes them a last resort); a stride reports their largest mean over 10 ms
    (`Stride.checks["reserve_nm_per_kg"]`, muscle_readings.reserve_mean) and is invalid beyond
    TOLERANCES["reserve_nm_per_kg"]; their largest node value beside it ("reserve_peak_nm_per_kg").

    a' is a control tied to the activation dynamics by a row (the defects stay linear: the
    node model holds every nonlinearity). The joints feel the range walls alone (`joint_passive`);
    the muscles' tendons are in series, so there are no parallel springs.
    """

    RATE_SCALE = 10.0  # F' = 10 g (De Groote et al. 2016 scale the rate so)
    ACTIVATION_SCALE = 100.0  # a' = 100 b: the controls of order one

    def __init__(self, mass: float, muscles: hill.Muscles, rate_smoothing: float = ACTIVATION_RATE_SMOOTHING):
        super().__init__(mass, 0.0)
        self.muscles, self.leg, self.n = muscles, hill.leg_functions(muscles), len(muscles.names)
        self.rate_smoothing = rate_smoothing  # 1/s: `smoothed`'s scale (StrideSettings.activation_rate_smoothing)

    @property
    def states(self) -> int:
        return 4 * self.n

    @property
    def controls(self) -> int:
        return 6 * self.n + NU

    def state_bounds(self):
        n = self.n
        return np.tile(np.r_[[0.01] * n, [0.0] * n], 2), np.tile(np.r_[[1.0] * n, [5.0] * n], 2)

    def bounds(self):
        n = self.n
        bound = ACTIVATION_RATE / self.ACTIVATION_SCALE
        return (np.r_[np.tile(np.r_[[0.0] * n, [-bound] * n, [-10.0] * n], 2), [-RESERVE_LIMIT] * NU],
                np.r_[np.tile(np.r_[[1.0] * n, [bound] * n, [10.0] * n], 2), [RESERVE_LIMIT] * NU])

    def _legs(self, z, u):
        """Per leg (R, L): (a, F, e, a', F') slices."""
        n = self.n
        for k in range(2):
            zz, uu = z[2 * n * k:2 * n * (k + 1)], u[3 * n * k:3 * n * (k + 1)]
            yield zz[:n], zz[n:], uu[:n], self.ACTIVATION_SCALE * uu[n:2 * n], self.RATE_SCALE * uu[2 * n:]

    def active(self, z, u):
        return ca.vertcat(*[self.leg.moments(F) for _, F, _, _, _ in self._legs(z, u)]) + self.mass * u[6 * self.n:]

    def rates(self, U):
        n = self.n
        return ca.vertcat(*[ca.vertcat(self.ACTIVATION_SCALE * U[3 * n * k + n:3 * n * k + 2 * n, :],
                                       self.RATE_SCALE * U[3 * n * k + 2 * n:3 * n * (k + 1), :])
                            for k in range(2)])

    def smoothed(self, U):
        """The activations' rates a' (1/s, 2n rows, a column per node) times `rate_smoothing`
        (ACTIVATION_RATE_SMOOTHING's default), for the transcription's smoothing: a' is a control tied to the
        excitation by the activation dynamics' row, and a' alternating node to node leaves the
        trapezoid's defects unchanged while the excitation zig-zags between its bounds."""
        n = self.n
        return self.rate_smoothing * self.ACTIVATION_SCALE * ca.vertcat(
            *[U[3 * n * k + n:3 * n * k + 2 * n, :] for k in range(2)])

    def _joint(self, theta, k):
        return theta[3 + 3 * k:6 + 3 * k]

    def rows(self, rows, theta, thetad, z, u) -> None:
        for k, (a, F, e, ad, Fd) in enumerate(self._legs(z, u)):
            rows.add((ad - self.leg.activation_rate(e, a)) / self.ACTIVATION_SCALE)
            rows.add(self.leg.residual(self._joint(theta, k), self._joint(thetad, k), a, F, Fd))

    def integrands(self, theta, thetad, z, u) -> dict:
        legs = list(self._legs(z, u))
        return {"activation": sum(self.leg.activation_cost(a) for a, *_ in legs),
                "muscle_metabolic": sum(self.leg.metabolic_rate(self._joint(theta, k), self._joint(thetad, k), a, F, Fd)
                                        for k, (a, F, _, _, Fd) in enumerate(legs)),
                "force_rate": sum(self.leg.force_rate_cost(Fd) for *_, Fd in legs),
                "force_rate_abs": sum(self.leg.force_rate_abs(Fd) for *_, Fd in legs),
                "muscle_rates": sum(ca.sumsqr(Fd / self.RATE_SCALE) for *_, Fd in legs),
                "reserves": ca.sumsqr(u[6 * self.n:]), "moment_rates": 0.0}

    def swap(self, z):
        return ca.vertcat(z[2 * self.n:], z[:2 * self.n])

    def forward_rates(self, theta, thetad, z, u):
        """z' (4n) of a forward simulation: the activation dynamics da/dt(e, a) of the
        excitations e in u, and the Hill equilibrium solved for F' (the implicit tendon dynamics
        made explicit: mechanics.muscles.tendon_force_rate); u's a' and F' are not used."""
        return ca.vertcat(*[ca.vertcat(self.leg.activation_rate(e, a),
                                       self._tendon_rate(self._joint(theta, k), self._joint(thetad, k), a, F))
                            for k, (a, F, e, _, _) in enumerate(self._legs(z, u))])

    @cached_property
    def _tendon_rate(self) -> ca.Function:
        return hill.tendon_force_rate(self.muscles)

    def joint_passive(self, js, theta):
        """The joints' generalised passive moments (N m, 9): the range walls alone
        (mechanics.joint_space's `limits`), since the muscles' parallel elements hold their own
        passive force, which Riener & Edrich's relaxed-leg moments include too. With both, the
        hip's passive moment swung the leg (20.6 J taken at the stance hip, 15.4 J returned at the
        swing hip, 3.5 m/s) and the cadence rose to 166 / 202 / 219 steps/min at 2.5 / 3.5 / 4.5 m/s
        (problems/muscle_passive.py, 2026-11-27)."""
        return js.limits(theta)

    def initial(self, theta, thetad, tau):
        """(z, u) of a guess that makes the moments tau (N m, 6 x c) at node angles and rates
        theta, theta' (9 x c): per node the least-squares tendon forces F >= 0 with
        moments(F) = tau (scipy's nnls, a small penalty MIN_FORCE_PENALTY |F|^2), then the
        activation that holds the Hill equilibrium with them (F' = 0), in [0.01, 1]; e = a."""
        from scipy.optimize import nnls  # here: scipy.optimize costs 0.3 s at every CLI start

        n, c = self.n, theta.shape[1]
        arm = -np.asarray(self.muscles.moment_arms).T * self.muscles.max_force  # (3, n) N m per F
        system = np.vstack([arm, MIN_FORCE_PENALTY * np.eye(n)])
        z, u = np.zeros((4 * n, c)), np.zeros((6 * n + NU, c))
        for k in range(2):
            joints = slice(3 + 3 * k, 6 + 3 * k)
            F = np.column_stack([nnls(system, np.r_[tau[3 * k:3 * k + 3, j], np.zeros(n)])[0] for j in range(c)])
            F = np.clip(F, 0.0, 1.5)
            a = np.column_stack([hill.holding_activation(self.muscles, theta[joints, j], thetad[joints, j], F[:, j])
                                 for j in range(c)])
            z[2 * n * k:2 * n * (k + 1)] = np.vstack([a, F])
            u[3 * n * k:3 * n * k + n] = a
        return z, u


def actuation(mass: float, limit: float, tendons: dict, muscles: hill.Muscles | None = None,
              dynamic: bool = False, rate_smoothing: float = ACTIVATION_RATE_SMOOTHING,
              velocity: bool = False) -> Torques:
    """The actuation model of a stride's settings: muscles where given (their activation rates'
    smoothing scale `rate_smoothing`, 1/s), else torques (moment dynamics with `dynamic`, the
    torque-velocity limit with `velocity`), with springs where tendons are set."""
    if muscles is not None:
        return MuscleDriven(mass, muscles, rate_smoothing)
    if any(tendons.values()):
        return TorquesWithSprings(mass, limit, tendons, dynamic, velocity)
    return Torques(mass, limit, dynamic, velocity)
