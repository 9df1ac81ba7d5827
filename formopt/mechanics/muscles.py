"""Hill-type muscle-tendon units of one planar leg: gait2d's eight muscles in De Groote's form.

The muscles (Ackermann & van den Bogert 2010, J Biomech 43:1055, the gait2d model; `MUSCLES`):
iliopsoas, glutei, hamstrings, rectus femoris, vasti, gastrocnemius, soleus and tibialis
anterior, each a contractile element with a parallel elastic element in series with a compliant
tendon, without pennation (gait2d has none). The parameters are gait2d's (`from_gait2d`; the table,
io/data/gait2d_muscles.csv, is BioMAC-Sim-Toolbox's gait2dc_par.xls, Apache-2.0); the formulation,
the tendon and the force-velocity curve are De Groote et al. 2016's (Ann Biomed Eng 44:2922,
supplementary material). The force-length curves of the fibres are gait2d's, per muscle: its
widths and parallel-element slack lengths belong to its constant moment arms (with De Groote's
single narrow curve, at 62 kg and 1.81 m, rectus femoris would pull 4.3 F_max passively at knee
120 deg, hip 0 deg (gait2d's: 0.46), and the hip extensors hold 22 N m at hip 0 deg (224)).
The fast-twitch fractions are gait2d's, within 0.05 of the group means of Uchida et al. 2016
(PLoS ONE, as 3dpredictsim tabulates them) except the hamstrings (0.35 against 0.50).

Joint angles theta = [hip, knee, ankle] (rad) follow design.md section 2: hip flexion, knee
flexion and ankle dorsiflexion positive, the ankle 0 with the foot perpendicular to the shank.
gait2d measures each angle counter-clockwise with the body facing +x (its file: "moment arm
positive when the muscle swings the distal segment anteriorly"), so its hip and ankle angles are
formopt's and its knee angle is minus formopt's knee flexion (gait2d's knee range is -160..0
deg): theta_gait2d = `GAIT2D_SIGNS` * theta, and formopt's flexion moment arms are
r = `GAIT2D_SIGNS` * d_gait2d. With these, per muscle (lengths in m, forces in N):

    l_MT = L0 - r . theta                  (constant moment arms: gait2d's path model)
    v_MT = -r . theta'
    l_T  = l_Ts (ln(5 (F + 0.25)) / 35 + 0.995),  v_T = l_Ts F' / (35 (F + 0.25))
    l_M  = l_MT - l_T,  v_M = v_MT - v_T,  l~ = l_M / l_opt,  v~ = v_M / v_max
    0    = a f_L(l~) f_V(v~) + f_PE(l~) + beta v~ - F          (Hill equilibrium, cos(alpha) = 1)
    tau  = -r^T (F_max F)                  (joint moments, extensor / plantarflexor positive)

F is the normalised tendon force (a state), F' its rate (a control) and a the activation (a
state): the implicit tendon dynamics of De Groote et al. 2016, whose formulation with F as a
state converged from every initial guess tried there. `tau` is mechanics.joint_space's joint
moment (extension of hip and knee, plantarflexion of the ankle positive; the generalised force
on the flexion angles is -tau).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

import casadi as ca
import numpy as np

MUSCLES = ("iliopsoas", "glutei", "hamstrings", "rectus_femoris", "vasti", "gastrocnemius",
           "soleus", "tibialis_anterior")
JOINTS = ("hip", "knee", "ankle")
GAIT2D_SIGNS = np.array([1.0, -1.0, 1.0])  # theta_gait2d = GAIT2D_SIGNS * theta (hip, knee, ankle)
# The body gait2dc_par.xls is made for (its Height and Mass rows).
REFERENCE_HEIGHT = 1.8  # m
REFERENCE_MASS = 75.0  # kg
STRENGTH_EXPONENT = 2.0 / 3.0  # F_max ~ mass^(2/3): see `from_gait2d`

# -- De Groote et al. 2016, supplementary material ------------------------------------------
# Force-velocity: f_V = d1 ln(d2 v + d3 + sqrt((d2 v + d3)^2 + 1)) + d4, v in v_max.
FORCE_VELOCITY = (-0.318323436899127, -8.149156043475250, -0.374121508647863, 0.885644059915004)
# Tendon: F = c1 exp(kT (l_T / l_Ts - c2)) - c3.
TENDON_C1, TENDON_C2, TENDON_C3, TENDON_K = 0.2, 0.995, 0.25, 35.0
MAX_VELOCITY = 10.0  # v_max, optimal fibre lengths per second (De Groote et al. 2016)
# Fibre damping beta (F_max per v_max): Falisse et al. 2019 (J R Soc Interface 16:20190402,
# 3dpredictsim): keeps the equilibrium's derivative in F' away from zero when a = 0.
DAMPING = 0.01
# Activation dynamics (De Groote et al. 2016, eq. 1-2, and their time constants).
ACTIVATION_TIME, DEACTIVATION_TIME = 0.015, 0.060  # s
ACTIVATION_SMOOTHING = 10.0  # b; see `activation_rate`
PASSIVE_SMOOTHING = 0.05  # l_opt: the parallel element's slack corner, rounded (f_PE = 6e-4 there)

# -- Bhargava et al. 2004 (J Biomech 37:81), smooth as in 3dpredictsim -----------------------
MUSCLE_DENSITY = 1059.7  # kg/m^3 (Mendez & Keys 1960, Metabolism 9:184; OpenSim's probes' default)
SPECIFIC_TENSION = 0.25e6  # Pa (OpenSim's metabolic probes' default, BioMAC's getEratec_bhargava)
ACTIVATION_HEAT = (40.0, 133.0)  # W/kg, slow / fast twitch (Bhargava et al. 2004)
MAINTENANCE_HEAT = (74.0, 111.0)  # W/kg, slow / fast twitch (Bhargava et al. 2004)
SHORTENING_HEAT = (0.16, 0.18, 0.157)  # of F_iso, of F_M (shortening); of F_M (lengthening)
MINIMUM_HEAT = 1.0  # W per kg of muscle (OpenSim's Bhargava2004MuscleMetabolicsProbe)
SMOOTHING_VELOCITY = 0.01  # m/s: the tanh switches of the heat rates (b = 1/0.01 = 100 s/m)


@dataclass(frozen=True)
class Muscles:
    """The muscle-tendon units of one leg (arrays of shape (n,), moment arms (n, 3))."""

    names: tuple[str, ...]
    max_force: np.ndarray  # N, F_max
    optimal_fibre_length: np.ndarray  # m, l_opt
    width: np.ndarray  # l_opt: f_L = exp(-((l~ - 1) / width)^2)
    passive_slack: np.ndarray  # l_opt: the parallel element's slack length
    passive_stiffness: np.ndarray  # F_max / l_opt^2
    tendon_slack_length: np.ndarray  # m, l_Ts
    length_at_zero: np.ndarray  # m, L0: the unit's length at theta = 0
    moment_arms: np.ndarray  # m, r: flexion (hip, knee) / dorsiflexion (ankle) moment arms
    fast_twitch: np.ndarray  # fraction of fast-twitch fibres

    @property
    def max_velocity(self) -> np.ndarray:
        """v_max (m/s) = MAX_VELOCITY * l_opt."""
        return MAX_VELOCITY * self.optimal_fibre_length

    @property
    def volume(self) -> np.ndarray:
        """Fibre volume (m^3) = F_max l_opt / sigma (physiological cross-section times l_opt)."""
        return self.max_force * self.optimal_fibre_length / SPECIFIC_TENSION

    @property
    def mass(self) -> np.ndarray:
        """Muscle mass (kg) = density * volume."""
        return MUSCLE_DENSITY * self.volume


def from_gait2d(table: Mapping[str, np.ndarray], mass: float = REFERENCE_MASS,
                height: float = REFERENCE_HEIGHT) -> Muscles:
    """gait2d's muscles (`table`: its columns, gait2d's names, units and signs, one value per
    muscle in the order of `MUSCLES`) scaled to a body of `mass` (kg) and `height` (m).

    Lengths (l_opt, l_Ts, L0, moment arms) scale with height; maximal forces with
    (mass / 75 kg)^(2/3): geometric similarity, the exponent strength follows across body sizes
    (Jaric 2002, Sports Med 32:615; Markovic & Jaric 2004, Eur J Appl Physiol 92:139). With force
    proportional to mass every stride would be the same per kg; with mass^(2/3) a heavier runner
    of the same height is weaker per kg. The reference body is gait2dc_par.xls's (1.8 m, 75 kg).
    """
    def column(key: str) -> np.ndarray:
        return np.asarray(table[key], float)

    length = height / REFERENCE_HEIGHT
    return Muscles(
        names=MUSCLES,
        max_force=column("Fmax") * (mass / REFERENCE_MASS) ** STRENGTH_EXPONENT,
        optimal_fibre_length=column("Lceopt") * length,
        width=column("Width"),
        passive_slack=column("PEEslack"),
        passive_stiffness=column("kPEE"),
        tendon_slack_length=column("SEEslack") * length,
        length_at_zero=column("L0") * length,
        moment_arms=np.column_stack([column(f"dR{j}") for j in JOINTS]) * GAIT2D_SIGNS * length,
        fast_twitch=column("%FT/100"))


def subset(muscles: Muscles, names: tuple[str, ...]) -> Muscles:
    """The named muscles only (in the order given)."""
    index = [muscles.names.index(name) for name in names]
    arrays = {key: getattr(muscles, key)[index] for key in
              ("max_force", "optimal_fibre_length", "width", "passive_slack", "passive_stiffness",
               "tendon_slack_length", "length_at_zero", "moment_arms", "fast_twitch")}
    return replace(muscles, names=tuple(names), **arrays)


# -- the normalised curves (any CasADi or float argument, element-wise) ---------------------
def _smooth_max(x, y, width):
    """max(x, y), smoothed over `width` (the hyperbola (x + y + sqrt((x - y)^2 + width^2)) / 2)."""
    return 0.5 * (x + y + ca.sqrt((x - y) ** 2 + width**2))


def active_force_length(length, width):
    """f_L(l~) = exp(-((l~ - 1) / width)^2): gait2d's active force at full activation per F_max,
    l~ = l_M / l_opt (1 at l~ = 1, 1/e at 1 +- width)."""
    return ca.exp(-(((length - 1.0) / width) ** 2))


def force_velocity(velocity):
    """f_V(v~): v~ = v_M / v_max, lengthening positive; 0 at v~ = -1, 1 at 0, 1.8 at +1."""
    d1, d2, d3, d4 = FORCE_VELOCITY
    return d1 * ca.asinh(d2 * velocity + d3) + d4


def passive_force_length(length, slack, stiffness):
    """f_PE(l~) = k s(l~ - slack)^2: gait2d's parallel element (k = 1: F_max at 1 l_opt beyond
    slack), s(x) = (x + sqrt(x^2 + w^2)) / 2 rounding its corner over w = `PASSIVE_SMOOTHING`."""
    return stiffness * _smooth_max(length - slack, 0.0, PASSIVE_SMOOTHING) ** 2


def tendon_force(length):
    """F(l~_T): tendon force per F_max, l~_T = l_T / l_Ts (1.0 at 4.7 % strain)."""
    return TENDON_C1 * ca.exp(TENDON_K * (length - TENDON_C2)) - TENDON_C3


def tendon_length(force):
    """l~_T(F): the inverse of `tendon_force` (F > -0.25)."""
    return ca.log((force + TENDON_C3) / TENDON_C1) / TENDON_K + TENDON_C2


# -- one leg's units ----------------------------------------------------------------------
def mtu_lengths(muscles: Muscles, angles):
    """l_MT = L0 - r theta (m, shape (n,)) for theta = [hip, knee, ankle] (rad)."""
    return ca.DM(muscles.length_at_zero) - ca.mtimes(ca.DM(muscles.moment_arms), angles)


def mtu_velocities(muscles: Muscles, rates):
    """v_MT = -r theta' (m/s, shape (n,), lengthening positive)."""
    return -ca.mtimes(ca.DM(muscles.moment_arms), rates)


