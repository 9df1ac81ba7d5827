"""Lab axes from physics, never from the lab's names.

Up is the force plate's mean force (body weight) when there is one; else the standing body
(pelvis above feet), pitched so that the resting feet's marker paths are level (they ride a
level belt: stance.py), with the bootstrap spread of that pitch and the sides' difference in
the notes; a foot rests by stance.at_rest (its cluster's angular speed from its rigid fit).
Forward: the pelvis moves forward relative to the stance foot (treadmill or overground). Left:
from the L and R markers; a left-handed file frame (a mirrored lab) is said and does no harm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..io import markerset as msets
from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from .clean import measured_frames
from .filters import CUTOFF_HZ, lowpass
from .rigid import angular_velocity, kabsch
from .stance import StancePaths, at_rest, no_rest_reason, stance_paths


@dataclass(frozen=True)
class Axes:
    """Lab axes found from the data: forward, left, up (unit vectors (3,) in the file's frame)."""

    forward: np.ndarray
    left: np.ndarray
    up: np.ndarray
    vertical: str = ""  # how up was found
    mirrored: bool = False  # the file's frame is left-handed

    def sagittal(self, p) -> np.ndarray:
        """(..., 3) lab points -> (..., 2) forward and up coordinates (m)."""
        return np.stack([p @ self.forward, p @ self.up], axis=-1)

    def describe(self) -> str:
        names = "XYZ"

        def name(v):
            k = int(np.argmax(np.abs(v)))
            return f"{'+' if v[k] > 0 else '-'}{names[k]} ({abs(v[k]):.3f})"
        return (f"forward {name(self.forward)}, up {name(self.up)}, left {name(self.left)}; "
                f"up from {self.vertical}" + ("; the file's frame is left-handed (mirrored)"
                                              if self.mirrored else ""))


def unit(v) -> np.ndarray:
    return v / np.linalg.norm(v)


def left_of_labels(ref: dict, ms: msets.MarkerSet) -> np.ndarray:
    """The mean standing offset (3,) from each R leg marker to its L namesake (points left);
    `ref`: label -> standing position (3,)."""
    return np.mean([ref[ms.label("L", n)] - ref[ms.label("R", n)]
                    for seg in msets.SEGMENTS for n in ms.leg[seg] if not n.startswith("@")], axis=0)


def find_axes(static: Trial, trial: Trial, ms: msets.MarkerSet) -> tuple[Axes, list[str]]:
    """Up, forward and left from physics (module docstring), with notes on what was checked."""
    ref = static.mean_positions()
    feet = [n for s in SIDES for n in ms.cluster(s, "foot") if not n.startswith("@")]
    body = unit(np.mean([ref[n] for n in ms.pelvis], axis=0) - np.mean([ref[n] for n in feet], axis=0))
    paths = _stance_paths(trial, ms, ref, body)
    up, vertical = _vertical(trial, body, paths)
    tilt = math.degrees(math.acos(min(1.0, abs(float(up @ body)))))
    notes = [f"vertical: {vertical}; {tilt:.1f} deg from the standing body's"]
    if tilt > 15:
        rate = "" if trial.force is not None else f", or the rate ({trial.rate:g} Hz) is wrong"
        raise MocapError(f"{trial.source}: the vertical ({vertical}) is {tilt:.0f} deg from the "
                         f"standing body's: the standing trial is not upright or the files "
                         f"do not belong together{rate}")
    notes.append(_level_note(paths, up))
    pelvis = np.mean([trial.markers[n] for n in ms.pelvis], axis=0)
    belt = (paths.velocity @ paths.direction) * paths.direction  # the resting feet ride it
    travel = np.nanmedian(np.gradient(pelvis, 1.0 / trial.rate, axis=0), axis=0) - belt
    travel -= (travel @ up) * up
    forward = unit(travel)
    left = np.cross(up, forward)
    mirrored = bool(left_of_labels(ref, ms) @ left < 0)
    if mirrored:
        notes.append("the file's axes are left-handed (a mirrored lab frame, or left and right "
                     "labels swapped throughout): formopt uses its own axes; sagittal angles "
                     "are unaffected, sides are as labelled")
    return Axes(forward, left if not mirrored else -left, up, vertical, mirrored), notes


def _vertical(trial: Trial, body, paths: StancePaths) -> tuple[np.ndarray, str]:
    """Up (3,) and how it was found: the plate's mean force, else the standing body's up
    `body` pitched normal to the resting feet's paths."""
    if trial.force is not None:
        finite = np.all(np.isfinite(trial.force), axis=1)
        mean = trial.force[finite].mean(axis=0) if finite.any() else np.zeros(3)
        if not np.linalg.norm(mean) > 0:
            raise MocapError(f"{trial.source}: the force plate holds no finite non-zero force to "
                             f"find up from (an empty or broken plate: remove it)")
        return unit(mean) * (1 if mean @ body > 0 else -1), "the force plate's mean force"
    d = paths.direction
    return unit(body - (body @ d) * d), "the standing body, pitched to the resting feet's level paths"


def _level_note(paths: StancePaths, up) -> str:
    """How level the resting feet's paths are about `up`: pooled, per side, their spread."""
    sides = paths.side_elevations(up)
    pooled = math.degrees(math.asin(float(np.clip(paths.direction @ up, -1, 1))))
    return (f"the resting feet's paths ({len(paths.sides)} stances) rise {pooled:+.2f} deg "
            f"(bootstrap sd {math.degrees(paths.spread(up)):.2f} deg; "
            + ", ".join(f"{s} {math.degrees(e):+.2f}" for s, e in sides.items()) + ")")


def _stance_paths(trial: Trial, ms: msets.MarkerSet, ref: dict, body) -> StancePaths:
    """Each foot cluster's markers (low-passed at CUTOFF_HZ) over the frames it rests
    (stance.at_rest: its pitch rate from its rigid fit to its standing shape `ref`, about the
    axis normal to `body` and to the feet's fore-aft swing, its heights along `body`), as stance.stance_paths; then again with the
    vertical speed tested along the up those paths give (along `body` the belt's speed leaks
    into it: 0.1 m/s per 1.6 deg of tilt at 3.5 m/s). Only measured frames rest; refused,
    with what each foot failed, when neither has a stance."""
    markers, omega, measured = {}, {}, {}
    for s in SIDES:
        names = [n for n in ms.cluster(s, "foot") if not n.startswith("@")]
        measured[s] = measured_frames(trial, names)
        markers[s] = np.stack([lowpass(trial.markers[n], trial.rate, min(CUTOFF_HZ, 0.4 * trial.rate),
                                       trial.source) for n in names], axis=1)
        R, _ = kabsch(np.array([ref[n] for n in names]), markers[s])
        omega[s] = angular_velocity(R, trial.rate)
    feet = np.concatenate([M.mean(axis=1) for M in markers.values()])
    feet = feet - feet.mean(axis=0)
    feet -= np.outer(feet @ body, body)  # the feet swing fore and aft: normal to it is lateral
    lateral = unit(np.cross(body, np.linalg.eigh(feet.T @ feet)[1][:, -1]))
    pitch_rate = {s: w @ lateral for s, w in omega.items()}
    paths: StancePaths | None = None
    up = body
    for test_vertical in (False, True):
        tests = {s: ((M @ up).min(axis=1), pitch_rate[s],
                     np.gradient(M.mean(axis=1) @ up, 1.0 / trial.rate) if test_vertical else None, measured[s])
                 for s, M in markers.items()}
        paths = stance_paths(markers, {s: at_rest(*t) for s, t in tests.items()}, trial.rate) or paths
        if paths is None:
            raise MocapError(f"{trial.source}: no stance found: neither foot rests on the ground ("
                             + "; ".join(f"{'right' if s == 'R' else 'left'}: {no_rest_reason(*t, trial.rate)}"
                                         for s, t in tests.items())
                             + f"; is the rate, {trial.rate:g} Hz, right?)")
        up = unit(body - (body @ paths.direction) * paths.direction)
    assert paths is not None  # the loop ran
    return paths
