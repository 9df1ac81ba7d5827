"""The markers' units: as the file declares them, checked against the stature (the standing
markers span SPAN_PER_HEIGHT statures) and the run's against the standing trial's cluster
sizes; when a file does not say, inferred from the same two measures, with a note.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np

from ..io import markerset as msets
from ..io.markerset import SIDES
from ..io.mocap import MocapError, Trial
from .clean import clean

SPAN_PER_HEIGHT = (0.35, 1.1)  # the standing markers' span, statures
CLUSTER_RATIO = (0.8, 1.25)  # the run's cluster sizes over the standing trial's


def resolve_units(static: Trial, trial: Trial, height: float, ms: msets.MarkerSet) -> None:
    """Check the declared units of both trials (or infer and apply them, then clean the
    trial: clean.clean); refuses with one line naming the file."""
    _static_units(static, height)
    ratio = cluster_size(trial, ms) / cluster_size(static, ms)
    lo, hi = CLUSTER_RATIO
    if trial.units:
        if not lo < ratio < hi:
            raise MocapError(f"{trial.source}: its clusters are {ratio:.3g} times the standing "
                             f"trial's: are the units ({trial.units}) right?")
        return
    scale = 10.0 ** -round(math.log10(ratio))
    if not lo < ratio * scale < hi:
        raise MocapError(f"{trial.source}: the file gives no units and its clusters are "
                         f"{ratio:.3g} times the standing trial's")
    _scale(trial, scale)
    trial.notes.append(f"{Path(trial.source).name}: no units in the file: "
                       f"{_unit_name(scale)}, from the standing trial's cluster sizes")
    clean(trial)


def _static_units(static: Trial, height: float) -> None:
    """The standing trial's units against the stature (inferred and applied when not given)."""
    span = marker_span(static)
    lo, hi = (f * height for f in SPAN_PER_HEIGHT)
    if static.units:
        if not lo <= span <= hi:
            raise MocapError(f"{static.source}: the standing markers span {span:.3g} m, not a "
                             f"{height:g} m runner's {lo:.2f}-{hi:.2f} m: are the units "
                             f"({static.units}) right?")
        return
    scale = next((s for s in (1e-3, 1e-2, 1.0) if lo <= span * s <= hi), None)
    if scale is None:
        raise MocapError(f"{static.source}: the file gives no units and its markers span "
                         f"{span:.3g} units: no unit makes that a {height:g} m runner")
    _scale(static, scale)
    static.notes.append(f"{Path(static.source).name}: no units in the file: "
                        f"{_unit_name(scale)}, from the standing body's size "
                        f"({span * scale:.2f} m for a {height:g} m runner)")
    clean(static)


def _unit_name(scale) -> str:
    return {1e-3: "millimetres", 1e-2: "centimetres", 1.0: "metres"}.get(scale, f"{scale:g} m")


def _scale(trial: Trial, scale: float) -> None:
    for name in trial.markers:
        trial.markers[name] = trial.markers[name] * scale
    trial.units = _unit_name(scale)


def marker_span(static: Trial) -> float:
    """The largest distance between two markers' mean standing positions (the file's unit)."""
    points = np.array([p for p in static.mean_positions().values() if np.all(np.isfinite(p))])
    return float(np.max(np.linalg.norm(points[:, None] - points[None], axis=-1)))


def cluster_size(trial: Trial, ms: msets.MarkerSet) -> float:
    """The median distance between the markers of each cluster of the map, in the trial's
    median frame (m, or the file's unit)."""
    clusters = [ms.pelvis] + [[n for n in ms.cluster(side, seg) if not n.startswith("@")]
                              for side in SIDES for seg in msets.SEGMENTS]
    mid = {n: np.nanmedian(trial.markers[n], axis=0) for c in clusters for n in c if n in trial.markers}
    d = [np.linalg.norm(mid[a] - mid[b]) for c in clusters for a, b in itertools.combinations(c, 2)
         if a in mid and b in mid]
    d = [x for x in d if np.isfinite(x) and x > 0]
    if not d:
        raise MocapError(f"{trial.source}: no marker cluster of the {ms.name} map to measure")
    return float(np.median(d))
