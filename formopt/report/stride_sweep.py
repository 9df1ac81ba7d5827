"""Figures of a stride map (studies.stride_map rows, as read from its CSV: strings).

- `cadence_figure`: the scene's objective, the mechanical power and the impact loss against
  the imposed cadence (or step length), one line per speed (or per value of the other swept
  parameter); on each line the least-objective row is marked: the free optimum as the grid
  resolves it (the rows' minimum, not a separate free solve).
- `speed_figure`: against speed, the least-objective row of each speed (over the other
  parameter, when one is swept): its power, impact loss and cadence.
- `map_figure`: filled contours of the objective, the power and the impact loss over the
  first two parameters, the least-objective point of each line of the first marked.

Valid strides (optim.stride.result: impacts and checks) are drawn filled, converged invalid ones
hollow, strides without an optimum as red crosses (and left out of lines and contours).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from matplotlib.figure import Figure

from .figures import _axis_label, _subplots

LABELS = {"cadence_spm": "cadence (steps/min)", "step_length_m": "step length (m)",
          "speed_mps": "running speed (m/s)", "slope_deg": "slope (deg)",
          "friction": "friction coefficient", "objective_value": "objective (per distance)",
          "mechanical_power_W": "mechanical power W+/T (W)",
          "impact_loss_W": "impact loss, T_c x step rate (W)"}
PANELS = ("objective_value", "mechanical_power_W", "impact_loss_W")


def _label(key: str) -> str:
    return LABELS.get(key) or _axis_label(key)


def _converged(rows) -> list[dict]:
    return [r for r in rows if not r["error"] and r["success"] == "True"]


def _value(r, key) -> float:
    return float(r[key]) if r.get(key) not in ("", None) else np.nan


def _best(rows) -> dict:
    """The best row as optim.stride.rank orders strides: valid first, then the least objective."""
    return min(rows, key=lambda r: (r["valid"] != "True", float(r["objective_value"])))


def _groups(rows, by: str | None) -> dict[float, list[dict]]:
    """Rows by the value of `by` (all in one group when None)."""
    out: dict[float, list[dict]] = {}
    for r in rows:
        out.setdefault(float(r[by]) if by else 0.0, []).append(r)
    return dict(sorted(out.items()))


def _counts(rows) -> str:
    ok = _converged(rows)
    valid = sum(r["valid"] == "True" for r in ok)
    return (f"{len(rows)} strides: {valid} valid, {len(ok) - valid} invalid (hollow), "
            f"{len(rows) - len(ok)} without an optimum (red x)")


def cadence_figure(rows: list[dict], x: str, by: str | None) -> Figure:
    """PANELS against `x` (cadence_spm or step_length_m), one line per value of `by`, the
    best row of each line (valid first, then the least objective) marked with a star."""
    fig, axes = _subplots(1, len(PANELS), figsize=(4.2 * len(PANELS), 3.8))
    groups = _groups(_converged(rows), by)
    many = len(groups) > 10  # a colour scale (and a colour bar) instead of a legend
    import matplotlib

    colors = ([matplotlib.colormaps["viridis"](k / max(len(groups) - 1, 1)) for k in range(len(groups))]
              if many else [f"C{k % 10}" for k in range(len(groups))])
    for (value, line), color in zip(groups.items(), colors):
        line = sorted(line, key=lambda r: float(r[x]))
        xs = np.array([float(r[x]) for r in line])
        bad = np.array([r["valid"] != "True" for r in line])
        best = _best(line)
        for ax, key in zip(axes, PANELS):
            y = np.array([_value(r, key) for r in line])
            ax.plot(xs, y, "-o", ms=3, lw=1, color=color,
                    label=f"{by} = {value:g}" if by else None)
            if bad.any():
                ax.plot(xs[bad], y[bad], "o", ms=6, mfc="white", color=color)
            ax.plot(float(best[x]), _value(best, key), "*", ms=12, color=color, mec="black", clip_on=False)
    failed = [r for r in rows if r["error"] or r["success"] != "True"]
    for ax, key in zip(axes, PANELS):
        if failed:
            ax.plot([float(r[x]) if r[x] else np.nan for r in failed],
                    np.full(len(failed), np.nanmin(ax.get_ylim())), "x", color="red", ms=6)
        ax.set_xlabel(_label(x))
        ax.set_ylabel(_label(key))
    if by and not many:
        axes[0].legend(fontsize=7)
    elif by:
        values = list(groups)
        scale = matplotlib.cm.ScalarMappable(matplotlib.colors.Normalize(min(values), max(values)), "viridis")
        fig.colorbar(scale, ax=axes[-1], label=_label(by))
    fig.suptitle(_counts(rows) + "; star: each line's least objective (the free optimum as the "
                 "grid resolves it)", fontsize=8)
    fig.tight_layout()
    return fig


def speed_figure(rows: list[dict]) -> Figure:
    """Against speed, the least-objective row of each speed: its power, impact loss, cadence."""
    best = [_best(line) for line in _groups(_converged(rows), "speed_mps").values()]
    fig, axes = _subplots(1, 3, figsize=(12.6, 3.8))
    speeds = np.array([float(r["speed_mps"]) for r in best])
    for ax, key in zip(axes, ("mechanical_power_W", "impact_loss_W", "cadence_spm")):
        y = np.array([_value(r, key) for r in best])
        ax.plot(speeds, y, "-o", ms=3, color="tab:blue")
        bad = np.array([r["valid"] != "True" for r in best])
        if bad.any():
            ax.plot(speeds[bad], y[bad], "o", ms=6, mfc="white", color="tab:blue")
        ax.set_xlabel(_label("speed_mps"))
        ax.set_ylabel(_label(key))
    fig.suptitle(_counts(rows) + "; per speed the least-objective stride of the grid", fontsize=8)
    fig.tight_layout()
    return fig


def map_figure(rows: list[dict], px: str, py: str) -> Figure:
    """Filled contours of PANELS over (px, py); per value of px, the least-objective point
    (white stars), invalid strides as rings, failed ones as red crosses."""
    ok = _converged(rows)
    xs = sorted({float(r[px]) for r in rows})
    ys = sorted({float(r[py]) for r in rows})
    fig, axes = _subplots(1, len(PANELS), figsize=(4.6 * len(PANELS), 3.8))
    stars = [_best(line) for line in _groups(ok, px).values()]
    for ax, key in zip(axes, PANELS):
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in ok:
            grid[ys.index(float(r[py])), xs.index(float(r[px]))] = _value(r, key)
        if len(xs) > 1 and len(ys) > 1 and np.isfinite(grid).sum() >= 3:
            filled = ax.contourf(xs, ys, np.ma.masked_invalid(grid), levels=14, cmap="viridis")
        else:  # too few points for contours (a pcolormesh of one column drew nothing): squares
            filled = ax.scatter([float(r[px]) for r in ok], [float(r[py]) for r in ok],
                                c=[_value(r, key) for r in ok], marker="s", s=150, cmap="viridis")
        fig.colorbar(filled, ax=ax, label=_label(key))
        ax.plot([float(r[px]) for r in stars], [float(r[py]) for r in stars], "*", ms=9,
                color="white", mec="black", clip_on=False)
        invalid = [r for r in ok if r["valid"] != "True"]
        ax.plot([float(r[px]) for r in invalid], [float(r[py]) for r in invalid], "o", ms=5,
                mfc="none", color="white")
        failed = [r for r in rows if r["error"] or r["success"] != "True"]
        ax.plot([float(r[px]) for r in failed], [float(r[py]) for r in failed], "x", color="red", ms=5)
        ax.set_xlabel(_label(px))
        ax.set_ylabel(_label(py))
    fig.suptitle(_counts(rows) + f"; star: the least objective at each {_label(px).split(' (')[0]}",
                 fontsize=8)
    fig.tight_layout()
    return fig


def stride_sweep_figures(rows: list[dict], params: list[str]) -> dict[str, Figure]:
    """The figures a grid supports, by name: `cadence` when the cadence or step length is
    swept (lines per value of the other parameter), `speed` when the speed is, `map` for two
    parameters (the first two). None when no stride converged."""
    if not _converged(rows):
        return {}
    figures = {}
    imposed = [p for p in params if p in ("cadence_spm", "step_length_m")]
    others = [p for p in params if p not in imposed]
    if imposed:
        figures["cadence"] = cadence_figure(rows, imposed[0], others[0] if others else None)
    if "speed_mps" in params:
        figures["speed"] = speed_figure(rows)
    if len(params) >= 2:
        figures["map"] = map_figure(rows, params[0], params[1])
    if not figures:  # one parameter, neither cadence nor speed: cadence-figure style lines
        figures["curve"] = cadence_figure(rows, params[0], None)
    return figures