def fibre_state(muscles: Muscles, angles, rates, force, force_rate):
    """(l~, v~): normalised fibre length and velocity (v_max, lengthening positive), shape (n,).

    From the joint angles and rates (rad, rad/s) and the tendon state: normalised force F and
    its rate F' (1/s). The tendon's length follows from F, its velocity from F' (no pennation).
    """
    slack = ca.DM(muscles.tendon_slack_length)
    tendon = slack * tendon_length(force)
    tendon_velocity = slack * force_rate / (TENDON_K * (force + TENDON_C3))
    fibre = mtu_lengths(muscles, angles) - tendon
    fibre_velocity = mtu_velocities(muscles, rates) - tendon_velocity
    return fibre / ca.DM(muscles.optimal_fibre_length), fibre_velocity / ca.DM(muscles.max_velocity)


def hill_residual(muscles: Muscles, activation, angles, rates, force, force_rate):
    """The Hill equilibrium a f_L f_V + f_PE + beta v~ - F (per F_max, shape (n,)); 0 on a path."""
    length, velocity = fibre_state(muscles, angles, rates, force, force_rate)
    fibre = (activation * active_force_length(length, ca.DM(muscles.width)) * force_velocity(velocity)
             + passive_force_length(length, ca.DM(muscles.passive_slack),
                                    ca.DM(muscles.passive_stiffness))
             + DAMPING * velocity)
    return fibre - force


