"""Touchdowns: when each foot meets the ground, its strike pattern and touchdown state.

From the vertical force where there is a force plate (FORCE_THRESHOLD_N, rising): a single
treadmill plate sees both feet, the side is the foot that is lower then. Otherwise from the
foot's speed over the ground (belt added), falling below FOOT_SPEED_FRACTION of the running
speed. The cadence they give is checked against the feet's own rhythm: a force file that does
not span the marker file is refused. Strike pattern from the foot strike angle (foot angle at
touchdown relative to standing; Altman & Davis 2012, Gait Posture 35:298-300): rearfoot
> 8 deg, forefoot < -1.6 deg, midfoot between. A touchdown whose markers around it (+-30 ms)
were missing, spiked, frozen, or whose clusters were not rigid (residual > 12 mm), or whose
segment angle or rate jumps from its side's neighbouring steps or from its side's over the
trial (_jumps), is listed with valid_data False and its reason, and left out of the means;
touchdowns a foot misses (the cadence expects one and none is found, _missed) are listed too.

Contact order (contact_order): which of the heel and forefoot points reaches its stance level
first, each point by the first of its own markers (kinematics.Kinematics.soles: the heel
marker, each metatarsal marker, or where a map has none the foot cluster's sole points): each
marker's lowest height from STEP_WINDOW before the touchdown to ORDER_WINDOW after it is its
stance level, and it has reached it when it is within LEVEL_M of it; "flat" when the two reach
times differ by at most FLAT_S. Against the plate's centre of pressure (plate.strike_index) on
RBDS001, the metatarsals' mean as the forefoot said heel or flat for 163 of 163 forefoot
touchdowns; each metatarsal on its own agrees in 157 (6 flat).
With a plate, the centre of pressure's index and class (cop_index) ride along each touchdown.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from ..mechanics.model import joint_angles, xy
from .clean import measured_frames
from .filters import lowpass
from .joints import Calibration
from .kinematics import Kinematics
from .plate import FORCE_CUTOFF_HZ, strike_index
from .stance import at_rest, no_rest_reason, stances

FORCE_THRESHOLD_N = 50.0  # vertical force at touchdown
FOOT_SPEED_FRACTION = 0.5  # without a plate: the foot's speed over the ground below this
#                            fraction of the running speed
RIGID = 0.012  # m: a cluster's rms residual beyond this is not a rigid body at that frame
STEP_WINDOW = 0.03  # s each side of a touchdown whose markers must be sound
SPEED_RANGE = (0.5, 12.0)  # m/s: running
CADENCE_TOLERANCE = 0.1  # relative: touchdowns against the feet's rhythm
REARFOOT_DEG, FOREFOOT_DEG = 8.0, -1.6  # Altman & Davis (2012) foot strike angle thresholds
ORDER_WINDOW = 0.15  # s after a touchdown: both points are down by then (stance >= 0.2 s)
LEVEL_M = 0.003  # m above its stance level a point counts as down: 2-3 times the filtered
#                  markers' noise, and less than the 5-20 mm each point still falls in the
#                  frames before it lands
FLAT_S = 0.010  # s: two contacts this close are one ("flat"): about two frames at 150-200 Hz
#                 (each reach time is quantised to a frame), and under a third of the 25-50 ms
#                 rise to the impact peak, within which the rigid impact is one event
JUMP_NEIGHBOURS = 3  # steps each side a touchdown is compared with
JUMP_SD = 5.0  # robust standard deviations (1.4826 MAD) of the neighbours
JUMP_FLOOR = {"segments.foot": (5.0, "deg"), "segments.shank": (5.0, "deg"),
              "segments.thigh": (5.0, "deg"), "rates.foot": (200.0, "deg/s"),
              "rates.shank": (200.0, "deg/s"), "rates.thigh": (200.0, "deg/s")}
#  floors: 3-5 times the step-to-step sd of touchdown angles (0.6-1.6 deg on the shipped runs)
MISSED_STRIDES = 1.5  # a foot's touchdowns this many strides apart miss one between them
SEPARATION = {"force plate": 0.15, "kinematics": 0.25}  # s: a touchdown within this of the
#                                                        last one is the same contact


@dataclass(frozen=True)
class Touchdown:
    time: float  # s
    side: str  # "R" or "L"
    frame: int  # marker frame just before the contact
    strike: str  # "heel", "midfoot", "forefoot"
    foot_strike_angle: float  # rad, foot angle relative to standing, toe up positive
    segments: dict[str, float]  # rad: trunk (tilt), thigh, shank (from the downward vertical,
    #                             end ahead positive), foot (relative to standing)
    angles: dict[str, float]  # rad: trunk, hip, knee, ankle (formopt's joint angles)
    rates: dict[str, float]  # rad/s: thigh, shank, foot (absolute)
    hip_velocity: tuple[float, float]  # m/s, ground frame (belt added)
    hip_height: float  # m above the lower foot point
    hip_from_point: dict[str, tuple[float, float]]  # m: the hip from the heel and the forefoot (forward, up)
    contact_order: str = "flat"  # "heel", "forefoot" or "flat": the point the markers put down first
    reach_s: tuple[float, float] = (0.0, 0.0)  # s after the touchdown: heel, forefoot at their stance level
    valid_data: bool = True
    problems: tuple[str, ...] = ()  # why valid_data is False
    cop_index: float | None = None  # the centre of pressure along the foot (plate.strike_index)

    def state(self) -> np.ndarray:
        """formopt's touchdown state vector (model.STATE)."""
        a, w = self.angles, self.rates
        return np.array([a["trunk"], a["hip"], a["knee"], a["ankle"], *self.hip_velocity, 0.0,
                         w["thigh"], w["shank"], w["foot"]])


