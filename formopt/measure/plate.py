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

The stopped mass (two_mass_fit, after Clark, Ryan & Weyand 2017, J Exp Biol 220:247): the
vertical force of one contact, from the touchdown until it falls back through CONTACT_END_N,
fitted as the sum of two pulses: F(t) = A1 sin(pi t / (2 t1)) for t < 2 t1 (the foot and
shank stopped at touchdown, a half sine peaking at t1) + A2 sin(pi t / t_c) (the rest of the
body over the contact time t_c). A1, A2 >= 0 by least squares for each t1 in IMPACT_SEARCH_S
(1 ms steps: where plate_impact seeks the impact peak), the t1 of the best R^2 kept; the stopped
mass's impulse J1 = 4 A1 t1 / pi. A t1 on the range's end is no impact pulse the plate can
separate: the first pulse then takes up the stance's departure from a half sine (RBDS001's
forefoot steps: t1 free up to 100 ms goes to 75-100 ms, half the stance).
Clark et al. fitted 500 waveforms with R^2 0.95 (rearfoot and forefoot alike), the stopped
mass about 8 % of body mass.
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
CONTACT_END_N = 50.0  # N: the contact ends when the vertical force falls back through this
MIN_CONTACT_S = 0.1  # s: a contact shorter than this is not a running stance (no fit)


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


@dataclass(frozen=True)
class TwoMassFit:
    """The vertical force of one contact as two pulses (module docstring), SI."""

    impulse_1: float  # N s: J1, the stopped mass's impulse
    t1: float  # s: its pulse's peak after the touchdown (the pulse lasts 2 t1)
    impulse_2: float  # N s: the rest of the body's half sine
    contact: float  # s: t_c, the window fitted (touchdown to CONTACT_END_N)
    r2: float  # the fit's coefficient of determination over the window
    r2_half_sine: float  # the half sine's alone (what the first pulse adds)

    @property
    def bounded(self) -> bool:
        """t1 on an end of IMPACT_SEARCH_S: no separate impact pulse."""
        return min(abs(self.t1 - b) for b in IMPACT_SEARCH_S) < 5e-4


def two_mass_fit(force, rate: float, up, time: float, source: str = "") -> TwoMassFit | None:
    """The two-mass fit of the contact starting at `time` (s): force (samples, 3; N) at `rate`
    Hz, `up` the lab's (3,); None when the contact is shorter than MIN_CONTACT_S or runs past
    the end of the record."""
    f = lowpass(force, rate, min(FORCE_CUTOFF_HZ, 0.4 * rate), source) @ up
    k0 = round(time * rate)
    after = np.flatnonzero(f[k0 + round(MIN_CONTACT_S * rate):] < CONTACT_END_N)
    if not len(after):
        return None
    end = k0 + round(MIN_CONTACT_S * rate) + int(after[0])
    y, t = f[k0:end], np.arange(end - k0) / rate
    contact = (end - k0) / rate
    half_sine = np.sin(np.pi * t / contact)
    spread = float(np.sum((y - y.mean()) ** 2))
    alone = 1.0 - float(np.sum((y - (y @ half_sine) / (half_sine @ half_sine) * half_sine) ** 2)) / spread
    best = None
    for t1 in np.arange(IMPACT_SEARCH_S[0], IMPACT_SEARCH_S[1] + 1e-9, 0.001):
        pulse = np.where(t < 2 * t1, np.sin(np.pi * t / (2 * t1)), 0.0)
        a, residual = _nonnegative_lstsq(np.stack([pulse, half_sine], axis=1), y)
        r2 = 1.0 - residual / spread
        if best is None or r2 > best.r2:
            best = TwoMassFit(4 * a[0] * t1 / np.pi, float(t1), 2 * a[1] * contact / np.pi, contact, r2, alone)
    return best


def _nonnegative_lstsq(A, y) -> tuple[np.ndarray, float]:
    """min |A x - y| over x >= 0 for two columns: the free solution, else the better of
    each column alone."""
    x = np.linalg.lstsq(A, y, rcond=None)[0]
    if np.all(x >= 0):
        return x, float(np.sum((A @ x - y) ** 2))
    options = []
    for j in range(2):
        xj = np.zeros(2)
        xj[j] = max(float(A[:, j] @ y / (A[:, j] @ A[:, j])), 0.0)
        options.append((xj, float(np.sum((A @ xj - y) ** 2))))
    return min(options, key=lambda o: o[1])
