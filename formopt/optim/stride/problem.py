"""The half stride as a multiphase problem: phases, transitions, objective, settings.

A half stride starts just after the leading foot's (R) touchdown impact and ends just before the
other foot's (L) touchdown. Phases per strike (`STRIKE_PHASES`), each with the contact rows it
holds (point, "t" tangential or "n" normal, on the ground of slope `slope`):

- heel:     heel -> [flat-foot impact] flat -> forefoot -> flight
- forefoot: landing (forefoot) -> [heel-drop impact] flat -> forefoot -> flight
- flat:     flat -> forefoot -> flight

A forefoot strike lets the heel come down (as RBDS001's forefoot strikes do): held on the
forefoot alone, the whole stance hangs on the ankle's moment, and the optimum was a hop of
0.06 s contact at 340-450 steps/min (2026-11-23, every objective).

A phase that adds a point starts with an impact (its point reaches the ground at the previous
phase's end, T_c counted); a phase that drops a point starts when that point's normal force
reaches zero (heel-off, toe-off). The flight ends with L's touchdown in the strike's first
contact set: the impact, then the legs swapped and moved back by one step must give the start.

On a flat foot, heel [t, n] and forefoot [n]: the foot's rigidity holds the forefoot's
tangential motion (the rows of mechanics.impact for a flat strike).

Under Coulomb a touchdown may slide (`SLIDING_PHASES`, `StrideSettings.touchdown = "slide"`):
the impact in its sliding mode (p_t = -s mu p_n, the point's normal velocity zero after it,
the tangential free with the sign s of the slip), then a `slide` phase (the point on the
ground, tangential force -s mu f_n, s v_t >= 0, s = `StrideSettings.slip` fixed) that ends
when v_t reaches zero; the strike's sticking sequence follows. A flat touchdown has no sliding variant (two points share
the slip: velocity_level's law, checked after the solve).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...mechanics.errors import InputError
from ...mechanics.muscles import Muscles
from .actuation import ACTIVATION_RATE_SMOOTHING, springs
from .contact import CLEARANCE
from .ranges import RANGES, check


@dataclass(frozen=True)
class Phase:
    """One phase: its name and the contact rows it holds ((point, "t" | "n"), ...)."""

    name: str
    rows: tuple[tuple[str, str], ...]
    sliding: str = ""  # the point that slides (its "t" row carries -s mu f_n, not a constraint)

    @property
    def points(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(p for p, _ in self.rows))


HEEL = Phase("heel", (("heel_R", "t"), ("heel_R", "n")))
FLAT = Phase("flat", (("heel_R", "t"), ("heel_R", "n"), ("forefoot_R", "n")))
FOREFOOT = Phase("forefoot", (("forefoot_R", "t"), ("forefoot_R", "n")))
LANDING = Phase("landing", FOREFOOT.rows)  # a forefoot strike's first contact
FLIGHT = Phase("flight", ())
STRIKE_PHASES = {"heel": (HEEL, FLAT, FOREFOOT, FLIGHT), "forefoot": (LANDING, FLAT, FOREFOOT, FLIGHT),
                 "flat": (FLAT, FOREFOOT, FLIGHT)}
STRIKES = tuple(STRIKE_PHASES)
# the phase lists of a touchdown that slides: the slide of the strike's first point, then its
# sticking sequence
SLIDING_PHASES = {strike: (Phase("slide", phases[0].rows, sliding=phases[0].rows[0][0]), *phases)
                  for strike, phases in STRIKE_PHASES.items() if len(phases[0].points) == 1}
TOUCHDOWN_MODES = ("stick", "slide")
# Share of the nodes per phase (normalised over a strike's phases): about RBDS001's durations
# at 3.5 m/s (heel contact 0.03 s, flat 0.12 s, forefoot 0.09 s, flight 0.11 s), with at least
# MIN_NODES each, since a short phase still needs its start and end conditions.
NODE_SHARE = {"slide": 0.12, "heel": 0.12, "landing": 0.12, "flat": 0.3, "forefoot": 0.25, "flight": 0.33}
MIN_NODES = 4
OBJECTIVES = ("effort", "work", "metabolic", "joint-metabolic", "activation")
# The actuation ladder (actuation.py): torque sources, with springs in parallel (`tendons`), or
# muscles (`muscles`). The muscles take "metabolic" (their own energy, Bhargava et al. 2004, plus
# FORCE_RATE_WEIGHT times their squared force rates) or "activation"; the torque rungs the others
# ("joint-metabolic": Minetti & Alexander's muscle at each joint, costs.joint_metabolic_rate).
ACTUATIONS = ("torque", "torque+springs", "muscles")
MUSCLE_OBJECTIVES = ("metabolic", "activation")
TRANSCRIPTIONS = ("trapezoid", "hermite-simpson")  # transcription.py's
# StrideSettings.consistency_rows' forms (the comment at the field says what each imposes)
CONSISTENCY_ROWS = ("exact", "trapezoid", "off")
# m/s^2: with consistency_rows "trapezoid", a released point's height at the next phase's first
# column (its held drift) at least -RELEASE_DRIFT h^2 (h the held phase's last interval): the trapezoid's
# own drift there, -5 to -21 h^2 at RBDS001's heel 3.5 m/s optimum without the rows (40 / 80 / 160
# nodes; problems/stride_mesh.py prints it), within the bound, so no column is forced to meet it.
RELEASE_DRIFT = 40.0
# Margaria R. (1968) Int Z angew Physiol 25:339: efficiencies of positive and negative muscle work
EFFICIENCY_POSITIVE = 0.25
EFFICIENCY_NEGATIVE = 1.2
# The work objectives split each joint's power exactly with two slack variables per joint and
# node, P = P+ - P-, P+ and P- >= 0, their weighted sum minimised (Bryson's split): both parts
# end exact, no smoothing width to choose. The smooth split the brief proposed,
# (P + sqrt(P^2 + eps^2)) / 2 with eps = 1 W (and 5 W), left IPOPT short of convergence after
# 1000 iterations in every work and metabolic solve tried (2026-11-23); with the slacks they
# converge in about 250.
# the work objectives leave a joint moment that does no work free: a small effort term (this
# weight times the effort objective) makes the optimum unique
WORK_REGULARISATION = 1e-2
# The trapezoidal rule cannot see accelerations that alternate node to node (their interval
# means cancel): the light feet used such a sawtooth at the acceleration bound, which the
# forward simulation does not reproduce (0.2 rad off in a phase at 24 nodes). A small penalty
# on the squared change of the accelerations between nodes, SMOOTHING * sum h |A_k+1 - A_k|^2
# per distance (s^3/m), removes it. It is not negligible on a coarse trapezoid mesh: 13 % of the
# objective at 40 nodes, 8 % at 80, 3 % with Hermite-Simpson at 20 intervals (RBDS001, heel,
# torque+springs, effort, 3.5 m/s at 130 steps/min: problems/stride_smoothing.py, 2026-11-25),
# one reason the trapezoid's optimum moves with the mesh (docs/concepts/stride.md). Hermite-Simpson
# smooths the accelerations' curvature within each interval instead (transcription.HermiteSimpson:
# its null mode, not a smooth motion): 1.0 / 0.2 / 0.08 % of the objective at 20 / 40 / 80
# intervals, where the change between columns took 3.1 / 1.3 / 0.4 % (the same stride, release
# rows gone: problems/stride_mesh.py, 2026-11-26); without any smoothing its swing ankle
# oscillates column to column and the forward check fails (1.45 rad at 20 intervals). A larger
# weight is not what Hermite-Simpson's slow descents with moment dynamics need (12 ms, 5 cm/s
# approach floor, 3.5 m/s, free cadence; problems/stride_mesh.py --smoothing, 2026-11-27): at 1e-5
# Hermite-Simpson 40 took 1270 iterations (1002 at 1e-6) to 158.1 steps/min and +4.1 % of cost
# without the term (150.9 at 1e-6); at 1e-4 Hermite-Simpson 20 did not converge in 3000 (193).
# Nor is the free cadence: imposed at 150.9, Hermite-Simpson 40 converged in 124 iterations
# (0.5 % below the free solve's optimum at that cadence), but imposed at 155 it had not in 1500.
# With muscles the activations' rates join the accelerations, scaled by
# StrideSettings.activation_rate_smoothing (actuation.ACTIVATION_RATE_SMOOTHING).
SMOOTHING = 1e-6
# The one weight of the muscles' "metabolic" objective: FORCE_RATE_WEIGHT times the force-rate
# term (costs.FORCE_RATE_SCALE: the volume-weighted squared tendon-force rates per distance, Kipp
# et al. 2018's rate of force generation) beside the muscles' metabolic energy per distance (per
# m g). Bhargava's heat charges force held over time, about the same per metre in a short contact
# as in a long one, and left the cadence at 222 steps/min at 3.5 m/s against RBDS001's 171.4 (the
# activation weight this replaces, 0 / 1 / 10, moved it to 226 / 221 / 218). Calibrated once on
# RBDS001 at 3.5 m/s, 24 nodes (python problems/muscle_calibration.py --weights 16 32 64 80
# --steps 0: 188.1 / 185.2 / 174.6 / 174.3 steps/min; 160 gives 173.5, the reserves 0.54 N m/kg)
# and frozen; 2.5 and 4.5 m/s and a 75 kg body held out gave 145.4 / 181.5 and 173.4 steps/min
# (reserve weight 100, the joints' soft walls). With the reserves at 10000 (the muscles' joints
# still the range walls alone: actuation.MuscleDriven.joint_passive): 155.5 / 179.1 / 196.8 at
# 2.5 / 3.5 / 4.5 m/s, all valid (problems/stride_ladder.py --nodes 24 --rungs muscles,
# 2026-11-27; docs/concepts/muscles.md, "In the stride"); with Riener & Edrich's moments added to
# the muscles' own passive fibres 166.0 / 202.1 / 218.7: their passive elasticity counted twice.
# Solved on Hermite-Simpson, whose cadence moves about 1 % from 40 to 80 intervals, this weight
# gives 136.7 steps/min at 3.5 m/s on the forefoot phase's ceiling (notes.MUSCLE_HERMITE): what
# it fitted on the 24-node trapezoid may be that mesh's phase-end layers. Calibrated there instead
# (problems/muscle_calibration.py --transcription hermite-simpson --nodes 40, 2026-11-27) it is
# 11.9 (170.9 steps/min), and held out at 2.5 and 4.5 m/s (12, the global search on 40 intervals)
# it gives 202.6 and 151.1: a cadence that falls with speed. Neither weight is a runner's across
# speeds; this one stays until the cost is.
FORCE_RATE_WEIGHT = 80.0
# The force-rate term's power (StrideSettings.force_rate_power): 2, the squared rates above, or 1,
# their absolute values (mechanics.muscles.force_rate_cost: Kram & Taylor 1990's cost of force
# per contact time, docs/concepts/muscles.md "The force rate's power"), each with its own weight
# calibrated on RBDS001 at 3.5 m/s. Power 1's, 12, on the free optimum of the mesh near converged
# for cadence (graded 1, 80 nodes, the global search's on 40 solved again on 80: `cd problems &&
# python muscle_energy.py --speed 3.5 --grading 1 --nodes 80 --start search --power 1 --weight 12`):
# 170.8 steps/min against the runner's 171.4; bracketed warm from weight 120's stride (`--load
# --free`): 8 / 15 / 30 / 60 / 120 gave 179.9 / 168.2 / 164.1 / 161.6 / 159.4 (at 24 nodes the
# cadence stays above 175 at any weight: `python problems/muscle_calibration.py --power 1 --weights
# 30 60 120 240`, 187.5 / 180.0 / 175.7 from 60 up, so that mesh cannot calibrate it). On
# Hermite-Simpson 40 intervals 12 gives 156.9; calibrated there 6.9 (170.2), held out (one start
# each) 202.4 and 168.1 steps/min at 2.5 and 4.5 m/s: falling from 2.5 to 3.5 m/s, then about flat
# (2026-11-27, docs/concepts/muscles.md, "On Hermite-Simpson").
FORCE_RATE_POWERS = (1, 2)
FORCE_RATE_WEIGHTS = {2: FORCE_RATE_WEIGHT, 1: 12.0}


def force_rate_weight(power: int, weight: float | None = None) -> float:
    """The force-rate term's weight: `weight`, or (None) its power's calibrated one
    (FORCE_RATE_WEIGHTS)."""
    return FORCE_RATE_WEIGHTS[power] if weight is None else weight
# The muscles' reserve moments' weight (m/s per (N m/kg)^2; costs' `reserves` term): at 100,
# 1 N m/kg held over a step costs about 30, four to twelve times a stride's whole objective
# (2.4-7.1 with the force-rate term, RBDS001 at 2.5-4.5 m/s), at 10000 a hundred times that. The
# reserves pay no force rate: at 10 (set when the objective was about 0.5) they took 0.51 N m/kg
# at force-rate weight 16 and bought the low cadence (176.4 steps/min against 188.1 at 100;
# RBDS001, 3.5 m/s, 24 nodes, problems/muscle_calibration.py --weights 16 --steps 0
# --reserve-weight 10). At 100 they still buy the fast moment changes at the contact's events
# (0.18-0.58 N m/kg in bursts at 2.5-4.5 m/s, beyond the 0.1 tolerance: invalid strides); at
# 10000 the muscles make those moments (reserves 0.01-0.05 N m/kg, RBDS001, 24 nodes, valid), but
# only when the solve is continued from the optimum at 100: a cold solve at 10000 ended in a
# costlier optimum (192.9 steps/min at 3.5 m/s, objective 6.03 against 5.80 from 100, soft walls;
# docs/concepts/muscles.md, "Where the reserves act"). So the muscles' start
# (local.muscle_start) solves at each weight of RESERVE_CONTINUATION below the setting's, in turn,
# before the setting's own.
RESERVE_WEIGHT = 10000.0
RESERVE_CONTINUATION = (100.0,)
# Moment dynamics' time T (StrideSettings.moment_time, s): with effort the torque rungs pay
# int (tau^2 + T^2 tau'^2) dt (costs.py), whose Euler-Lagrange equation tau - T^2 tau'' = demand
# filters what the motion asks with the kernel exp(-|t|/T) / 2T: a step rises from 10 to 90 %
# in 2 ln 5 T = 3.2 T. A muscle's force rises in about 30-50 ms (activation 15 ms and
# deactivation 60 ms time constants, De Groote et al. 2016; twitch contraction times of
# 30-50 ms), so T = 40 ms / 3.2 = 12 ms; MOMENT_TIME_MAX bounds the setting. Off by default
# (StrideSettings.moment_time = 0): at 12 ms (RBDS001, heel, springs, free cadence, 2.5 / 3.5 /
# 4.5 m/s; problems/stride_mesh.py --moment-time 0.012, 2026-11-27) the trapezoid's cadence moved
# under 0.4 % from 40 to 80 nodes but its cost 5-10 %, and Hermite-Simpson's optima were another
# stride (131 / 151 / 166 steps/min against the trapezoid's 161 / 173 / 182), held by the forefoot
# phase's ceiling at 2.5 m/s or landing the forefoot grazing on the friction cone's edge (invalid),
# and not converged in 1000 iterations at 40 intervals.
MOMENT_TIME = 0.012
MOMENT_TIME_MAX = RANGES["moment_time_s"].high
# A least approach speed at every impact (StrideSettings.approach_speed, m/s), against the
# grazing touchdowns of Hermite-Simpson's optima: a point that reaches the ground at v_n- = 0
# takes a zero impulse, so p_n >= 0 and both cone rows mu p_n -+ p_t >= 0 hold with equality at
# once (four rows' gradients in three impulses: no unique multipliers), and formopt's check reads
# mu_c = |p_t| / p_n from round-off (0.81-7.5 at mu 0.8: invalid). 5 cm/s is a floor, not a
# runner's: RBDS001's forefoot reaches the ground at 0.64 m/s (median; least 0.11) and the heel at
# 0.32-0.59 m/s (problems/approach_speed.py). Measured (RBDS001, heel, springs, free cadence,
# problems/stride_mesh.py --cadence 0 --approach-speed 0.05, 2026-11-27): each grazing optimum
# made valid at a cost of 0.05-0.4 %, the floor active where it grazed; without moment dynamics
# Hermite-Simpson 40 at 2.5 m/s 124.9 steps/min (0.04309 against the grazing 0.04307; its forefoot
# phase on its 0.25 s ceiling), the trapezoid 40 at 3.5 m/s unmoved (169.5); with moment dynamics
# (12 ms) Hermite-Simpson 40 at 3.5 m/s 150.9 steps/min in 1002 iterations (the grazing one 150.8
# in 1102: the grazing does not make it slow, a descent at IPOPT's least barrier with the Hessian
# regularised at every step does), at 4.5 m/s 165.7 in 561 (124 s CPU; without the floor 165.8 in
# 2556, 415 s, a 0.09 % costlier optimum landing the forefoot at 3 mm/s), at 2.5 m/s not converged in 3000
# (705 s CPU, the objective still falling, no impact grazing, the forefoot phase on its 0.25 s
# ceiling). Held by the floor and the bounds, it stays off by default.
APPROACH_SPEED = 0.05


# Tendons: a spring in parallel with the stance leg's joint, engaged unloaded at the touchdown
# and released at toe-off, tau_spring = k m (theta - theta_touchdown) (extensor positive,
# k in N m/rad per kg). It stands for the elastic return of the stance's negative work
# (Achilles and patellar tendons, the arch) that a torque-driven model lacks: without it, the
# energy a joint absorbs is lost and must be paid again, so a rigid impact is a free brake.
# What the spring still holds at toe-off is lost (the clutch lets go): budget's `spring_J`.
TENDON_JOINTS = ("hip", "knee", "ankle")
# The tendons of a runner's scenes (N m/rad per kg), a share of the joints' stance
# quasi-stiffness that RBDS001 shows at 3.5 m/s (mechanics.landing.RUNNING_JOINTS, from the data
# set's inverse dynamics: knee 7.4, ankle 4.8 N m/rad per kg): about a third at the knee (mostly
# muscle) and most of it at the ankle (the Achilles tendon). Tried on RBDS001's body (heel
# strike, effort, 40 nodes, 2026-11-23): 5/8 at 3.5 m/s gave 152 steps/min and 0.18 s stance;
# these gave 159 steps/min, 0.238 s and 20.4 N/kg at 3.5 m/s (4 starts) against the runner's
# 171.4, 0.245 s and 23.5 N/kg, and rigid impacts of 1-8 J against 40-110 J without tendons.
# Chosen among two settings on one runner, not fitted: docs/concepts/stride.md.
RUNNER_TENDONS = {"knee": 2.5, "ankle": 4.0}
# The torque scenes' stride (formopt/scenes/stride.toml and stride_rbds001.toml; docs/concepts/
# stride.md, "The torque scenes on Hermite-Simpson", 2026-11-28): Hermite-Simpson at 40 intervals, the
# ankle's spring alone (RUNNER_ANKLE), the impacts' T_c charged at the metabolic price of the
# positive work that replaces it (RUNNER_IMPACT_WEIGHT = 1 / EFFICIENCY_POSITIVE, on the cost of
# transport's scale 1 / (m g d) that the metabolic objective uses: costs.py; the effort objective
# has no metabolic units, so the weight is borrowed from that scale, a choice), moment dynamics
# (MOMENT_TIME) and every impact approaching at least at APPROACH_SPEED. Why each part:
# - RUNNER_TENDONS' knee spring, engaged at touchdown and paid by no muscle, made Hermite-
#   Simpson's strides crouch (the stance knee to 79-103 deg, the spring's 3.9 N m/kg at 103 deg
#   against RBDS001's peak knee moment of 2.6-3.1; a runner's knee flexes to 37-44 deg);
# - without it and with the impacts free the strides land stiff (35-42 J a step); charged at
#   weight 1 a flat strike still lands with 35 J and is the least costly (its effort 40 % lower);
# - moments that jump let Hermite-Simpson's stance end with the forefoot pushing 0.4-2.1 body
#   weights (a runner's force falls to zero): with moment dynamics the release holds it at zero
#   (ocp.Release), and IPOPT converges in tens of iterations (ipopt_options.TORQUE_HERMITE_IPOPT);
# - without the approach floor the forefoot strike's heel comes down grazing (7.6 mm/s), where
#   the impulse and its cone's rows vanish together.
# What it gives, 40 -> 80 intervals, is optim.stride.notes.RUNNER_MESH's.
RUNNER_ANKLE = {"ankle": 4.0}
RUNNER_IMPACT_WEIGHT = 1.0 / EFFICIENCY_POSITIVE
RUNNER_TRANSCRIPTION, RUNNER_NODES = "hermite-simpson", 40  # their mesh (the scene files' [stride])


def other_leg(point: str) -> str:
    """heel_R <-> heel_L, forefoot_R <-> forefoot_L."""
    return point[:-1] + ("L" if point.endswith("R") else "R")


@dataclass(frozen=True)
class StrideSettings:
    """What the stride NLP is built with (SI); the speed, slope, friction and an imposed
    cadence are parameters of the built NLP (`StrideNLP.solve`)."""

    strike: str = "heel"
    objective: str = "effort"
    nodes: int = 40  # collocation intervals over the half stride
    law: str = "no-slip"  # contact law of the impacts (no-slip; coulomb: the mode checked, local.optimum)
    touchdown: str = "stick"  # the touchdown impact's mode: "slide" (coulomb) adds the slide phase
    slip: int = 1  # a sliding touchdown's slip sign s along the ground (+1 forward, -1 back)
    impact_weight: float = 0.0  # weight (1/m) of the impacts' summed T_c (and slide friction) per distance
    torque_limit: float = 4.0  # N m per kg of body mass, every joint
    # Each phase's duration bounds (s), a runner's from 2.5 to 6 m/s with room to spare, so that
    # no realistic optimum is held by them (a stride on one says so: bounds.on_bounds):
    # - contact about 0.30 s at 2.5 m/s and 0.24 s at 3.5 (RBDS001, Fukuchi et al. 2017, PeerJ
    #   5:e3298), 0.27 s at 3.5 to about 0.16 s at 7 m/s (Dorn, Schache & Pandy 2012, JEB 215:1944,
    #   Fig. 2B), 0.08-0.12 s only at sprinters' top speeds (Weyand et al. 2000, J Appl Physiol
    #   89:1991); Nummela et al. 2007 (Int J Sports Med 28:655) the same fall with speed;
    # - flight (aerial time) 0.09-0.14 s, nearly independent of speed (Weyand 2000; Dorn 2012),
    #   about 0.08 s for RBDS001 at 2.5 m/s (a 0.383 s step less its 0.30 s stance);
    # - the stance's parts, as shares of RBDS001's stance at 3.5 m/s (heel 0.03 s, flat 0.12 s,
    #   forefoot 0.09 s: NODE_SHARE's source): heel alone 12 %, flat foot 50 %, forefoot 38 %.
    # So over contacts of 0.14-0.33 s: heel (or a forefoot strike's landing) 0.01-0.1 s (under
    # 0.01 s the heel and the forefoot land as one, a flat strike: that strike is solved on its
    # own); flat 0.03-0.25 s; forefoot 0.03-0.25 s; flight 0.03-0.25 s. Their sum allows a contact
    # of 0.07-0.6 s. The slide (Coulomb's variant, problem.SLIDING_PHASES) is no runner's phase:
    # its bounds are numerical (0.5 ms, the slip may stop at once; 0.1 s).
    # Before 2026-11-25 the bounds were numerical (heel 0.005-0.1 s, the others 0.02-0.3 s); the
    # heel's 0.005 s floor held the paper body's heel optimum at 3.5 m/s and RBDS001's at 4.5 m/s.
    duration: dict = field(default_factory=lambda: {"slide": (0.0005, 0.1), "heel": (0.01, 0.1),
                                                    "landing": (0.01, 0.1), "flat": (0.03, 0.25),
                                                    "forefoot": (0.03, 0.25), "flight": (0.03, 0.25)})
    max_iter: int = 1000
    tolerance: float = 1e-6
    tendons: dict = field(default_factory=dict)  # joint ("hip", "knee", "ankle") -> N m/rad/kg
    transcription: str = "trapezoid"  # or "hermite-simpson" (transcription.TRANSCRIPTIONS)
    muscles: Muscles | None = None  # one leg's muscles scaled to the body: the "muscles" rung
    # the muscles' metabolic objective's one weight (calibration only; None: FORCE_RATE_WEIGHTS')
    force_rate_weight: float | None = None
    force_rate_power: int = 2  # the force-rate term's power (FORCE_RATE_POWERS)
    reserve_weight: float = RESERVE_WEIGHT  # the muscles' reserves' weight (a what-if only)
    # 1/s, >= 0: the muscles' activation rates' scale in the transcription's smoothing beside the
    # accelerations (actuation.MuscleDriven.smoothed; actuation.ACTIVATION_RATE_SMOOTHING says why
    # 10); 0 leaves their null mode open: a stalled refinement's first step (refine.continued)
    activation_rate_smoothing: float = ACTIVATION_RATE_SMOOTHING
    # s, > 0: the torque rungs' moments as states, their squared rates weighed by its square
    # (actuation.Torques, costs.py: the time below which a change costs more than its moment)
    moment_time: float = 0.0
    # the torque rungs' limit falling with the joint's rate as its muscles' force does
    # (actuation.Torques.rows, JOINT_MAX_RATE)
    torque_velocity: bool = False
    clearance: float = CLEARANCE  # m: the swing foot's least height while the other holds the ground
    # m/s, >= 0: each impact's points reach the ground at least this fast (v_n- <= -approach_speed;
    # 0, the default, allows a grazing touchdown, where the impulse and its friction cone's rows
    # vanish together). APPROACH_SPEED says what it does and why it stays off.
    approach_speed: float = 0.0
    # The rows that hold the transcription's own errors at the phase ends, which the continuous
    # stride meets by itself: with springs the held contacts' work and the energy budget
    # (collocation), a released point's height at the next phase's first column (its held drift),
    # a torque source's released f_n = 0 at its phase's last column (ocp.Release). "exact": each
    # = 0 (>= 0 for the height), met by the trapezoid through one-column layers of the moments at
    # the phase ends (1.1-1.6 N m/kg at every mesh) whose cost falls as O(h): RBDS001, heel,
    # springs, 3.5 m/s, the durations held at the shipped 40-node optimum's, the cost moves -14.5
    # and -7.8 % from 40 to 80 to 160 nodes. "trapezoid": each as the trapezoid meets it, none
    # forcing a column: the held work <= 0 and the budget >= 0 (the transcription may absorb
    # energy, not give it), the height >= -RELEASE_DRIFT h^2, no f_n = 0 row (a torque source
    # lets go by a jump of its moments); -3.3 and -1.2 % (p 1.54). "off": none; -3.3 and -1.4 %.
    # The last two to the same limit (0.171) but not on the free optimum: there they leave the
    # shipped stride for a cheaper one with grazing landings (159 -> 140 steps/min), which the
    # exact rows hold off only at coarse meshes (docs/concepts/stride.md, "Rows the continuous
    # stride meets by itself"). "exact" by default: every shipped figure has it.
    consistency_rows: str = "exact"
    # 0 to 1: each phase's mesh graded toward both of its ends (transcription.fractions: the
    # first interval about (1 - g) + g pi^2 / (4 n) times a uniform one's); 0, the default, the
    # uniform mesh of every shipped figure. What it does to the cost's convergence from N to 2N
    # nodes: docs/concepts/stride.md, "A mesh graded toward the phases' ends".
    grading: float = 0.0

    def __post_init__(self):
        if self.strike not in STRIKE_PHASES:
            raise InputError(f"strike {self.strike!r}: expected one of {', '.join(STRIKES)}")
        if self.objective not in OBJECTIVES:
            raise InputError(f"objective {self.objective!r}: expected one of {', '.join(OBJECTIVES)}")
        if self.touchdown not in TOUCHDOWN_MODES:
            raise InputError(f"touchdown {self.touchdown!r}: expected stick or slide")
        if self.touchdown == "slide" and (self.law != "coulomb" or self.strike not in SLIDING_PHASES):
            raise InputError(f"touchdown 'slide': expected law coulomb and strike "
                             f"{' or '.join(SLIDING_PHASES)}, not {self.law} and {self.strike}")
        self._check_muscles()
        if self.transcription not in TRANSCRIPTIONS:
            raise InputError(f"transcription {self.transcription!r}: expected {' or '.join(TRANSCRIPTIONS)}")
        if self.slip not in (1, -1):
            raise InputError(f"slip = {self.slip}: expected 1 (forward) or -1 (back)")
        # under Coulomb the touchdown may need its sliding variant, one phase more
        phases = SLIDING_PHASES.get(self.strike, self.phases) if self.law == "coulomb" else self.phases
        nodes = check("nodes", self.nodes, whole=True)
        if nodes < MIN_NODES * len(phases) + 2:
            raise InputError(f"nodes = {self.nodes}: expected at least {MIN_NODES * len(phases) + 2} "
                             f"for a {self.strike} strike under {self.law}")
        if self.law not in ("no-slip", "coulomb"):
            raise InputError(f"law {self.law!r}: expected no-slip or coulomb (frictionless "
                             "impacts leave the foot sliding, a phase the stride does not model)")
        check("impact_weight", self.impact_weight)
        if not 0.0 <= self.moment_time <= MOMENT_TIME_MAX or (self.moment_time and self.muscles is not None):
            raise InputError(f"moment_time = {self.moment_time}: expected 0 to {MOMENT_TIME_MAX} s, "
                             "0 with muscles (their moments are their tendons' forces)")
        if self.torque_velocity and self.muscles is not None:
            raise InputError("torque_velocity: the torque rungs' limit; the muscles have their own force-velocity")
        check("grading", self.grading)
        if self.consistency_rows not in CONSISTENCY_ROWS:
            raise InputError(f"consistency_rows = {self.consistency_rows!r}: expected {', '.join(CONSISTENCY_ROWS)}")
        if self.consistency_rows == "trapezoid" and (self.transcription != "trapezoid" or self.moment_time
                                                      or self.muscles is not None):
            raise InputError("consistency_rows = 'trapezoid': measured on the trapezoid's torque rungs "
                             "without moment dynamics only (RELEASE_DRIFT's h is a trapezoid interval)")
        if not 0.0 < self.reserve_weight < math.inf:
            raise InputError(f"reserve_weight = {self.reserve_weight}: expected a finite number > 0")
        check("torque_limit_nm_per_kg", self.torque_limit)
        check("clearance_m", self.clearance)
        check("approach_speed_mps", self.approach_speed)
        check("max_iterations", self.max_iter, whole=True)
        for joint, k in self.tendons.items():
            if joint not in TENDON_JOINTS:
                raise InputError(f"tendons.{joint}: expected a joint of {', '.join(TENDON_JOINTS)}")
            check("tendon_nm_per_rad_kg", k, name=f"tendons.{joint}")
        for name, (lo, hi) in self.duration.items():
            if name not in NODE_SHARE:
                raise InputError(f"duration {name}: expected a phase of {', '.join(NODE_SHARE)}")
            for bound in (lo, hi):
                check("duration_s", bound, name=f"duration {name}")
            if not lo < hi:
                raise InputError(f"duration {name} = ({lo}, {hi}): expected low < high")

    def _check_muscles(self):
        """The muscles' settings (__post_init__): their objectives, no tendons in parallel, the
        force-rate term's power and weight, the activation rates' smoothing scale, none of them
        on a torque rung."""
        if self.muscles is not None and (self.tendons or self.objective not in MUSCLE_OBJECTIVES):
            raise InputError(f"actuation 'muscles': expected objective {' or '.join(MUSCLE_OBJECTIVES)} and no "
                             f"tendons (the muscles' tendons are in series), not {self.objective!r}"
                             + (f" and tendons {self.tendons}" if self.tendons else ""))
        if self.muscles is None and self.objective == "activation":
            raise InputError("objective 'activation': expected actuation 'muscles'")
        if self.force_rate_weight is not None and not 0.0 <= self.force_rate_weight < math.inf:
            raise InputError(f"force_rate_weight = {self.force_rate_weight}: expected a finite number >= 0")
        if self.force_rate_power not in FORCE_RATE_POWERS:
            raise InputError(f"force_rate_power = {self.force_rate_power}: expected 1 (|F'|) or 2 (F'^2)")
        if self.muscles is None and (self.force_rate_power != 2 or self.force_rate_weight is not None):
            raise InputError("force_rate_power / force_rate_weight: the muscles' metabolic objective's, "
                             "expected actuation 'muscles'")
        if not 0.0 <= self.activation_rate_smoothing < math.inf:
            raise InputError(f"activation_rate_smoothing = {self.activation_rate_smoothing}: expected a finite "
                             "number >= 0 (1/s)")
        if self.muscles is None and self.activation_rate_smoothing != ACTIVATION_RATE_SMOOTHING:
            raise InputError("activation_rate_smoothing: the muscles' activation rates' scale, expected "
                             "actuation 'muscles'")

    @property
    def actuation(self) -> str:
        """The rung of ACTUATIONS these settings build."""
        return "muscles" if self.muscles is not None else "torque+springs" if springs(self.tendons) else "torque"

    @property
    def rate_weight(self) -> float:
        """The force-rate term's weight (`force_rate_weight`)."""
        return force_rate_weight(self.force_rate_power, self.force_rate_weight)

    @property
    def phases(self) -> tuple[Phase, ...]:
        return (SLIDING_PHASES if self.touchdown == "slide" else STRIKE_PHASES)[self.strike]

    def node_split(self) -> list[int]:
        """Intervals per phase: MIN_NODES each, the rest shared by NODE_SHARE (the flight
        takes the rounding)."""
        shares = [NODE_SHARE[p.name] for p in self.phases]
        rest = self.nodes - MIN_NODES * len(shares)
        split = [MIN_NODES + round(rest * s / sum(shares)) for s in shares]
        split[-1] += self.nodes - sum(split)
        return split


def metabolic(positive, negative):
    """Margaria's metabolic proxy W+/0.25 + W-/1.2 (J)."""
    return positive / EFFICIENCY_POSITIVE + negative / EFFICIENCY_NEGATIVE