@dataclass
class Steps:
    touchdowns: list[Touchdown]
    cadence_spm: float
    belt_speed: float  # m/s: the stance foot's backward speed (0 overground)
    speed: float  # m/s: the runner's speed over the ground
    method: str  # "force plate" or "kinematics"
    notes: list[str] = field(default_factory=list)  # from the reader and the checks
    missed: list[str] = field(default_factory=list)  # stretches where a foot's touchdowns
    #                                                  were not found, and why (_missed)

    @property
    def valid(self) -> list[Touchdown]:
        return [td for td in self.touchdowns if td.valid_data]

    @property
    def left_out(self) -> list[str]:
        """The steps not used, and why: those found but unsound, and those not found."""
        return [f"{td.time:.3f} s ({td.side}): {'; '.join(td.problems)}"
                for td in self.touchdowns if not td.valid_data] + self.missed


def strike_pattern(foot_strike_angle: float) -> str:
    """Rearfoot ("heel"), "midfoot" or "forefoot" from the foot strike angle (rad)."""
    deg = math.degrees(foot_strike_angle)
    return "heel" if deg > REARFOOT_DEG else "forefoot" if deg < FOREFOOT_DEG else "midfoot"


def contact_order(heel, forefoot, frame: int, rate: float) -> tuple[str, tuple[float, float]]:
    """(order, (heel, forefoot) reach times in s after `frame`) from the heights ((k, frames)
    or (frames,); m) of the heel's and the forefoot's markers, each point reached when the
    first of its markers is (module docstring: stance level, LEVEL_M, FLAT_S)."""
    reach = []
    for zs in (np.atleast_2d(heel), np.atleast_2d(forefoot)):
        lo = max(frame - round(STEP_WINDOW * rate), 0)
        hi = min(frame + round(ORDER_WINDOW * rate) + 1, zs.shape[1])
        reach.append(min((lo + int(np.flatnonzero(z <= z.min() + LEVEL_M)[0]) - frame) / rate
                         for z in zs[:, lo:hi]))
    gap = reach[0] - reach[1]
    order = "flat" if abs(gap) <= FLAT_S + 1e-9 else "heel" if gap < 0 else "forefoot"
    return order, (reach[0], reach[1])


def force_plate_touchdowns(force, force_rate: float, up, threshold: float = FORCE_THRESHOLD_N,
                           source: str = "") -> np.ndarray:
    """Times (s) where the low-passed force (samples, 3; N) along `up` rises through
    `threshold` N, one per contact."""
    vertical = lowpass(force, force_rate, min(FORCE_CUTOFF_HZ, 0.4 * force_rate), source) @ up
    on = np.flatnonzero((vertical[1:] >= threshold) & (vertical[:-1] < threshold)) + 1
    return _separated(on / force_rate, SEPARATION["force plate"])


def foot_speed_touchdowns(velocity, rate: float, belt: float, speed: float,
                          fraction: float = FOOT_SPEED_FRACTION) -> np.ndarray:
    """Times (s) where the foot's speed over the ground (its lab velocity (frames, 2), forward
    and up, m/s, plus the belt's `belt` m/s) falls below `fraction` of the running `speed`."""
    slow = np.linalg.norm(velocity + [belt, 0.0], axis=1) < fraction * speed
    on = np.flatnonzero(slow[1:] & ~slow[:-1]) + 1
    return _separated(on / rate, SEPARATION["kinematics"])


