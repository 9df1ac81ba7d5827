"""The stride's admissible values, each once, with its source: the `[stride]` scene keys, the
settings of a built NLP, the API's overrides and every point a map derives are checked here,
before any solve.

A stride scene's speed, cadence and step length are one relation (a step is a half stride:
L = v T, cadence = 60 / T, so cadence = 60 v / L): a point that imposes two of them derives the
third, and the derived one is held to its range too (`point`).
"""

from __future__ import annotations

from ...mechanics import limits
from ...mechanics.errors import InputError
from ...mechanics.limits import Range

RANGES = {
    # 1-8 m/s: a slow jog (RBDS's slowest trials are 2.5 m/s; running below about 2 m/s turns
    # into walking, Hreljac 1993) to a fast sprint's 8 m/s; the stride's guess and bounds are a
    # runner's, not a sprinter's at 10-12 m/s.
    "speed_mps": Range(1.0, 8.0, "m/s"),
    "cadence_spm": limits.CADENCE_SPM,
    # a step (half a stride) of 0.3 to 2.7 m: a jog at 1 m/s and 200 steps/min is 0.3 m; the
    # longest sprint steps are about 2.7 m (Bolt's 100 m world record, Berlin 2009: 41 steps,
    # 2.44 m on average). A cadence of 60 steps/min at 3.5 m/s (a 3.5 m step) is no run.
    "step_length_m": Range(0.3, 2.7, "m"),
    # +-20 deg: the steepest paved streets (about 20 deg); the stride's guess and the trunk's
    # bounds are a level runner's (limits.SLOPE_DEG's 60 deg is for a single impact).
    "slope_deg": Range(-20.0, 20.0, "deg"),
    "friction": limits.FRICTION,
    # collocation intervals over the half stride: 14 (problem.MIN_NODES per phase and two: a
    # flat strike's three phases; StrideSettings asks each strike's own minimum) to 120, what
    # solves. Measured on the shipped stride scene (heel, one start, the generic guess; a 2-core
    # machine under a load of 5, 2026-11-25): 40 nodes 6 s wall (79 iterations), 80 nodes 17 s
    # (142), 120 nodes 111 s (301); 160 nodes stopped at 1000 iterations after 287 s without
    # converging, 240 and 400 gave no answer within 300 s. The mesh study's 2N of 40-60 fits.
    "nodes": Range(14, 120),
    # weight (1/m) of the impacts' T_c per distance beside the objective: 0 to 1000 (at 1000
    # the impacts outweigh any stride's effort by orders of magnitude).
    "impact_weight": Range(0.0, 1e3),
    # joint moment bound per kg of body mass: 0.5-20 N m/kg (running's stance moments peak at
    # 2-4 N m/kg at the knee and ankle, Schache et al. 2011, Med Sci Sports Exerc 43:1260).
    "torque_limit_nm_per_kg": Range(0.5, 20.0, "N m/kg"),
    # a tendon's stiffness per kg: 0-20 N m/rad per kg (RBDS001's stance quasi-stiffness is
    # 4.8 at the ankle and 7.4 at the knee: mechanics.landing.RUNNING_JOINTS).
    "tendon_nm_per_rad_kg": Range(0.0, 20.0, "N m/rad/kg"),
    # a phase's duration bounds: 0 < low < high <= 2 s (a stance at the slowest jog is 0.4 s)
    "duration_s": Range(0.0, 2.0, "s", low_open=True),
    # the swing foot's least height while the other foot holds the ground (contact.CLEARANCE):
    # 0 (the ground alone, the strides before 2026-11-25) to 10 cm. A bound, not a measure: the
    # swing foot is a flight's time from the ground at the stance's start and end, and a floor
    # far above walking's 1-2 cm minimum toe clearance would set the swing, not bound it.
    "clearance_m": Range(0.0, 0.1, "m"),
    # an impact's least approach speed (StrideSettings.approach_speed): 0 (grazing allowed) to
    # 1 m/s (a heel reaches the ground at about 0.5-1 m/s in running)
    "approach_speed_mps": Range(0.0, 1.0, "m/s"),
    # moment dynamics' time (StrideSettings.moment_time; problem.MOMENT_TIME's 12 ms a muscle's):
    # 0 (torque sources that jump) to problem.MOMENT_TIME_MAX
    "moment_time_s": Range(0.0, 0.2, "s"),
    # each phase's mesh graded toward its ends (StrideSettings.grading, transcription.fractions):
    # 0 uniform to 1, the cosine map (the end intervals O(1/n^2) of the phase's duration)
    "grading": Range(0.0, 1.0),
    "max_iterations": limits.MAX_ITERATIONS,
    "starts": Range(1, 100),
    # the global search's spend (optim.stride.search): 1-8; spend 8 is 33 grid cadences and
    # about 120 solves, several minutes at 40 nodes on a loaded 2-core machine (2026-11-25)
    "spend": Range(1, 8),
}



def allow_nodes(most: int) -> None:
    """Lets a mesh study build meshes of up to `most` intervals, past the scenes' 120
    (RANGES["nodes"]: each finer mesh solved warm from the one before, where a cold solve at 160
    does not converge); for problems/' mesh scripts, never a scene."""
    RANGES["nodes"] = Range(RANGES["nodes"].low, max(most, 120))

def check(key: str, value, whole: bool = False, name: str = "") -> float:
    """`value` within RANGES[key] (a finite number), else InputError naming `name` (default:
    the key)."""
    return limits.check(name or key, value, RANGES[key], whole)


def point(speed: float, cadence: float | None = None, step: float | None = None) -> tuple[float, float | None]:
    """(speed m/s, cadence steps/min or None) of a point that gives a speed and at most one of
    an imposed cadence or step length (m); each given and each derived value checked against
    RANGES, the derived one named as derived."""
    check("speed_mps", speed)
    if cadence is not None and step is not None:
        raise InputError("cadence_spm and step_length_m: impose one of them at a given speed "
                         "(cadence = 60 speed / step length)")
    if step is not None:
        cadence = _derived("step_length_m", step, speed, "cadence_spm")
    elif cadence is not None:
        _derived("cadence_spm", cadence, speed, "step_length_m")
    return speed, cadence


def _derived(key: str, value: float, speed: float, other: str) -> float:
    """The other of cadence and step length at `speed` (60 v / value: the relation is its own
    inverse), `value` and the derived one each checked (InputError naming both)."""
    check(key, value)
    derived = 60.0 * speed / value
    if derived not in RANGES[other]:
        raise InputError(f"{key} = {value:g} at {speed:g} m/s: gives {other} = {derived:.4g}, outside "
                         f"{RANGES[other].text()}")
    return derived
