"""The muscles' readings of a solved stride (`Stride.muscles`, the reserves' checks): their
metabolic energy, their tendons' stored and returned energy, and the reserves' largest mean
over a window (the muscle stride's validity, result.TOLERANCES["reserve_nm_per_kg"]).
"""

from __future__ import annotations

import numpy as np

from ...mechanics import muscles as hill
from .actuation import MuscleDriven
from .collocation import StrideNLP
from .layout import Solved
from .ocp import INTEGRANDS

# The reserves are judged by their largest mean over 10 ms (`reserve_mean`), less than the
# muscles' activation time (15 ms, mechanics.muscles), not by their largest node value: at the
# phases' first and last columns, where a contact is made or let go, the node value grows as the
# mesh's end intervals shrink while its impulse vanishes (heel, 3.5 m/s, graded 1: 0.038 / 0.073 /
# 0.099 N m/kg at the forefoot phase's last column on 80 / 160 / 320 nodes; the mean 0.012 /
# 0.013), so the peak measures the mesh, not a shortfall of the muscles (docs/concepts/muscles.md,
# "The reserves' measure").
RESERVE_WINDOW_S = 0.01


def reserve_mean(t: np.ndarray, reserves: np.ndarray, window: float = RESERVE_WINDOW_S) -> float:
    """The largest mean of |r| over `window` s (W, at most the half period T) of the periodic
    stride: t (c,) the half stride's node times (s, from 0 to T, a phase boundary's time twice),
    reserves (6, c) the right then left leg's hip, knee and ankle (N m/kg), |r| linear between
    the nodes (as checks.forward replays the reserves); the next half stride is this one with the
    legs swapped. m(t0) = (1/W) int_{t0}^{t0+W} |r| dt is quadratic in t0 between its kinks (t0 or
    t0 + W at a node), so its largest value is at a kink or at a piece's vertex."""
    T = t[-1]
    if not 0.0 < window <= T:
        raise ValueError(f"reserve_mean: window {window:g} s outside (0, {T:g}], the half period")
    times = np.concatenate([t, t + T])
    rows = np.abs(np.hstack([reserves, reserves[[3, 4, 5, 0, 1, 2]]]))
    kinks = np.unique(np.clip(np.concatenate([times, times - window]), 0.0, T))
    area = np.concatenate([np.zeros((6, 1)), np.cumsum(0.5 * (rows[:, 1:] + rows[:, :-1]) * np.diff(times), axis=1)],
                          axis=1)  # int_0^{t_k} |r| dt at each node

    def mean(t0):
        return (_integral(times, rows, area, t0 + window) - _integral(times, rows, area, t0)) / window

    a, m, b = mean(kinks[:-1]), mean(0.5 * (kinks[1:] + kinks[:-1])), mean(kinks[1:])
    p, c = 0.5 * (b - a), 0.5 * (a + b) - m  # each piece m + p u + c u^2 for u in [-1, 1]
    u = np.where(c < 0, -p / np.where(c < 0, 2 * c, 1.0), 2.0)  # a concave piece's vertex
    vertex = np.where(np.abs(u) <= 1, m + p * u + c * u ** 2, -np.inf)
    return float(max(a.max(), b.max(), vertex.max()))


def _integral(times: np.ndarray, rows: np.ndarray, area: np.ndarray, x: np.ndarray) -> np.ndarray:
    """int_0^x y dt (rows, n x points) for each row y given at `times` (non-decreasing, a time
    twice where y jumps) and linear between them, `area` its integral at each time; x (points,)
    within [times[0], times[-1]]."""
    h = np.diff(times)
    k = np.clip(np.searchsorted(times, x, side="right") - 1, 0, times.size - 2)
    s = x - times[k]
    slope = (rows[:, k + 1] - rows[:, k]) / np.where(h[k] > 0, h[k], 1.0)
    return area[:, k] + rows[:, k] * s + 0.5 * slope * s ** 2


def muscle_outputs(nlp: StrideNLP, solved: Solved, checks: dict, t: np.ndarray) -> dict | None:
    """The muscles' histories and energies per step (Stride.muscles), None for the torque rungs:
    their metabolic energy (J, the NLP's integral), the tendons' stored and returned energy (J:
    the sums of the rises and of the falls of each tendon's elastic energy,
    mechanics.muscles.tendon_energy; `achilles`: soleus and gastrocnemius); adds the reserves'
    largest mean over RESERVE_WINDOW_S (`reserve_mean`, the validity's) and largest node value
    (N m/kg) to `checks`; `force_rate_term`: the objective's force-rate power and weight (the
    metabolic objective's); t (c,) the node times (s)."""
    act, blocks = nlp.ocp.models[0].actuation, solved.blocks
    if not isinstance(act, MuscleDriven):
        return None
    n = act.n
    k = INTEGRANDS.index("muscle_metabolic")
    metabolic_J = sum(float(L[k] @ w) for L, w in nlp.integrands(blocks, solved.parameters))
    Z = np.hstack([blocks[f"Z_{p.name}"] for p in nlp.phases])
    U = np.hstack([blocks[f"U_{p.name}"] for p in nlp.phases])
    legs = [Z[2 * n * k:2 * n * (k + 1)] for k in range(2)]
    activation = np.vstack([z[:n] for z in legs])
    force = np.vstack([z[n:] for z in legs])
    stored = np.diff(np.vstack([hill.tendon_energy(act.muscles, f) for f in (force[:n], force[n:])]), axis=1)
    names = [f"{m}_{side}" for side in "RL" for m in act.muscles.names]
    rises, falls = np.maximum(stored, 0).sum(axis=1), np.maximum(-stored, 0).sum(axis=1)
    checks["reserve_nm_per_kg"] = reserve_mean(t, U[6 * n:])
    checks["reserve_peak_nm_per_kg"] = float(np.abs(U[6 * n:]).max())
    achilles = [k for k, name in enumerate(names) if name.split("_")[0] in ("soleus", "gastrocnemius")]
    rate = {"power": nlp.settings.force_rate_power, "weight": nlp.settings.rate_weight}
    return {"metabolic_J": metabolic_J, "force_rate_term": rate, "tendon_stored_J": float(rises.sum()),
            "tendon_returned_J": float(falls.sum()), "achilles_stored_J": float(rises[achilles].sum()),
            "reserve_nm_per_kg": checks["reserve_nm_per_kg"], "reserve_peak_nm_per_kg": checks["reserve_peak_nm_per_kg"],
            "names": names, "activation": activation.T,
            "tendon_force_N": (force * np.tile(act.muscles.max_force, 2)[:, None]).T,
            "peak_activation": dict(zip(names, activation.max(axis=1).round(4).tolist())),
            "stored_J": dict(zip(names, rises.round(3).tolist())),
            "returned_J": dict(zip(names, falls.round(3).tolist()))}