def touchdowns(trial: Trial, kin: Kinematics, cal: Calibration,
               force_threshold_n: float = FORCE_THRESHOLD_N,
               foot_speed_fraction: float = FOOT_SPEED_FRACTION) -> Steps:
    """Touchdowns of both feet, their side, strike pattern, touchdown state and validity;
    the cadence and speed checked (module docstring)."""
    foot_low = {s: np.minimum(kin.points[f"{s}.heel"][:, 1], kin.points[f"{s}.forefoot"][:, 1])
                for s in SIDES}
    motion = {s: _foot_motion(kin, cal, s) for s in SIDES}
    notes = list(trial.notes) + list(cal.notes)
    belt = _belt_speed(trial, cal, motion, notes)
    pelvis = np.mean([kin.points[f"{s}.hip"][:, 0] for s in SIDES], axis=0)
    speed = belt + float(np.median(np.gradient(pelvis, 1.0 / kin.rate)))
    if not SPEED_RANGE[0] <= speed <= SPEED_RANGE[1]:
        raise MocapError(f"{trial.source}: a running speed of {speed:.3g} m/s is outside "
                         f"{SPEED_RANGE[0]:g}-{SPEED_RANGE[1]:g} m/s: wrong units or rate "
                         f"(is the rate, {trial.rate:g} Hz, right?)")
    if trial.force is not None:
        assert trial.force_rate is not None  # io.mocap reads the force with its rate
        method = "force plate"
        times = [(t, min(SIDES, key=lambda s: foot_low[s][int(t * kin.rate)]))
                 for t in force_plate_touchdowns(trial.force, trial.force_rate, cal.axes.up,
                                                 force_threshold_n, trial.source)
                 if int(t * kin.rate) < len(kin.t)]
    else:
        method = "kinematics"
        times = sorted((t, s) for s in SIDES for t in foot_speed_touchdowns(
            motion[s][0], kin.rate, belt, speed, foot_speed_fraction))
    if len(times) < 2:
        raise MocapError(f"{trial.source}: fewer than two touchdowns found ({method}"
                         + (f"; is the rate, {trial.rate:g} Hz, right?)" if method == "kinematics" else ")"))
    cadence = 60.0 / float(np.median(np.diff([t for t, _ in times])))
    _check_cadence(trial, kin, foot_low, cadence, notes)
    steps = []
    window = max(1, round(STEP_WINDOW * kin.rate))
    for t, side in times:
        frame = math.floor(t * kin.rate + 1e-6) - 1  # t * rate is a whole frame up to rounding
        if 2 <= frame < len(kin.t) - 2:
            problems = _problems(trial, kin, cal, side, frame, window)
            steps.append(_touchdown(kin, side, frame, t, belt, foot_low[side][frame], problems))
    steps = _jumps(steps)
    if trial.force is not None and trial.cop is not None and trial.force_rate is not None:
        steps = [replace(td, cop_index=strike_index(
            trial.force, trial.cop, trial.force_rate, cal.axes.up, cal.axes.forward, td.time, kin.t,
            kin.points[f"{td.side}.heel"][:, 0], kin.points[f"{td.side}.forefoot"][:, 0])) for td in steps]
    bad = sum(not td.valid_data for td in steps)
    if bad:
        notes.append(f"{bad} of {len(steps)} touchdowns have unsound markers around them: "
                     f"listed, left out of the means")
    missed = _missed(trial, cal, times, cadence)
    if missed:
        notes.append(f"{len(missed)} stretches without the touchdowns the cadence expects: listed")
    return Steps(steps, cadence, belt, speed, method, notes, missed)


def _foot_motion(kin: Kinematics, cal: Calibration, side: str):
    """The foot cluster's centre: sagittal velocity (frames, 2; m/s, lab) and height (m);
    the foot's angular velocity (rad/s)."""
    cluster = cal.points[f"{side}.heel"][0]
    centre = cal.axes.sagittal(np.mean([kin.markers[n] for n in cluster], axis=0))
    dt = 1.0 / kin.rate
    return np.gradient(centre, dt, axis=0), centre[:, 1], np.gradient(kin.angles[f"{side}.foot"], dt)