def tendon_force_rate(muscles: Muscles) -> ca.Function:
    """(theta (3), theta' (3), a (n), F (n)) -> F' (n, 1/s): `hill_residual` = 0 solved for the
    tendon forces' rates, the explicit form of the implicit tendon dynamics (a forward simulation's
    right-hand side). The residual falls monotonically with F' (a faster-stretching tendon leaves
    a slower fibre, and f_V and the damping rise with the fibre's velocity); Newton from F' = 0
    (CasADi's rootfinder, which raises where it does not converge; its evaluation warnings off:
    a replay from outside the muscles' domain printed one per Newton step, thousands)."""
    n = len(muscles.names)
    angles, rates = ca.SX.sym("theta", 3), ca.SX.sym("theta_dot", 3)
    act, force, rate = ca.SX.sym("a", n), ca.SX.sym("F", n), ca.SX.sym("F_dot", n)
    residual = ca.Function("residual", [rate, ca.vertcat(angles, rates, act, force)],
                           [hill_residual(muscles, act, angles, rates, force, rate)])
    solver = ca.rootfinder("tendon_rate", "newton", residual, {"abstol": 1e-10, "max_iter": 50,
                                                               "show_eval_warnings": False})
    return ca.Function("tendon_force_rate", [angles, rates, act, force],
                       [solver(ca.DM.zeros(n), ca.vertcat(angles, rates, act, force))])


