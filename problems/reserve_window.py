"""The reserves' 10 ms mean read two ways on one muscle stride: as result.reserve_mean reads it
(|r| on each interval its trapezoid mean, the validity's measure since 2026-11-27) and with |r|
linear between the nodes (as checks.forward replays the reserves), next to their node value.
On a window of about one interval the two differ: a lone node's spike reads 0.5 and 0.75 of its
height at W = h. The stride: a shipped or given stride scene's strike, one start, no forward
check (its reserves are the NLP's).

    python problems/reserve_window.py [--scene stride_muscles] [--strike heel] [--window 0.01]

Prints the stride's cadence, its node spacing (ms), and the three readings (N m/kg).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from formopt import api
from formopt.optim.stride import optimum
from formopt.optim.stride.result import RESERVE_WINDOW_S, reserve_mean


def integral(times: np.ndarray, rows: np.ndarray, x: np.ndarray) -> np.ndarray:
    """int_0^x |r| dt (rows (6, c) of |r| at `times`, non-decreasing, linear between them)."""
    h = np.diff(times)
    k = np.clip(np.searchsorted(times, x, side="right") - 1, 0, times.size - 2)
    area = np.concatenate([np.zeros((rows.shape[0], 1)), np.cumsum(0.5 * (rows[:, 1:] + rows[:, :-1]) * h, axis=1)],
                          axis=1)
    s = x - times[k]
    slope = (rows[:, k + 1] - rows[:, k]) / np.where(h[k] > 0, h[k], 1.0)
    return area[:, k] + rows[:, k] * s + 0.5 * slope * s ** 2


def linear_mean(t: np.ndarray, reserves: np.ndarray, window: float = RESERVE_WINDOW_S) -> float:
    """reserve_mean's largest 10 ms mean with |r| linear between the nodes: the mean is quadratic
    in t0 between its breakpoints (t0 or t0 + W at a node), so per piece its ends and its vertex."""
    T = t[-1]
    times = np.concatenate([t, t + T])
    rows = np.abs(np.hstack([reserves, reserves[[3, 4, 5, 0, 1, 2]]]))
    ends = np.unique(np.clip(np.concatenate([times, times - window]), 0.0, T))

    def mean(x):
        return (integral(times, rows, x + window) - integral(times, rows, x)) / window

    a, m, b = mean(ends[:-1]), mean(0.5 * (ends[1:] + ends[:-1])), mean(ends[1:])
    p, c = 0.5 * (b - a), 0.5 * (a + b) - m  # the piece m + p u + c u^2, u in [-1, 1]
    u = np.where(c < 0, -p / np.where(c < 0, 2 * c, 1.0), 2.0)
    vertex = np.where(np.abs(u) <= 1, m + p * u + c * u ** 2, -np.inf)
    return float(max(a.max(), b.max(), vertex.max()))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="stride_muscles")
    parser.add_argument("--strike", default="heel")
    parser.add_argument("--window", type=float, default=RESERVE_WINDOW_S)
    args = parser.parse_args(argv)
    spike = np.zeros((6, 31))
    spike[2, 15] = 1.0
    grid = np.linspace(0.0, 0.3, 31)  # 10 ms intervals
    print(f"a lone spike of 1 at W = h = 10 ms: interval means {reserve_mean(grid, spike):.3f}, "
          f"linear {linear_mean(grid, spike):.3f}")
    scene = api.load(args.scene)
    nlp = scene.nlp(args.strike)
    stride = optimum(nlp, scene.speed, scene.slope, scene.friction, scene.cadence, simulate=False,
                     starts=scene.starts)
    n = nlp.ocp.models[0].actuation.n
    r = np.hstack([stride.solved.blocks[f"U_{p.name}"] for p in nlp.phases])[6 * n:]
    h = np.diff(stride.t)
    print(f"{args.scene}, {args.strike}, {scene.speed} m/s, {nlp.settings.nodes} nodes: {stride.cadence_spm:.1f} "
          f"steps/min, intervals {h[h > 0].min() * 1e3:.1f}-{h.max() * 1e3:.1f} ms; reserves over "
          f"{args.window * 1e3:g} ms: interval means {reserve_mean(stride.t, r, args.window):.4f}, linear "
          f"{linear_mean(stride.t, r, args.window):.4f}; at a node {np.abs(r).max():.4f} N m/kg")
    return 0


if __name__ == "__main__":
    sys.exit(main())
