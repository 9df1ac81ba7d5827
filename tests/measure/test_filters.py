"""The zero-lag low-pass: its gain measured on sinusoids against what it promises (-6 dB at the
design cut-off, -3 dB at effective_cutoff), the -3 dB point against the Butterworth's closed
form, and the second-order sections against the transfer-function form they replaced."""

import math

import numpy as np
import pytest
from scipy.signal import butter, filtfilt

from formopt.io.mocap import MocapError
from formopt.measure.filters import CUTOFF_HZ, ORDER, effective_cutoff, gain, lowpass

RATE = 150.0  # Hz, RBDS001's marker rate


def measured_gain(frequency, rate=RATE, cutoff=CUTOFF_HZ, seconds=20.0):
    """Amplitude out / in of a sinusoid at `frequency`, fitted (sin and cos) over the middle
    half of the record, away from the ends' transients."""
    t = np.arange(int(seconds * rate)) / rate
    y = lowpass(np.sin(2 * np.pi * frequency * t), rate, cutoff)
    mid = slice(len(t) // 4, 3 * len(t) // 4)
    basis = np.column_stack([np.sin(2 * np.pi * frequency * t[mid]), np.cos(2 * np.pi * frequency * t[mid])])
    (a, b), *_ = np.linalg.lstsq(basis, y[mid], rcond=None)
    return math.hypot(a, b)


@pytest.mark.parametrize("rate,cutoff", [(150.0, 10.0), (300.0, 50.0), (1000.0, 6.0)])
def test_gain_is_half_at_the_cutoff_and_one_over_root_two_at_the_effective_cutoff(rate, cutoff):
    assert measured_gain(cutoff, rate, cutoff) == pytest.approx(0.5, abs=1e-3)  # -6.02 dB
    f3 = effective_cutoff(rate, cutoff)
    assert measured_gain(f3, rate, cutoff) == pytest.approx(1 / math.sqrt(2), abs=1e-3)  # -3.01 dB
    assert measured_gain(0.1 * cutoff, rate, cutoff) == pytest.approx(1.0, abs=1e-3)
    assert gain(rate, cutoff, [cutoff, f3]) == pytest.approx([0.5, 1 / math.sqrt(2)], abs=1e-12)


@pytest.mark.parametrize("rate,cutoff", [(150.0, 10.0), (300.0, 50.0), (100.0, 40.0), (2000.0, 1.0)])
def test_effective_cutoff_matches_the_butterworth_closed_form(rate, cutoff):
    """|H|^2 = 1 / (1 + (tan(pi f/fs) / tan(pi fc/fs))^(2n)) (bilinear Butterworth), so the
    pass's |H|^2 = 1/sqrt(2) at tan(pi f/fs) = (sqrt(2) - 1)^(1/(2n)) tan(pi fc/fs)."""
    x = (math.sqrt(2) - 1) ** (1 / (2 * ORDER)) * math.tan(math.pi * cutoff / rate)
    assert effective_cutoff(rate, cutoff) == pytest.approx(rate / math.pi * math.atan(x), rel=1e-9)


def test_effective_cutoff_is_0_802_of_the_cutoff_far_below_nyquist():
    assert effective_cutoff(10000.0, 1.0) == pytest.approx((math.sqrt(2) - 1) ** 0.25, rel=1e-6)
    assert effective_cutoff(10000.0, 1.0) == pytest.approx(0.802, abs=5e-4)
    # RBDS001's markers (10 Hz at 150 Hz): the bilinear warp lifts the ratio a little above 0.802
    assert 0.802 < effective_cutoff(RATE, CUTOFF_HZ) / CUTOFF_HZ < 0.81


def test_second_order_sections_match_the_transfer_function_form():
    """The filter before sections: butter's (b, a) through filtfilt; the same to round-off."""
    rng = np.random.default_rng(4)
    x = np.cumsum(rng.normal(size=(900, 3)), axis=0)
    b, a = butter(ORDER, CUTOFF_HZ / (RATE / 2))
    assert lowpass(x, RATE, CUTOFF_HZ) == pytest.approx(filtfilt(b, a, x, axis=0), abs=1e-10)


@pytest.mark.parametrize("cutoff", [0.0, 75.0, 100.0])
def test_cutoffs_outside_zero_to_nyquist_are_refused(cutoff):
    with pytest.raises(MocapError, match=f"run.c3d: the filter cutoff {cutoff:g} Hz must lie between 0 "
                                         f"and half the sampling rate .75 Hz."):
        lowpass(np.zeros((100, 3)), RATE, cutoff, "run.c3d")


def test_too_short_a_signal_is_refused():
    with pytest.raises(MocapError, match=r"run.c3d: 9 samples are too few to filter"):
        lowpass(np.zeros((9, 3)), RATE, CUTOFF_HZ, "run.c3d")
    assert lowpass(np.ones((10, 3)), RATE, CUTOFF_HZ) == pytest.approx(np.ones((10, 3)))