def _belt_speed(trial: Trial, cal: Calibration, motion: dict, notes: list) -> float:
    """The ground's backward speed (m/s; 0 overground): the foot cluster's median over its
    stances (stance.at_rest: measured, low, turning and moving up or down slowly for its own
    motion; stance.stances), both feet's averaged, or the one foot's that has stances (the
    other named in `notes` with what it failed); refused, naming both, when neither has."""
    speeds, failed = [], []
    for side, (v, height, omega) in motion.items():
        measured = measured_frames(trial, [n for n in cal.points[f"{side}.heel"][0] if n in trial.markers])
        found = stances(at_rest(height, omega, v[:, 1], measured), trial.rate)
        if found:
            speeds.append(-float(np.median(np.concatenate([v[a:b, 0] for a, b in found]))))
        else:
            failed.append(f"{'right' if side == 'R' else 'left'}: "
                          f"{no_rest_reason(height, omega, v[:, 1], measured, trial.rate)}")
    if not speeds:
        raise MocapError(f"{trial.source}: no stance found: neither foot rests on the ground ("
                         f"{'; '.join(failed)}; is the rate, {trial.rate:g} Hz, right?)")
    if failed:
        notes.append(f"one foot never rests ({failed[0]}): the belt's speed from the other")
    return float(np.mean(speeds))


def _jumps(steps: list[Touchdown]) -> list[Touchdown]:
    """Each touchdown whose foot, shank or thigh angle, or whose segment rate, lies far from
    the median of its side's JUMP_NEIGHBOURS steps on each side, or from the median of all its
    side's other steps (more than JUMP_SD robust standard deviations of theirs and the floor of
    JUMP_FLOOR), marked unsound, the reason named: a cluster that slipped or was relabelled for
    a step passes the rigidity test, and one turned for many steps in a row passes the
    neighbours' test (they moved with it) but not the trial's while most steps are sound."""
    out = list(steps)
    for side in SIDES:
        idx = [k for k, td in enumerate(steps) if td.side == side]
        for key, (floor, unit) in JUMP_FLOOR.items():
            kind, seg = key.split(".")
            values = np.degrees([getattr(steps[k], kind)[seg] for k in idx])
            for j, k in enumerate(idx):
                neighbours = np.delete(values[max(j - JUMP_NEIGHBOURS, 0):j + JUMP_NEIGHBOURS + 1],
                                       min(j, JUMP_NEIGHBOURS))
                for near, whose in ((neighbours, "its neighbours'"), (np.delete(values, j), "its side's")):
                    if len(near) < 4:
                        continue
                    med = float(np.median(near))
                    limit = max(floor, JUMP_SD * 1.4826 * float(np.median(np.abs(near - med))))
                    if abs(values[j] - med) > limit:
                        td = out[k]
                        why = (f"the {seg} {'angle' if kind == 'segments' else 'rate'} {values[j]:.0f} {unit} "
                               f"is {values[j] - med:+.0f} from {whose} {med:.0f} (beyond {limit:.0f})")
                        out[k] = replace(td, valid_data=False, problems=td.problems + (why,))
                        break
    return out


def _problems(trial: Trial, kin: Kinematics, cal: Calibration, side: str, frame: int,
              window: int) -> tuple[str, ...]:
    """What is wrong with the markers of this leg and the pelvis around a touchdown."""
    lo, hi = max(frame - window, 0), frame + window + 1
    clusters = {c for name, (c, _, _) in cal.points.items() if name.startswith(side + ".")}
    names = sorted({n for c in clusters for n in c if n in trial.markers})
    out = []
    unsound = [n for n in names if n in trial.suspect and trial.suspect[n][lo:hi].any()]
    if unsound:
        out.append(f"missing or spiked samples in {', '.join(unsound)}")
    for c in sorted(clusters):
        worst = float(np.max(kin.residual[c][lo:hi]))
        if worst > RIGID:
            out.append(f"the cluster {', '.join(c)} is not rigid ({worst * 1e3:.0f} mm)")
    return tuple(out)