def joint_moments(muscles: Muscles, force):
    """tau = -r^T (F_max F) (N m, shape (3,)): hip and knee extension, ankle plantarflexion +."""
    return -ca.mtimes(ca.DM(muscles.moment_arms).T, ca.DM(muscles.max_force) * force)


def activation_rate(excitation, activation, smoothing: float = ACTIVATION_SMOOTHING):
    """da/dt (1/s) for excitation e and activation a (De Groote et al. 2016, eq. 1-2):

        da/dt = [(f + 1/2) / (tau_a (1/2 + 3a/2)) + (1/2 - f) (1/2 + 3a/2) / tau_d] (e - a),
        f = tanh(b (e - a)) / 2.

    b = 10 here: De Groote et al. used b = 0.1, with which the two time constants blend almost
    evenly (f <= 0.05); with b = 10 activation is fast and deactivation slow as intended.
    """
    scale = 0.5 + 1.5 * activation
    switch = 0.5 * ca.tanh(smoothing * (excitation - activation))
    return ((switch + 0.5) / (ACTIVATION_TIME * scale)
            + (0.5 - switch) * scale / DEACTIVATION_TIME) * (excitation - activation)


def holding_activation(muscles: Muscles, angles, rates, force) -> np.ndarray:
    """The activation (shape (n,), in [0.01, 1]) that holds the Hill equilibrium at tendon
    forces F (F_max) with F' = 0 and angles and rates theta, theta' (3): `hill_residual` solved
    for a, a = (F - f_PE - beta v~) / (f_L f_V), clipped (f_L f_V at least 1e-3)."""
    length, velocity = (np.asarray(v, float).ravel() for v in fibre_state(muscles, angles, rates, force, 0.0))
    passive = np.asarray(passive_force_length(length, muscles.passive_slack, muscles.passive_stiffness), float).ravel()
    active = np.asarray(active_force_length(length, muscles.width) * force_velocity(velocity), float).ravel()
    return np.clip((force - passive - DAMPING * velocity) / np.maximum(active, 1e-3), 0.01, 1.0)


