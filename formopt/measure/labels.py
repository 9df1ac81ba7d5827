"""The running trial's labels checked against the standing trial's.

A standing trial holds still. Each running cluster is fitted to its standing shape (Kabsch): a
permutation of its labels that fits three times better (MT1 and MT5 swapped, say) is swapped
back, and so is a leg cluster found on the other side of the pelvis; each swap is noted.

The pelvis is checked first, since the sides are judged in its frame, and only by upright
fits: a near-planar cluster with its left and right labels swapped is the mirror image of its
standing shape, and a mirror image of a planar shape fits it exactly upside down (turned
180 deg about the forward axis). A fit whose up is more than 90 deg from the standing body's
(median over the sampled frames) is no fit; a pelvis that fits only upside down is refused.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from ..io import markerset as msets
from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from .axes import left_of_labels, unit
from .rigid import fit_residual, kabsch

STATIC_DRIFT = 0.05  # m: the pelvis of a standing trial moves less
LABEL_TOLERANCE = 0.010  # m rms: a cluster fitting worse than this has its labels questioned
SAMPLE_FRAMES = 60  # frames of the run, evenly spread, that the label fits use


def check_static(static: Trial, ms: msets.MarkerSet) -> None:
    """A standing trial holds still: its pelvis drifts less than STATIC_DRIFT."""
    static.require(ms.pelvis, f"the standing trial ({ms.name} markers)")
    if static.frames > 1:
        centre = np.mean([static.markers[n] for n in ms.pelvis], axis=0)
        drift = float(np.max(np.linalg.norm(centre - np.nanmedian(centre, axis=0), axis=1)))
        if drift > STATIC_DRIFT:
            raise MocapError(f"{static.source}: not a standing trial: the pelvis moves "
                             f"{drift:.2f} m (a standing trial holds within {STATIC_DRIFT:g} m)")
    static.require(ms.standing(), f"the standing trial ({ms.name} markers)")


def check_labels(static: Trial, trial: Trial, ms: msets.MarkerSet) -> None:
    """Swap back labels whose side, or whose order within a cluster, differs from the standing
    trial's; each swap is noted in `trial.notes`."""
    ref = static.mean_positions()
    sample = np.linspace(0, trial.frames - 1, min(trial.frames, SAMPLE_FRAMES)).astype(int)
    legs = {seg: {s: [n for n in ms.cluster(s, seg) if not n.startswith("@")] for s in SIDES}
            for seg in msets.SEGMENTS}
    feet = [n for s in SIDES for n in ms.cluster(s, "foot") if not n.startswith("@")]
    up = unit(np.mean([ref[n] for n in ms.pelvis], axis=0) - np.mean([ref[n] for n in feet], axis=0))
    if 3 <= len(ms.pelvis) <= 6:
        _swap_within(ref, trial, list(ms.pelvis), sample, up)
    _swap_sides(ref, trial, ms, legs, sample)
    for names in [n for by_side in legs.values() for n in by_side.values()]:
        if 3 <= len(names) <= 6:
            _swap_within(ref, trial, names, sample)


def _stack(trial: Trial, names, sample) -> np.ndarray:
    return np.stack([trial.markers[n][sample] for n in names], axis=1)


def _swap_sides(ref: dict, trial: Trial, ms: msets.MarkerSet, legs: dict, sample) -> None:
    """Each leg cluster lies on its own side of the pelvis (in the standing pelvis's frame);
    mirror-image clusters fit either side's shape, so their place decides."""
    R, t = kabsch(np.array([ref[n] for n in ms.pelvis]), _stack(trial, ms.pelvis, sample))
    centre = np.mean([ref[n] for n in ms.pelvis], axis=0)
    left = unit(left_of_labels(ref, ms))
    for seg, names in legs.items():
        lateral = {s: np.median((np.einsum("fji,fj->fi", R, _stack(trial, names[s], sample).mean(axis=1) - t)
                                 - centre) @ left) for s in SIDES}
        if lateral["R"] > 0 > lateral["L"]:
            _relabel(trial, dict(zip(names["R"] + names["L"], names["L"] + names["R"])))
            trial.notes.append(f"the {seg} markers' sides are swapped in the run relative to "
                               f"the standing trial: swapped back")


def _swap_within(ref: dict, trial: Trial, names: list[str], sample, up=None) -> None:
    """The permutation of `names` that fits the standing shape best, if three times better.
    `up` (3,), the standing body's up: only upright fits count (module docstring); none
    upright is a MocapError."""
    reference = np.array([ref[n] for n in names])

    def residual(run_names):  # median over the sampled frames of the rms fit residual (m)
        current = _stack(trial, run_names, sample)
        R, t = kabsch(reference, current)
        if up is not None and not np.median(np.einsum("fij,j->fi", R, up) @ up) > 0:
            return math.inf  # upside down
        return float(np.median(fit_residual(reference, current, R, t)))

    base = residual(names)
    if base <= LABEL_TOLERANCE:
        return
    best = min(itertools.permutations(names), key=lambda p: residual(list(p)))
    if residual(list(best)) == math.inf:
        raise MocapError(f"{trial.source}: the markers {', '.join(names)} fit the standing trial's "
                         f"only upside down, whatever their labels: not the same runner's or "
                         f"mislabelled beyond repair")
    if residual(list(best)) < base / 3:
        moved = {a: b for a, b in zip(names, best) if a != b}
        _relabel(trial, {b: a for a, b in moved.items()})
        trial.notes.append(f"{' and '.join(sorted(moved))} are swapped in the run "
                           f"relative to the standing trial: swapped back")


def _relabel(trial: Trial, mapping: dict) -> None:
    """Rename markers: run label -> standing label (all at once)."""
    trial.markers.update({new: trial.markers[old].copy() for old, new in mapping.items()})
    for d in (trial.suspect, trial.gaps):
        moved = {new: d[old] for old, new in mapping.items() if old in d}
        for old in mapping:
            d.pop(old, None)
        d.update(moved)
