"""Lab axes from physics, never from the lab's names.

Up is the force plate's mean force (body weight) when there is one; else the standing body
(pelvis above feet), pitched so that the stance foot moves level (a level belt or floor).
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
    stance = _stance_motion(trial, ms, body)
    up, vertical = _vertical(trial, body, stance)
    tilt = math.degrees(math.acos(min(1.0, abs(float(up @ body)))))
    notes = [f"vertical: {vertical}; {tilt:.1f} deg from the standing body's"]
    if tilt > 15:
        raise MocapError(f"{trial.source}: the vertical ({vertical}) is {tilt:.0f} deg from the "
                         f"standing body's: the standing trial is not upright or the files "
                         f"do not belong together")
    if stance is None:
        raise MocapError(f"{trial.source}: no stance found: the feet never rest on the ground "
                         f"(is the rate, {trial.rate:g} Hz, right?)")
    pelvis = np.mean([trial.markers[n] for n in ms.pelvis], axis=0)
    travel = np.nanmedian(np.gradient(pelvis, 1.0 / trial.rate, axis=0), axis=0) - stance
    travel -= (travel @ up) * up
    forward = unit(travel)
    left = np.cross(up, forward)
    mirrored = bool(left_of_labels(ref, ms) @ left < 0)
    if mirrored:
        notes.append("the file's axes are left-handed (a mirrored lab frame, or left and right "
                     "labels swapped throughout): formopt uses its own axes; sagittal angles "
                     "are unaffected, sides are as labelled")
    return Axes(forward, left if not mirrored else -left, up, vertical, mirrored), notes


def _vertical(trial: Trial, body, stance) -> tuple[np.ndarray, str]:
    """Up (3,) and how it was found: the plate's mean force, else the standing body's up
    `body` pitched normal to the stance foot's velocity `stance`, else `body` itself."""
    if trial.force is not None:
        finite = np.all(np.isfinite(trial.force), axis=1)
        mean = trial.force[finite].mean(axis=0) if finite.any() else np.zeros(3)
        if not np.linalg.norm(mean) > 0:
            raise MocapError(f"{trial.source}: the force plate holds no finite non-zero force to "
                             f"find up from (an empty or broken plate: remove it)")
        return unit(mean) * (1 if mean @ body > 0 else -1), "the force plate's mean force"
    if stance is not None:  # the stance foot moves level: pitch the body's up to be normal to it
        d = unit(stance)
        return unit(body - (body @ d) * d), "the standing body, pitched to the stance foot's level motion"
    return body, "the standing body (pelvis above feet)"


def _stance_motion(trial: Trial, ms: msets.MarkerSet, up) -> np.ndarray | None:
    """The stance foot's median velocity (3,; m/s, lab) over the frames each foot rests lowest."""
    velocities = []
    for s in SIDES:
        names = [n for n in ms.cluster(s, "foot") if not n.startswith("@")]
        M = np.stack([trial.markers[n] for n in names], axis=1)
        low = (M @ up).min(axis=1)
        rest = low < np.percentile(low, 5) + 0.005
        if rest.sum() >= 5:
            velocities.append(np.median(np.gradient(M, 1.0 / trial.rate, axis=0)[rest].reshape(-1, 3), axis=0))
    return np.mean(velocities, axis=0) if velocities else None
