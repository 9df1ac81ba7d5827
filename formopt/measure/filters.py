"""Zero-lag low-pass filtering of marker and force signals (time along axis 0).

A Butterworth filter of order ORDER is run forward and backward (scipy's `sosfiltfilt`, in
second-order sections): no phase lag, and the magnitude is the design filter's squared,
`|H(f)|^2`. So at the design cut-off `fc` the gain is 1/2 (-6 dB), not 1/sqrt(2); the
-3 dB point of the pass sits lower (`effective_cutoff`). For the bilinear Butterworth,
`|H(f)|^2 = 1 / (1 + (tan(pi f / fs) / tan(pi fc / fs))^(2 n))`, so the pass's -3 dB point is
`f3 = fs / pi * atan((sqrt(2) - 1)^(1 / (2 n)) tan(pi fc / fs))`, about 0.802 fc for n = 2
and fc well below fs / 2.
"""

from __future__ import annotations

import math

import numpy as np

from ..io.mocap import MocapError

CUTOFF_HZ = 10.0  # the markers' default design cut-off (Winter 2009, Biomechanics and Motor
#                   Control of Human Movement)
ORDER = 2  # of the design filter; run forward and backward: 4th order, zero lag


def design(rate: float, cutoff: float, source: str = "") -> np.ndarray:
    """Second-order sections (n, 6) of the ORDER Butterworth low-pass at `cutoff` Hz for
    samples at `rate` Hz; refused unless 0 < cutoff < rate / 2."""
    from scipy.signal import butter

    if not 0 < cutoff < rate / 2:
        raise MocapError(f"{source}: the filter cutoff {cutoff:g} Hz must lie between 0 and half "
                         f"the sampling rate ({rate / 2:g} Hz)")
    return butter(ORDER, cutoff / (rate / 2), output="sos")


def lowpass(x, rate: float, cutoff: float, source: str = "") -> np.ndarray:
    """`x` (samples, ...) low-passed along axis 0: the design filter at `cutoff` Hz run forward
    and backward (module docstring: -6 dB at `cutoff`, -3 dB at effective_cutoff(rate, cutoff))."""
    from scipy.signal import sosfiltfilt

    sos = design(rate, cutoff, source)
    padlen = 3 * (2 * len(sos) + 1)  # sosfiltfilt's default odd extension at each end
    if len(x) <= padlen:
        raise MocapError(f"{source}: {len(x)} samples are too few to filter")
    return sosfiltfilt(sos, x, axis=0)


def gain(rate: float, cutoff: float, frequency) -> np.ndarray:
    """Magnitude of the forward-backward pass at `frequency` Hz: |H(f)|^2 of the design filter."""
    from scipy.signal import sosfreqz

    _, h = sosfreqz(design(rate, cutoff), worN=np.atleast_1d(np.asarray(frequency, float)), fs=rate)
    return np.abs(h) ** 2


def effective_cutoff(rate: float, cutoff: float) -> float:
    """The -3 dB frequency (Hz) of `lowpass`: where the forward-backward gain is 1/sqrt(2),
    found on the filter's own response (between 0 and `cutoff`, where the gain is 1/2)."""
    from scipy.optimize import root_scalar

    target = 1.0 / math.sqrt(2.0)
    found = root_scalar(lambda f: float(gain(rate, cutoff, f)[0]) - target,
                        bracket=(0.0, cutoff), method="brentq", xtol=1e-12)
    return float(found.root)
