"""optim.stride.muscle_readings: the reserves' largest mean over their window (the muscle
stride's validity), against a brute-force moving mean."""

import numpy as np
import pytest

from formopt.optim.stride.muscle_readings import RESERVE_WINDOW_S, reserve_mean


def test_the_reserves_mean_over_their_window():
    """reserve_mean: |r| averaged over RESERVE_WINDOW_S, the worst window of the periodic stride
    (the next half stride the legs swapped), so a one-node spike counts by its impulse."""
    t = np.linspace(0.0, 0.3, 301)  # 1 ms intervals, a half period of 0.3 s
    r = np.zeros((6, t.size))
    r[1] = 0.04  # the right knee's constant reserve: its mean is itself
    assert reserve_mean(t, r) == pytest.approx(0.04)
    r[1], r[2, 150] = 0.0, 1.0  # one node's spike: a triangle of area 1 ms * 1 N m/kg
    assert reserve_mean(t, r) == pytest.approx(1e-3 / RESERVE_WINDOW_S)
    r[2, 150], r[1, -1], r[4, 0] = 0.0, 1.0, 1.0  # the right knee at the end, the left at the start:
    assert reserve_mean(t, r) == pytest.approx(1e-3 / RESERVE_WINDOW_S)  # one burst across the touchdown
    assert reserve_mean(t, -r) == reserve_mean(t, r)  # |r|


def test_the_reserves_mean_reads_them_linear_between_the_nodes():
    """reserve_mean against a brute-force moving mean of |r| linear between the nodes (a lone
    spike at W = h reads 0.75 of its height), with a phase boundary's time twice, and a window
    longer than the half period refused."""
    t = np.linspace(0.0, 0.1, 11)  # 10 ms intervals
    r = np.zeros((6, t.size))
    r[2, 5] = 1.0
    assert reserve_mean(t, r, 0.01) == pytest.approx(0.75)
    t = np.r_[np.linspace(0.0, 0.04, 5), np.linspace(0.04, 0.1, 7)]  # a phase boundary at 40 ms: twice
    r = np.random.default_rng(0).normal(size=(6, t.size))  # two values there
    times, rows = np.concatenate([t, t + t[-1]]), np.abs(np.hstack([r, r[[3, 4, 5, 0, 1, 2]]]))
    fine = np.linspace(0.0, times[-1], 200001)
    k = np.clip(np.searchsorted(times, fine, side="right") - 1, 0, times.size - 2)
    h = np.diff(times)[k]
    s = np.divide(fine - times[k], h, out=np.zeros_like(fine), where=h > 0)
    linear = rows[:, k] * (1 - s) + rows[:, k + 1] * s  # |r| on a 1 us grid
    window = 0.013
    step = fine[1] - fine[0]
    area = np.concatenate([np.zeros((6, 1)), np.cumsum(0.5 * (linear[:, 1:] + linear[:, :-1]) * step, axis=1)], axis=1)
    n = round(window / step)
    brute = ((area[:, n:] - area[:, :-n]) / window)[:, :fine.size // 2].max()
    assert reserve_mean(t, r, window) == pytest.approx(brute, rel=1e-4)
    with pytest.raises(ValueError, match=r"window 0\.2 s outside"):
        reserve_mean(t, r, 0.2)
