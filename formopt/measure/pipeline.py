"""The whole measurement of a run against its standing trial: cleaning, units, marker map,
labels, axes, joint centres, kinematics and touchdowns, every check on the way."""

from __future__ import annotations

import copy
import itertools
from dataclasses import dataclass

import numpy as np

from ..io import markerset as msets
from ..io.mocap import Trial
from ..mechanics import limits
from .clean import clean
from .filters import CUTOFF_HZ
from .joints import Calibration, calibrate
from .kinematics import Kinematics, kinematics
from .labels import check_labels, check_static
from .touchdowns import FOOT_SPEED_FRACTION, FORCE_THRESHOLD_N, MISSED_STRIDES, Steps, touchdowns
from .units import resolve_units


@dataclass(frozen=True)
class Options:
    """What compare lets a user set about the measurement."""

    markers: str | None = None  # marker map: shipped name or TOML file; None: recognised
    cutoff_hz: float = CUTOFF_HZ  # design cut-off of the markers' low-pass (filters.py)
    force_threshold_n: float = FORCE_THRESHOLD_N  # vertical force at touchdown
    foot_speed_fraction: float = FOOT_SPEED_FRACTION  # without a plate: touchdown when the
    #                     foot's speed over the ground falls below this fraction of the running speed


@dataclass
class Measurement:
    trial: Trial  # the run as processed: units, labels, cleaning
    calibration: Calibration
    kinematics: Kinematics
    steps: Steps


def measure(trial: Trial, static: Trial, height: float, options: Options = Options()) -> Measurement:
    """Units, marker map, labels, axes, joint centres, kinematics and touchdowns of a run
    (`height`: the runner's stature, m), every check on the way; refuses with one line naming
    the file. The trials are taken as read (io.mocap.read) and copied: the Measurement holds
    the processed ones (cleaned, in m, labels as the standing trial's)."""
    limits.check("height", height, limits.BODY_HEIGHT_M)
    trial, static = copy.deepcopy(trial), copy.deepcopy(static)
    for t in (static, trial):
        t.check()
    for t in (static, trial):  # a trial without units is cleaned once they are known
        if t.units:
            clean(t)
    ms = msets.load(options.markers) if options.markers else msets.recognise(trial.markers, trial.source)
    resolve_units(static, trial, height, ms)
    check_static(static, ms)
    trial.require(ms.running(), f"the running trial ({ms.name} markers)")
    check_labels(static, trial, ms)
    cal = calibrate(static, trial, ms, height)
    kin = kinematics(trial, cal, options.cutoff_hz)
    steps = touchdowns(trial, kin, cal, options.force_threshold_n, options.foot_speed_fraction)
    steps.notes[:0] = [f"marker map: {ms.name} ({ms.title})"] + static.notes
    return Measurement(trial, cal, kin, steps)


def mean_cycle(m: Measurement, side: str = "R", points: int = 101) -> tuple[dict[str, np.ndarray], int]:
    """The mean gait cycle of `side`: its thigh, shank and foot angles and the pelvis's tilt
    (`trunk`) (rad, kinematics.py's conventions) at `points` from 0 to 100 % of each cycle
    between consecutive valid touchdowns of `side`, averaged; a cycle that misses a touchdown
    (longer than MISSED_STRIDES strides) is left out. Returns (angles, the cycles averaged)."""
    stride = 120.0 / m.steps.cadence_spm  # s, one cycle: two steps
    times = [td.time for td in m.steps.valid if td.side == side]
    cycles = [(t0, t1) for t0, t1 in itertools.pairwise(times) if t1 - t0 < MISSED_STRIDES * stride]
    kin = m.kinematics
    names = {"thigh": f"{side}.thigh", "shank": f"{side}.shank", "foot": f"{side}.foot", "trunk": "trunk"}
    return {k: np.mean([np.interp(np.linspace(t0, t1, points), kin.t, kin.angles[name]) for t0, t1 in cycles], axis=0)
            for k, name in names.items()}, len(cycles)


# The share of a gait cycle from touchdown that holds a runner's stance knee peak (10-20 %) and
# ends before the knee's swing flexion (after 40 %; toe-off at 30-37 %): `stance_knee_deg`'s window.
STANCE_SHARE = 0.35


def stance_knee_deg(m: Measurement, side: str = "R") -> tuple[float, int]:
    """The stance knee at its deepest: the mean cycle's (`mean_cycle`) knee flexion, thigh less
    shank angle (deg), at its largest over the cycle's first STANCE_SHARE (a runner's peak falls
    at 10-20 %, toe-off at 30-37 %, the knee's swing flexion after 40 %), and that maximum's place
    (% of the cycle). NaN and -1 without a cycle."""
    angles, cycles = mean_cycle(m, side)
    if not cycles:
        return float("nan"), -1
    knee = np.degrees(angles["thigh"] - angles["shank"])[:round(STANCE_SHARE * 100) + 1]
    peak = int(np.argmax(knee))
    return float(knee[peak]), peak
