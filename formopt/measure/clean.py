"""Cleaning a trial's markers: missing samples, frozen stretches and spikes are marked as not
measured, gaps up to MAX_GAP frames filled by linear interpolation, longer ones recorded.

A marker's trajectory is `xyz` (frames, 3); a mask is (frames,) bool.
"""

from __future__ import annotations

import numpy as np

from ..io.mocap import MocapError, Trial

MAX_GAP = 10  # frames interpolated; longer gaps leave their steps out
SPIKE = 0.025  # m off the 5-sample median
FROZEN = 5  # identical samples in a row


def runs(mask) -> list[tuple[int, int]]:
    """(start, stop) of each run of True (stop exclusive)."""
    edges = np.diff(np.concatenate([[0], np.asarray(mask, int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def missing_samples(xyz) -> np.ndarray:
    """Samples with a NaN or exactly (0, 0, 0): no measurement."""
    return np.any(~np.isfinite(xyz), axis=1) | np.all(xyz == 0.0, axis=1)


def frozen(xyz, length: int = FROZEN) -> np.ndarray:
    """Samples of stretches where `length` or more samples in a row are identical (a camera
    system repeating its last position)."""
    still = np.concatenate([[False], np.all(np.diff(xyz, axis=0) == 0.0, axis=1)])
    stuck = np.zeros(len(xyz), bool)
    for a, b in runs(still):  # samples a-1 .. b-1 are equal: b - a + 1 of them
        if b - a >= length - 1:
            stuck[a - 1:b] = True
    return stuck


def fill_gaps(xyz, missing) -> np.ndarray:
    """`xyz` with the `missing` samples linearly interpolated (held at the ends) per axis."""
    out = np.array(xyz, float)
    good = np.flatnonzero(~missing)
    for axis in range(3):
        out[missing, axis] = np.interp(np.flatnonzero(missing), good, out[good, axis])
    return out


def spikes(xyz, missing, threshold: float = SPIKE) -> np.ndarray:
    """Measured samples over `threshold` (m) from the median of the 5 samples around them (the
    missing ones filled first); none in a trajectory shorter than 5 samples."""
    from scipy.ndimage import median_filter

    if len(xyz) < 5:
        return np.zeros(len(xyz), bool)
    filled = fill_gaps(xyz, missing)
    off = np.linalg.norm(filled - median_filter(filled, size=(5, 1), mode="nearest"), axis=1)
    return (off > threshold) & ~missing


def clean(trial: Trial) -> Trial:
    """Mark in `trial.suspect` the missing samples (NaN, exact zeros), frozen stretches and
    spikes of every marker; interpolate them, and record gaps over MAX_GAP frames in
    `trial.gaps`; say what was done in `trial.notes`. Changes and returns `trial`."""
    spiked, stuck = 0, []
    for name, xyz in trial.markers.items():
        missing = missing_samples(xyz)
        if missing.all():
            raise MocapError(f"{trial.source}: marker {name} has no valid frame")
        still = frozen(xyz)
        if still.any():
            stuck.append(name)
        missing |= still
        if missing.all():
            raise MocapError(f"{trial.source}: marker {name} has no valid frame: frozen (the same "
                             f"position, or missing) for the whole trial")
        spike = spikes(xyz, missing)
        spiked += int(spike.sum())
        missing |= spike
        if missing.any():
            _fill(trial, name, missing)
    if spiked:
        trial.notes.append(f"{spiked} spike samples (over {SPIKE * 1e3:g} mm off their neighbours) "
                           f"treated as missing")
    if stuck:
        trial.notes.append(f"frozen stretches (the same position {FROZEN}+ frames running) "
                           f"treated as missing in {', '.join(stuck)}")
    gaps = sum(int(m.sum()) for m in trial.suspect.values())
    if gaps:
        trial.notes.append(f"{gaps} missing marker samples in {len(trial.suspect)} markers, "
                           f"gaps up to {MAX_GAP} frames interpolated")
    return trial


def measured_frames(trial: Trial, names) -> np.ndarray:
    """(frames,) bool: none of the markers `names` missing, frozen or spiked there (clean)."""
    bad = [trial.suspect[n] for n in names if n in trial.suspect]
    return ~np.logical_or.reduce(bad) if bad else np.ones(trial.frames, bool)


def _fill(trial: Trial, name: str, missing) -> None:
    """Interpolate marker `name` over `missing`, noting the gaps too long to trust."""
    trial.suspect[name] = missing
    trial.markers[name] = fill_gaps(trial.markers[name], missing)
    long = [(a, b) for a, b in runs(missing) if b - a > MAX_GAP]
    if long:
        trial.gaps[name] = long
        trial.notes.append(f"{name}: {len(long)} gaps longer than {MAX_GAP} frames "
                           f"({', '.join(f'{a / trial.rate:.2f}-{b / trial.rate:.2f} s' for a, b in long)})")
