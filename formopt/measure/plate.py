"""What a force plate says about each touchdown, beside the markers: where the foot first
pushes (the centre of pressure along the foot) and the impact (its window, impulse ratio, peak
and loading rate).

Where the foot first pushes (strike_index): the centre of pressure's place along the foot,
0 at the heel point and 1 at the forefoot point (formopt's two contact points; the heel
marker and the metatarsal heads on RBDS), averaged over the first COP_WINDOW_S of the contact
weighted by the vertical force: (integral of F s dt) / (integral of F dt), the point of
application of the impulse then, with the foot's points taken at each force sample (the foot
rides the belt ~0.07 m in 20 ms). Single samples near the touchdown's 50 N are noise (the
plate's centre of pressure is a moment over a force: at 50 N it jumps across the whole foot
from one sample to the next on RBDS001); the impulse's point over 10-30 ms moves by under 0.1
of the foot on RBDS001 T25 and T35. Its class (cop_point): the heel third, the middle third
("flat": the impulse acts between the two points, both carry it) and the forefoot third of the
heel-forefoot line (Cavanagh & Lafortune 1980's strike index in thirds, taken on the contact
points the model has rather than the shoe's length).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .filters import lowpass

FORCE_CUTOFF_HZ = 50.0  # low-pass of the force before the threshold (at most 0.4 of its rate)
COP_WINDOW_S = 0.020  # s after the touchdown over which the centre of pressure is averaged
THIRDS = (1.0 / 3.0, 2.0 / 3.0)  # of the heel-forefoot line: heel, flat, forefoot
IMPACT_SEARCH_S = (0.005, 0.060)  # s after a touchdown where an impact peak is sought
IMPACT_DEFAULT_S = 0.030  # s: the impact window when the force has no distinct impact peak
LOADING_BAND = (0.2, 0.8)  # of the impact peak: the loading rate's stretch (Milner et al. 2006)


@dataclass(frozen=True)
class PlateImpact:
    """What the plate measured over one touchdown's impact: from the touchdown (the force
    through its threshold) to the impact peak, the first local maximum of the low-passed
    vertical force within IMPACT_SEARCH_S, or IMPACT_DEFAULT_S without one."""

    window_s: float  # s, the impact window's length
    peak: bool  # a distinct impact peak was found
    impulse_ratio: float  # forward / vertical impulse over the window (braking negative)
    impact_peak_bw: float  # vertical force at the window's end, body weights
    loading_rate_bw_per_s: float  # mean slope from 20 to 80 % of it, BW/s


def plate_impact(force, rate: float, forward, up, time: float, weight: float,
                 source: str = "") -> PlateImpact:
    """The plate's impact of the touchdown at `time` (s): force (samples, 3; N, the ground on
    the runner), `forward`, `up` the lab axes (3,), `weight` the runner's (N)."""
    f = lowpass(force, rate, min(FORCE_CUTOFF_HZ, 0.4 * rate), source)
    vertical, horizontal = f @ up, f @ forward
    k0 = round(time * rate)
    lo, hi = k0 + int(IMPACT_SEARCH_S[0] * rate), min(k0 + int(IMPACT_SEARCH_S[1] * rate), len(vertical) - 1)
    peaks = [k for k in range(lo, hi) if vertical[k] >= vertical[k - 1] and vertical[k] > vertical[k + 1]]
    end = peaks[0] if peaks else min(k0 + round(IMPACT_DEFAULT_S * rate), len(vertical) - 1)
    window = slice(k0, end + 1)
    ratio = float(np.trapezoid(horizontal[window]) / np.trapezoid(vertical[window]))
    top = float(vertical[end])
    a, b = (k0 + int(np.flatnonzero(vertical[window] >= s * top)[0]) for s in LOADING_BAND)
    rate_bw = (vertical[b] - vertical[a]) * rate / max(b - a, 1) / weight
    return PlateImpact((end - k0) / rate, bool(peaks), ratio, top / weight, float(rate_bw))


def strike_index(force, cop, rate: float, up, forward, time: float, t_points, heel, forefoot) -> float:
    """The centre of pressure's force-weighted place along the foot over COP_WINDOW_S after
    the touchdown at `time` (s) (module docstring): force, cop (samples, 3; N, m, lab) at
    `rate` Hz; `up`, `forward` the lab axes (3,); the foot's heel and forefoot forward
    positions (frames,; m) at times t_points (frames,; s)."""
    k = np.arange(round(time * rate), round((time + COP_WINDOW_S) * rate) + 1)
    k = k[k < len(force)]
    t = k / rate
    x_heel, x_fore = np.interp(t, t_points, heel), np.interp(t, t_points, forefoot)
    s = (cop[k] @ forward - x_heel) / (x_fore - x_heel)
    weight = np.clip(force[k] @ up, 0.0, None)
    return float(np.sum(weight * s) / np.sum(weight)) if weight.sum() > 0 else float("nan")


def cop_point(index: float) -> str:
    """The impact point the centre of pressure's `index` (strike_index) says: "heel",
    "flat" or "forefoot" (THIRDS)."""
    return "heel" if index < THIRDS[0] else "forefoot" if index > THIRDS[1] else "flat"