def isometric_force(muscles: Muscles, activation, angles) -> np.ndarray:
    """The tendon force F (per F_max, shape (n,)) that holds the equilibrium at rest
    (theta' = 0, F' = 0) for activation a (n,) and angles theta (3,): Newton's method
    (CasADi's rootfinder) on `hill_residual`."""
    n = len(muscles.names)
    force = ca.SX.sym("force", n)
    residual = hill_residual(muscles, ca.DM(activation), ca.DM(angles), ca.DM.zeros(3), force, 0.0)
    solver = ca.rootfinder("isometric", "newton", ca.Function("g", [force], [residual]),
                           {"abstol": 1e-12, "max_iter": 100})
    return np.asarray(solver(ca.DM.ones(n) * 0.5)).ravel()


# -- what the muscles cost --------------------------------------------------------------
def maintenance_length_factor(length):
    """Bhargava's length dependence of the maintenance heat, smoothed: 0.5 below l~ = 0.5, l~ up
    to 1, 3 - 2 l~ up to 1.5, 0 beyond (OpenSim's Bhargava2004MuscleMetabolicsProbe default)."""
    rising = _smooth_max(length, 0.5, 0.02)
    falling = _smooth_max(3.0 - 2.0 * length, 0.0, 0.02)
    return -_smooth_max(-rising, -falling, 0.02)


def metabolic_terms(muscles: Muscles, activation, length, velocity) -> dict:
    """Bhargava et al. 2004's rates (W, each of shape (n,); `metabolic_rate` says how):
    activation heat A, maintenance heat M, shortening heat S and positive fibre work W."""
    mass, fast = ca.DM(muscles.mass), ca.DM(muscles.fast_twitch)
    slow_recruited = (1.0 - fast) * ca.sin(0.5 * math.pi * activation)
    fast_recruited = fast * (1.0 - ca.cos(0.5 * math.pi * activation))
    isometric = activation * active_force_length(length, ca.DM(muscles.width)) * ca.DM(muscles.max_force)
    contractile = isometric * force_velocity(velocity)
    fibre = contractile + ca.DM(muscles.max_force) * passive_force_length(
        length, ca.DM(muscles.passive_slack), ca.DM(muscles.passive_stiffness))
    speed = velocity * ca.DM(muscles.max_velocity)
    lengthening = 0.5 + 0.5 * ca.tanh(speed / SMOOTHING_VELOCITY)
    short_a, short_b, long_c = SHORTENING_HEAT
    return {"activation": mass * (ACTIVATION_HEAT[0] * slow_recruited + ACTIVATION_HEAT[1] * fast_recruited),
            "maintenance": mass * maintenance_length_factor(length) * (
                MAINTENANCE_HEAT[0] * slow_recruited + MAINTENANCE_HEAT[1] * fast_recruited),
            "shortening": -((short_a * isometric + short_b * fibre) * (1.0 - lengthening)
                            + long_c * fibre * lengthening) * speed,
            "work": -contractile * speed * (1.0 - lengthening)}


