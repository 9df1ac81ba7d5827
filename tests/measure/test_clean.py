"""Cleaning on known signals: what is marked missing (NaN, zeros, frozen stretches, spikes),
how gaps are filled (linear interpolation: exact on a line, within h^2/8 max|f''| on a
sinusoid) and what a trial records about it."""

import numpy as np
import pytest

from formopt.io.mocap import MocapError, Trial
from formopt.measure.clean import (
    FROZEN,
    MAX_GAP,
    SPIKE,
    clean,
    fill_gaps,
    frozen,
    missing_samples,
    runs,
    spikes,
)

RATE = 150.0  # Hz


def sine(frames=300, f=2.0, amplitude=0.1):
    """A marker moving on a 3-D sinusoid (frames, 3), m."""
    t = np.arange(frames) / RATE
    return np.column_stack([amplitude * np.sin(2 * np.pi * f * t), 1.0 + 0.5 * amplitude * np.cos(2 * np.pi * f * t),
                            0.2 + 0.01 * t])


def test_runs():
    assert runs([0, 1, 1, 0, 1]) == [(1, 3), (4, 5)]
    assert runs([0, 0]) == [] and runs([1, 1, 1]) == [(0, 3)]


def test_nan_rows_and_exact_zeros_are_missing():
    xyz = sine(10)
    xyz[2, 1] = np.nan
    xyz[5] = 0.0
    xyz[7, 0] = 0.0  # one zero coordinate is a measurement
    assert np.flatnonzero(missing_samples(xyz)).tolist() == [2, 5]


def test_filled_gaps_are_exact_on_a_line_and_within_the_interpolation_bound_on_a_sinusoid():
    line = np.outer(np.arange(50.0), [0.01, -0.02, 0.003]) + [0.1, 1.0, 0.0]
    gap = np.zeros(50, bool)
    gap[10:20] = True
    assert fill_gaps(np.where(gap[:, None], np.nan, line), gap) == pytest.approx(line, abs=1e-15)
    xyz, f, amplitude = sine(), 2.0, 0.1
    gap = np.zeros(len(xyz), bool)
    gap[100:100 + MAX_GAP] = True
    h = (MAX_GAP + 1) / RATE  # the interpolated span, s
    bound = h ** 2 / 8 * amplitude * (2 * np.pi * f) ** 2
    error = np.abs(fill_gaps(np.where(gap[:, None], 0.0, xyz), gap) - xyz)
    assert np.max(error) <= bound and np.max(error) > 0.2 * bound
    assert np.all(error[~gap] == 0)


def test_gaps_at_the_ends_hold_the_nearest_sample():
    xyz = sine(20)
    gap = np.zeros(20, bool)
    gap[:3] = gap[-2:] = True
    out = fill_gaps(xyz, gap)
    assert np.all(out[:3] == xyz[3]) and np.all(out[-2:] == xyz[-3])


def test_frozen_stretches_of_five_samples_are_marked_four_are_not():
    xyz = sine()
    xyz[50:50 + FROZEN] = xyz[50]
    xyz[200:200 + FROZEN - 1] = xyz[200]
    assert np.flatnonzero(frozen(xyz)).tolist() == list(range(50, 50 + FROZEN))


def test_spikes_over_25_mm_are_marked_smaller_ones_and_missing_samples_are_not():
    xyz = sine(f=1.0)  # moves at most 4 mm a frame, so the median of 5 is within 8 mm of it
    xyz[40] += [SPIKE * 1.5, 0, 0]
    xyz[80] += [0, SPIKE * 0.6, 0]
    xyz[120] += [0, 0, -SPIKE * 2.0]
    missing = np.zeros(len(xyz), bool)
    missing[120] = True  # already missing: not counted as a spike
    assert np.flatnonzero(spikes(xyz, missing)).tolist() == [40]
    assert not spikes(xyz[:4] + [1, 0, 0], np.zeros(4, bool)).any()  # too short to judge


def test_clean_marks_fills_and_records_what_it_did():
    xyz = sine()
    truth = xyz.copy()
    xyz[30] += [0.2, 0.0, 0.0]  # a spike
    xyz[60:60 + FROZEN] = xyz[60]  # frozen
    xyz[100:100 + MAX_GAP + 5] = np.nan  # a gap too long to trust
    trial = Trial({"R.Knee": xyz, "L.Knee": truth.copy()}, RATE, source="run.c3d")
    assert clean(trial) is trial
    marked = trial.suspect["R.Knee"]
    assert np.flatnonzero(marked).tolist() == [30, *range(60, 60 + FROZEN), *range(100, 100 + MAX_GAP + 5)]
    assert "L.Knee" not in trial.suspect and np.all(trial.markers["L.Knee"] == truth)
    assert trial.gaps == {"R.Knee": [(100, 100 + MAX_GAP + 5)]}
    assert np.all(np.isfinite(trial.markers["R.Knee"]))
    h, amplitude, f = (MAX_GAP + 6) / RATE, 0.1, 2.0  # the longest filled span (s); sine()'s motion
    assert np.max(np.abs(trial.markers["R.Knee"] - truth)) <= h ** 2 / 8 * amplitude * (2 * np.pi * f) ** 2
    notes = " | ".join(trial.notes)
    assert "R.Knee: 1 gaps longer than 10 frames (0.67-0.77 s)" in notes
    assert "1 spike samples (over 25 mm off their neighbours)" in notes
    assert "frozen stretches (the same position 5+ frames running) treated as missing in R.Knee" in notes
    assert f"{1 + FROZEN + MAX_GAP + 5} missing marker samples in 1 markers" in notes


def test_a_marker_with_no_valid_frame_is_refused():
    with pytest.raises(MocapError, match=r"run.c3d: marker R.Knee has no valid frame"):
        clean(Trial({"R.Knee": np.zeros((20, 3))}, RATE, source="run.c3d"))