def _check_cadence(trial: Trial, kin: Kinematics, foot_low: dict, cadence: float, notes: list) -> None:
    """The touchdowns' cadence against each foot's rhythm (twice its stride frequency, 60-300
    steps/min): they disagree when the force and marker files do not match, or without a
    plate when the rate is wrong (the markers' low-pass then cuts the stride's harmonics)."""
    def peak(signal, rate, lo, hi):
        spectrum = np.abs(np.fft.rfft(signal - signal.mean()))
        freqs = np.fft.rfftfreq(len(signal), 1.0 / rate)
        band = (freqs > lo) & (freqs < hi)
        return float(freqs[band][np.argmax(spectrum[band])]) if band.any() else float("nan")

    feet = 120.0 * np.mean([peak(foot_low[s], kin.rate, 0.5, 2.5) for s in SIDES])
    if not abs(cadence / feet - 1) < CADENCE_TOLERANCE:
        why = ("the force and marker data do not cover the same time (lengths or rates)"
               if trial.force is not None else f"is the rate, {trial.rate:g} Hz, right?")
        raise MocapError(f"{trial.source}: the touchdowns give a cadence of {cadence:.0f} steps/min "
                         f"but the feet move at {feet:.0f}: {why}")
    notes.append(f"cadence {cadence:.1f} steps/min; the feet's rhythm {feet:.1f}")


def _missed(trial: Trial, cal: Calibration, times, cadence: float) -> list[str]:
    """Each stretch between one foot's touchdowns longer than MISSED_STRIDES strides (two
    steps at `cadence`): how many touchdowns the rhythm expects there, and the share of its
    frames where that foot's markers were not measured (clean: missing, frozen or spiked)."""
    stride = 120.0 / cadence
    out = []
    for side in SIDES:
        own = [t for t, s in times if s == side]
        foot = [n for n in cal.points[f"{side}.heel"][0] if n in trial.markers]
        measured = measured_frames(trial, foot)
        for a, b in itertools.pairwise(own):
            if b - a > MISSED_STRIDES * stride:
                lost = 1.0 - measured[round(a * trial.rate):round(b * trial.rate)].mean()
                out.append(f"{a:.3f}-{b:.3f} s ({side}): about {round((b - a) / stride) - 1} touchdowns "
                           f"not found; the foot's markers not measured in {100 * lost:.0f} % of it")
    return out


def _separated(times, gap: float) -> np.ndarray:
    """`times` (sorted, s) without those within `gap` s after the last one kept."""
    out: list[float] = []
    for t in times:
        if not out or t - out[-1] > gap:
            out.append(float(t))
    return np.array(out)


def _touchdown(kin: Kinematics, side: str, frame: int, time: float, belt: float, low: float,
               problems: tuple[str, ...]) -> Touchdown:
    """The touchdown state at `frame`: segment and joint angles, central-difference rates and
    hip velocity (belt added), the hip's height over the lower foot point `low`."""
    dt = 1.0 / kin.rate

    def rate(key):
        return float((kin.angles[key][frame + 1] - kin.angles[key][frame - 1]) / (2 * dt))

    a = {k: float(kin.angles[f"{side}.{k}"][frame]) for k in ("thigh", "shank", "foot")}
    trunk = float(kin.angles["trunk"][frame])
    hip_p = kin.points[f"{side}.hip"]
    v = (hip_p[frame + 1] - hip_p[frame - 1]) / (2 * dt)
    order, reach = contact_order(kin.soles[f"{side}.heel"], kin.soles[f"{side}.forefoot"], frame, kin.rate)
    return Touchdown(time=time, side=side, frame=frame, strike=strike_pattern(a["foot"]),
                     foot_strike_angle=a["foot"], segments={"trunk": trunk, **a},
                     angles=joint_angles({"trunk": trunk, **a}),
                     rates={k: rate(f"{side}.{k}") for k in ("thigh", "shank", "foot")},
                     hip_velocity=(float(v[0] + belt), float(v[1])),
                     hip_height=float(hip_p[frame][1] - low),
                     hip_from_point={p: xy(hip_p[frame] - kin.points[f"{side}.{p}"][frame])
                                     for p in ("heel", "forefoot")},
                     contact_order=order, reach_s=reach, valid_data=not problems, problems=problems)


def shifted(kin: Kinematics, td: Touchdown, frames: int, belt: float) -> Touchdown:
    """Touchdown `td` taken `frames` marker frames later (earlier when negative): its state's
    sensitivity to the touchdown time (compare's uncertainty)."""
    frame = min(max(td.frame + frames, 1), len(kin.t) - 2)
    low = min(kin.points[f"{td.side}.{p}"][frame, 1] for p in ("heel", "forefoot"))
    return _touchdown(kin, td.side, frame, td.time + (frame - td.frame) / kin.rate, belt, low,
                      td.problems)