def metabolic_rate(muscles: Muscles, activation, length, velocity):
    """Metabolic energy rate (W, shape (n,)) of Bhargava et al. 2004 in a smooth form:

        E' = max(A + M + S, 1 W/kg * m_M) + W,  W = max(0, -F_CE v_M)
        A  = m_M (40 (1 - f) sin(pi a / 2) + 133 f (1 - cos(pi a / 2)))
        M  = m_M g(l~) (74 (1 - f) sin(pi a / 2) + 111 f (1 - cos(pi a / 2)))
        S  = -(0.16 F_iso + 0.18 F_M) v_M shortening,  -0.157 F_M v_M lengthening

    with m_M the muscle's mass (`Muscles.mass`), f its fast-twitch fraction, F_iso = a f_L F_max,
    F_CE = F_iso f_V, F_M = F_CE + f_PE F_max the fibres' force and v_M = v~ v_max (m/s,
    lengthening positive). As 3dpredictsim's getMetabolicEnergySmooth2004all (Falisse et al.
    2019) and OpenSim's Bhargava2004MuscleMetabolicsProbe: the shortening heat's force-dependent
    coefficient, the activation heat's decay 1, the fibres recruited by activation instead of
    excitation; the switches are tanh over `SMOOTHING_VELOCITY`, the corners hyperbolae over
    0.02 l_opt (g) and 0.1 W/kg (the floor). No basal rate. The terms: `metabolic_terms`.
    """
    mass = ca.DM(muscles.mass)
    terms = metabolic_terms(muscles, activation, length, velocity)
    heat = terms["activation"] + terms["maintenance"] + terms["shortening"]
    return _smooth_max(heat / mass, MINIMUM_HEAT, 0.1) * mass + terms["work"]


def activation_cost(muscles: Muscles, activation, power: float = 3.0):
    """sum_i V_i a_i^p / sum_i V_i: the volume-weighted mean of the activations to the power p
    (dimensionless, 0..1). p = 3, the endurance criterion of Crowninshield & Brand 1981
    (J Biomech 14:793); volume weighting as Ackermann & van den Bogert 2010."""
    volume = ca.DM(muscles.volume / muscles.volume.sum())
    return ca.dot(volume, activation**power)


# |F'| as sqrt(F'^2 + eps^2) - eps (1/s) in the force-rate cost's power 1: zero at zero, within
# eps of |F'| and smooth for IPOPT. A stance muscle's tendon force rises and falls at 3-20 /s
# (0 to 0.5-1 of F_max in 50-150 ms), so eps = 0.5 /s charges those rates within 3-15 % of
# |F'|; below eps the cost turns quadratic (F'^2 / (2 eps)), where the slack muscles' small
# rates sit.
FORCE_RATE_SMOOTHING = 0.5


def force_rate_cost(muscles: Muscles, force_rate, power: int = 2):
    """sum_i V_i |F'_i|^p / sum_i V_i (1/s^p): the volume-weighted mean of the normalised tendon
    forces' rates F' (1/s) to the power p, a cost of generating force quickly in the active
    muscle volume (Kipp, Grabowski & Kram 2018, J Exp Biol 221:jeb184218). p = 2: F'^2, smooth;
    p = 1: |F'| ~ sqrt(F'^2 + eps^2) - eps (FORCE_RATE_SMOOTHING), a loading to F and back costing
    2 F whatever its time, so per step F_peak ~ W T / t_c, Kram & Taylor 1990's 1 / t_c. Either
    charges a falling force as a rising one; a stand-in for Kipp's rate, not its equation."""
    return ca.dot(ca.DM(muscles.volume / muscles.volume.sum()), charged_force_rate(force_rate, power))


