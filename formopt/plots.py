"""Figures: stick figures of touchdown postures and bars of their impact indicators.

Files are written to a temporary name and renamed, so a figure on disk is always whole.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .body import Body  # noqa: E402
from .impact import ImpactResult, ground_axes  # noqa: E402
from .model import STRIKES, positions  # noqa: E402

POINT_MASS_TRUNK = 0.45  # m, length of the line that shows a point-mass trunk's lean


def stick_figure(ax, body: Body, x, strike: str, slope: float, color: str, label: str):
    """Draw the leg (and trunk) at touchdown state x, strike point at the origin."""
    p = positions(x, body, STRIKES[strike][0])
    chain = [p["hip"], p["knee"], p["ankle"]]
    ax.plot(*np.array(chain).T, "-o", color=color, lw=2.5, ms=4, label=label)
    foot = np.array([p["ankle"], p["heel"], p["forefoot"], p["ankle"]])
    ax.fill(*foot.T, color=color, alpha=0.35, lw=1.5, ec=color)
    if "shoulder" in p:
        ax.plot(*np.array([p["hip"], p["shoulder"]]).T, "-", color=color, lw=4)
    else:  # a point mass at the hip: show its lean only
        trunk = x[0]
        top = p["hip"] + POINT_MASS_TRUNK * np.array([math.sin(trunk), math.cos(trunk)])
        ax.plot(*np.array([p["hip"], top]).T, ":", color=color, lw=2)
    ax.plot(*p["hip"], "o", color=color, ms=10, alpha=0.6)


def ground(ax, slope: float, span=(-0.6, 0.6)):
    t, _ = ground_axes(slope)
    ends = np.array([span[0] * t, span[1] * t])
    ax.plot(*ends.T, color="0.3", lw=1)
    ax.fill_between(ends[:, 0], ends[:, 1], ends[:, 1] - 0.05, color="0.85")


def posture_figure(path, body: Body, strike: str, slope: float, postures) -> Path:
    """Overlaid stick figures; `postures` is a list of (state, label, color)."""
    fig, ax = plt.subplots(figsize=(5.5, 6.5))
    ground(ax, slope)
    for x, label, color in postures:
        stick_figure(ax, body, x, strike, slope, color, label)
    ax.set_aspect("equal")
    ax.set_xlabel("x, forward (m)")
    ax.set_ylabel("z, up (m)")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(f"{strike} strike at touchdown", fontsize=10)
    return save(fig, path)


def indicator_figure(path, results: dict[str, ImpactResult]) -> Path:
    """Bars of T_c, impulses, mu_c and dv of the trunk for each labelled result."""
    names = ["T_c (J)", "normal impulse (N s)", "tangential impulse (N s)", "mu_c",
             "dv trunk x (m/s)", "dv trunk z (m/s)"]

    def values(r):
        dv = r.dv_trunk or (float("nan"), float("nan"))
        return [r.T_c, r.impulse_total[1], r.impulse_total[0], r.mu_c, dv[0], dv[1]]

    fig, axes = plt.subplots(1, len(names), figsize=(12, 3.2))
    colors = ["0.55", "tab:blue", "tab:orange", "tab:green"]
    for k, (ax, name) in enumerate(zip(axes, names)):
        for j, (label, r) in enumerate(results.items()):
            ax.bar(j, values(r)[k], color=colors[j % len(colors)], label=label)
        ax.set_title(name, fontsize=9)
        ax.set_xticks([])
        ax.axhline(0, color="0.3", lw=0.8)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)


def save(fig, path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.tmp{path.suffix}")
    fig.savefig(tmp, dpi=120)
    plt.close(fig)
    os.replace(tmp, path)
    return path