def charged_force_rate(force_rate, power: int = 2):
    """|F'|^p (1/s^p) of each rate F' (1/s) as `force_rate_cost` charges it: F'^2, or with p = 1
    sqrt(F'^2 + eps^2) - eps (FORCE_RATE_SMOOTHING); CasADi, elementwise."""
    if power == 1:
        eps = FORCE_RATE_SMOOTHING
        return ca.sqrt(force_rate**2 + eps**2) - eps
    return force_rate**2


@dataclass(frozen=True)
class LegFunctions:
    """One leg's muscles as CasADi Functions, the calls a stride makes per node.

    Inputs: theta (3) rad, theta' (3) rad/s [hip, knee, ankle]; a, F, F' (n); e (n).
    residual(theta, theta', a, F, F') -> (n)  the Hill equilibrium (`hill_residual`)
    moments(F) -> (3)                        N m, extensor / plantarflexor positive
    activation_rate(e, a) -> (n)             1/s
    metabolic_rate(theta, theta', a, F, F') -> (1)   W, summed over the leg's muscles
    activation_cost(a) -> (1)                the volume-weighted mean of a^3
    force_rate_cost(F') -> (1)               the volume-weighted mean of F'^2 (1/s^2)
    force_rate_abs(F') -> (1)                the volume-weighted mean of |F'| (1/s), smoothed
    """

    residual: ca.Function
    moments: ca.Function
    activation_rate: ca.Function
    metabolic_rate: ca.Function
    activation_cost: ca.Function
    force_rate_cost: ca.Function
    force_rate_abs: ca.Function


def leg_functions(muscles: Muscles) -> LegFunctions:
    """The CasADi Functions (SX) of `LegFunctions` for one leg's muscles."""
    n = len(muscles.names)
    angles, rates = ca.SX.sym("theta", 3), ca.SX.sym("theta_dot", 3)
    act, exc, force, rate = (ca.SX.sym(name, n) for name in ("a", "e", "F", "F_dot"))
    state = [angles, rates, act, force, rate]
    length, velocity = fibre_state(muscles, angles, rates, force, rate)
    return LegFunctions(
        residual=ca.Function("muscle_residual", state,
                             [hill_residual(muscles, act, angles, rates, force, rate)]),
        moments=ca.Function("muscle_moments", [force], [joint_moments(muscles, force)]),
        activation_rate=ca.Function("activation_rate", [exc, act], [activation_rate(exc, act)]),
        metabolic_rate=ca.Function("metabolic_rate", state,
                                   [ca.sum1(metabolic_rate(muscles, act, length, velocity))]),
        activation_cost=ca.Function("activation_cost", [act], [activation_cost(muscles, act)]),
        force_rate_cost=ca.Function("force_rate_cost", [rate], [force_rate_cost(muscles, rate)]),
        force_rate_abs=ca.Function("force_rate_abs", [rate], [force_rate_cost(muscles, rate, power=1)]))


def tendon_energy(muscles: Muscles, force) -> np.ndarray:
    """The elastic energy (J, shape (n,) or (n, k)) a tendon holds at normalised force F, the
    integral of De Groote's tendon curve from its slack length:

        E = F_max l_Ts [(F + c3 - c1 exp(kT (1 - c2))) / kT - c3 (l~_T - 1)],  l~_T = tendon_length(F)
    """
    force = np.asarray(force, float)
    shape = (-1,) + (1,) * (force.ndim - 1)
    stretch = np.asarray(tendon_length(ca.DM(force)), float).reshape(force.shape) - 1.0
    per_length = ((force + TENDON_C3 - TENDON_C1 * math.exp(TENDON_K * (1.0 - TENDON_C2))) / TENDON_K
                  - TENDON_C3 * stretch)
    return (muscles.max_force * muscles.tendon_slack_length).reshape(shape) * per_length
