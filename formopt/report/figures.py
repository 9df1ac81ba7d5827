"""Figures: each function returns a Matplotlib Figure (saved by the caller, for example with
formopt.io.files.save_figure). Figures are made with `matplotlib.figure.Figure`, not pyplot,
so importing this module never touches the user's backend or open windows.
"""

from __future__ import annotations

import math
import textwrap
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # Matplotlib is imported when a figure is drawn: 0.26 s at every CLI start otherwise
    from matplotlib.figure import Figure

from ..mechanics.body import Body
from ..mechanics.impact import ImpactResult
from ..mechanics.model import STRIKES, ground_axes, positions

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


def posture_figure(body: Body, strike: str, slope: float, postures) -> Figure:
    """Overlaid stick figures; `postures` is a list of (state, label, color)."""
    fig, ax = _subplots(figsize=(5.5, 6.5))
    ground(ax, slope)
    for x, label, color in postures:
        stick_figure(ax, body, x, strike, slope, color, label)
    ax.set_aspect("equal")
    ax.set_xlabel("x, forward (m)")
    ax.set_ylabel("z, up (m)")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(f"{strike} strike at touchdown", fontsize=10)
    return fig


def indicator_figure(results: dict[str, ImpactResult]) -> Figure:
    """Bars of T_c, impulses, mu_c and dv of the trunk for each labelled result."""
    names = ["T_c (J)", "normal impulse (N s)", "tangential impulse (N s)", "mu_c (-)",
             "dv trunk x (m/s)", "dv trunk z (m/s)"]

    def values(r):
        dv = r.dv_trunk or (float("nan"), float("nan"))
        mu = r.mu_c if r.mu_c is not None else float("nan")  # no bar where undefined
        return [r.T_c, r.impulse_total[1], r.impulse_total[0], mu, dv[0], dv[1]]

    fig, axes = _subplots(1, len(names), figsize=(12, 3.2))
    colors = ["0.55", "tab:blue", "tab:orange", "tab:green"]
    for k, (ax, name) in enumerate(zip(axes, names)):
        for j, (label, r) in enumerate(results.items()):
            ax.bar(j, values(r)[k], color=colors[j % len(colors)], label=label)
        ax.set_title(name, fontsize=9)
        ax.set_xticks([])
        ax.axhline(0, color="0.3", lw=0.8)
    # one legend below the panels: inside one it would cover a bar
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=len(results),
               fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    return fig


def new_figure(figsize, dpi: float = 100) -> Figure:
    """A new Matplotlib Figure, outside pyplot (imported here, on the first figure drawn)."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, dpi=dpi)


def _subplots(*args, figsize=(6.4, 4.8), **kwargs):
    """(figure, axes) of a new Figure, outside pyplot."""
    fig = new_figure(figsize, 120)
    return fig, fig.subplots(*args, **kwargs)


def _rings(ax, points, ms: float, label: str | None = None):
    """Hollow markers seen on any colour map and on the white of masked cells: a black ring
    over a wider white one."""
    x, y = np.array(points, dtype=float).reshape(-1, 2).T
    ax.plot(x, y, "o", mfc="none", mec="white", mew=2.6, ms=ms + 1)
    ax.plot(x, y, "o", mfc="none", mec="black", mew=1.0, ms=ms, label=label)


def landing_figures(landing, model, slope: float, strike: str) -> dict[str, Figure]:
    """{"landing_sequence": stick figures through the landing, "energy": `energy_figure`}."""
    fig, ax = _subplots(figsize=(8, 5))
    ground(ax, slope, span=(-0.8, 0.8))
    frames = np.unique(np.searchsorted(landing.t, np.linspace(0, landing.t[-1], 8)).clip(0, len(landing.t) - 1))
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    for j, k in enumerate(frames):
        q = landing.q[k]
        pts = {p.name: q[model.cols(p.name)] for p in model.points}
        color = cmap(j / max(1, len(frames) - 1))
        chain = [pts[n] for n in ("hip", "knee", "ankle") if n in pts]
        ax.plot(*np.array(chain).T, "-o", color=color, ms=3, lw=1.8,
                label=f"{landing.t[k] * 1e3:.1f} ms")
        ax.fill(*np.array([pts["ankle"], pts["heel"], pts["forefoot"]]).T, color=color, alpha=0.3)
    ax.set_aspect("equal")
    ax.set_xlabel("x, forward (m)")
    ax.set_ylabel("z, up (m)")
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(f"landing after a {strike} strike", fontsize=10)
    sequence = fig

    return {"landing_sequence": sequence, "energy": energy_figure(landing)}


def invalid_phases(landing) -> list[tuple[float, str]]:
    """(time ms, why) where a landing breaks its own assumptions: no-slip needing more
    friction than the ground has, a contact the ground would have pulled (released there)."""
    return [(s * 1e3, "no-slip needs more friction than the ground has") for s in landing.slip_at] \
        + [(r * 1e3, "the ground would pull: contact released") for r, _, _ in landing.releases]


def energy_figure(landing) -> Figure:
    """Each energy's change since touchdown (J) against time (ms): kinetic, gravitational
    potential, joint springs, taken by the joints and friction, absorbed at the impacts, and
    their sum (the balance, flat but for integration drift); impacts as dashed lines, invalid
    stretches shaded."""
    fig, ax = _subplots(figsize=(8, 4.5))
    t = landing.t * 1e3
    for values, label, color in (
            (landing.T - landing.T[0], "kinetic T", "tab:blue"),
            (landing.V, "gravitational potential V", "tab:green"),
            (landing.spring, "joint springs", "tab:purple"),
            (landing.dissipated, "taken by joints and friction", "tab:brown"),
            (landing.absorbed, "absorbed at impacts (sum of T_c)", "tab:red"),
            (landing.energy - landing.energy[0], "total (balance)", "black")):
        ax.plot(t, values, color=color, lw=2.2 if color == "black" else 1.5, label=label,
                ls="--" if color == "black" else "-")
    for e in landing.impacts:
        ax.axvline(e.time * 1e3, color="tab:red", lw=0.8, ls=":")
    sliding = landing.slide[:-1] != 0
    for k in np.flatnonzero(sliding):  # the Coulomb law's sliding: valid, shown
        ax.axvspan(t[k], t[k + 1], color="0.8", lw=0, label="foot sliding" if k == np.argmax(sliding) else None)
    width = 0.005 * (t[-1] - t[0] or 1.0)
    shown = set()
    for at, why in invalid_phases(landing):
        ax.axvspan(at - width / 2, at + width / 2, color="tab:orange", alpha=0.6, lw=0,
                   label=None if why in shown else f"invalid: {why}")
        shown.add(why)
    ax.set_xlabel("time after touchdown (ms)")
    ax.set_ylabel("change since touchdown (J)")
    impacts = ", ".join(f"{e.contact} {e.T_c:.2f} J" for e in landing.impacts[:4])
    ax.set_title(f"T_c {landing.T_c_total:.3f} J in all ({impacts}); energy balance error "
                 f"{landing.energy_error:.1e} J", fontsize=9)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)
    fig.tight_layout()
    return fig


def sweep_figure(rows: list[dict], params: list[str]) -> Figure:
    """One parameter: absorbed energy (first impact, all impacts) and peak normal force
    against it (`_sweep_lines`). Two: maps of T_c_total and of the first impact's T_c over the
    grid (`_sweep_maps`). Valid landings (studies.sweep.valid) filled, invalid ones hollow (a
    slip, a pulled contact, an unfinished landing), failed points (no landing: the error column)
    as red crosses."""
    from ..studies.sweep import valid

    failed = [r for r in rows if r["error"]]
    counts = (f"{sum(valid(r) for r in rows)} valid, {sum(not r['error'] and not valid(r) for r in rows)} "
              f"invalid, {len(failed)} failed of {len(rows)}")
    fig = _sweep_lines(rows, params[0], failed, valid) if len(params) == 1 else _sweep_maps(rows, params, failed, valid)
    more = f"; further parameters ({', '.join(params[2:])}) overlaid" if len(params) > 2 else ""
    fig.suptitle(counts + more, fontsize=9)
    fig.tight_layout()
    return fig


def _cell(r: dict, key: str) -> float:
    """A sweep row's number (nan where the cell is empty)."""
    return float(r[key]) if r[key] not in ("", None) else np.nan


def _sweep_lines(rows: list[dict], param: str, failed: list[dict], valid) -> Figure:
    """`sweep_figure` for one parameter: T_c (first impact, all impacts) and the peak normal
    force against it."""
    rows = sorted(rows, key=lambda r: float(r[param]))
    x = np.array([float(r[param]) for r in rows])
    ok = np.array([valid(r) for r in rows])
    bad = np.array([not valid(r) and not r["error"] for r in rows])
    fig, axes = _subplots(1, 2, figsize=(11, 4))
    panels = ((axes[0], (("T_c_first", "first impact", "tab:blue"), ("T_c_total", "all impacts", "tab:red")),
               "absorbed energy T_c (J)"),
              (axes[1], (("f_n_max_N", "peak normal force", "tab:green"),), "peak normal contact force (N)"))
    for ax, series, ylabel in panels:
        for key, label, color in series:
            y = np.array([_cell(r, key) for r in rows])
            ax.plot(x, y, "-", color=color, lw=1, alpha=0.5)
            ax.plot(x[ok], y[ok], "o", ms=4, color=color, label=f"{label}, valid")
            if bad.any():
                ax.plot(x[bad], y[bad], "o", ms=5, mfc="none", color=color, label=f"{label}, invalid")
        if failed:
            ax.plot([float(r[param]) for r in failed], np.zeros(len(failed)), "x", color="red",
                    ms=6, label="failed (no landing)")
        ax.set_xlabel(_axis_label(param))
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=7)
    return fig


def _sweep_maps(rows: list[dict], params: list[str], failed: list[dict], valid) -> Figure:
    """`sweep_figure` for two parameters (the first two of `params`): maps of T_c_total and of
    the first impact's T_c, invalid points ringed, failed ones crossed."""
    px, py = params[:2]
    xs = sorted({float(r[px]) for r in rows})
    ys = sorted({float(r[py]) for r in rows})
    fig, axes = _subplots(1, 2, figsize=(12, 4.8))
    for ax, key, title in ((axes[0], "T_c_total", "T_c over the landing (J)"),
                           (axes[1], "T_c_first", "T_c at the first impact (J)")):
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in rows:
            grid[ys.index(float(r[py])), xs.index(float(r[px]))] = _cell(r, key)
        mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(grid), shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=title)
        invalid = [(float(r[px]), float(r[py])) for r in rows if not r["error"] and not valid(r)]
        if invalid:
            _rings(ax, invalid, 5, "invalid")
        if failed:
            ax.plot([float(r[px]) for r in failed], [float(r[py]) for r in failed], "x",
                    color="red", ms=5, label="failed (no landing)")
        ax.set_xlabel(_axis_label(px))
        ax.set_ylabel(_axis_label(py))
        if invalid or failed:
            ax.legend(fontsize=7, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False)
    return fig


def _axis_label(param: str) -> str:
    """'ankle_deg' -> 'ankle (deg)', 'hip_vx' -> 'hip_vx (m/s)'."""
    if param.endswith("_deg"):
        return f"{param[:-4]} (deg)"
    return {"hip_vx": "hip_vx (m/s)", "hip_vz": "hip_vz (m/s)", "speed_mps": "running speed (m/s)",
            "friction": "friction coefficient"}.get(param, param)


def comparison_figure(c, rep: dict) -> Figure:
    """Per side, like against like: the mean touchdown of the side's impact point and its
    optimum overlaid, the joint differences with the step-to-step sd, and T_c per step of that
    impact point (each with its band over the measurement's variants) beside the optimum's;
    `rep` the comparison's JSON report (Comparison.to_dict). A side without a valid optimum
    shows its measurement alone and, where the joint differences would be, why there is none;
    a side's headline is wrapped to its panel, never cut."""
    sides = [s for s in ("R", "L") if s in c.sides]
    fig, axes = _subplots(len(sides), 3, figsize=(14, 4.4 * len(sides)), squeeze=False,
                          gridspec_kw={"width_ratios": [1.1, 1, 1]})
    for row, side in zip(axes, sides):
        o, name = c.sides[side], "right" if side == "R" else "left"
        optimum = o.optimum if o.optimum is not None and o.optimum.success else None
        ax = row[0]
        ground(ax, 0.0)
        stick_figure(ax, c.body, o.reference, o.point, 0.0, "0.5", f"measured (mean {o.point} touchdown)")
        if optimum is not None:
            stick_figure(ax, c.body, optimum.state, o.point, 0.0, "tab:blue", "optimum, same gait")
        ax.set_aspect("equal")
        ax.set_xlabel("x, forward from the strike point (m)")
        ax.set_ylabel("z, up (m)")
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title(_wrapped(f"{name}: {_side_title(rep['optimum'][side], optimum is not None)}", TITLE_CHARS),
                     fontsize=8)
        _joint_panel(row[1], name, rep, side, None if optimum is not None else _no_optimum_reason(o))
        ax = row[2]
        ks = o.steps
        t = [c.steps.touchdowns[k].time for k in ks]
        band = np.array([c.T_c_band[k] for k in ks])
        values = np.array([c.step_T_c(k) for k in ks])
        ax.errorbar(t, values, yerr=[values - band[:, 0], band[:, 1] - values], fmt="o", ms=3,
                    color="0.4", ecolor="0.7", label=f"measured {o.point} steps (band: filter, frame)")
        if optimum is not None:
            ax.axhline(optimum.impact.T_c, color="tab:blue", ls="--", label=f"optimum ({o.point})")
        ax.set_xlabel("time (s)")
        ax.set_ylabel(f"absorbed energy T_c (J, {c.law})")
        ax.legend(fontsize=7)
        ax.set_title(f"{name}: T_c per {o.point} step ({c.steps.cadence_spm:.0f} steps/min)", fontsize=10)
    fig.tight_layout()
    return fig


TITLE_CHARS = 62  # characters of a line of a compare panel's 8-point title (14-inch figure, 3 panels)


def _wrapped(text: str, width: int, lines: int = 5) -> str:
    """`text` in lines of at most `width` characters (at most `lines`; beyond them " ..."):
    a title or a note that fits its panel."""
    return textwrap.fill(text, width, max_lines=lines, placeholder=" ...")


def _side_title(side: dict, solved: bool) -> str:
    """A compare side's headline (`side`: its JSON, studies.compare.side_dict); without a valid
    optimum what the panel shows, and whether the measured impact holds its law."""
    if solved:
        return side["headline"]
    ref = side["reference"]
    invalid = "" if ref["valid"] else f"; the measured impact is INVALID under {side['law']} ({'; '.join(ref['warnings'])})"
    return "measured only, no valid optimum" + invalid


def _no_optimum_reason(o) -> str:
    """Why a compare side (studies.compare.SideOptimum) has no valid optimum: none solved
    (`why_not`), or the solve's verdict (IPOPT's status, or the check that rejected it)."""
    if o.optimum is None:
        return o.why_not
    return o.optimum.verdict.removeprefix("NO OPTIMUM").strip(" ()")


def _joint_panel(ax, name: str, rep: dict, side: str, missing: str | None) -> None:
    """The optimum's joint angles minus the measured ones (deg) with the measured step-to-step
    sd; `missing`: why there is no valid optimum, written in the panel instead."""
    from ..studies.compare import JOINTS

    if missing is not None:
        ax.set_axis_off()
        ax.text(0.5, 0.5, _wrapped(f"no valid optimum: {missing}", 48, 10), transform=ax.transAxes,
                ha="center", va="center", fontsize=9, color="0.25")
        ax.set_title(f"{name}: no optimum to compare joint by joint", fontsize=10)
        return
    sd = [rep["summary"][side]["angles_deg_sd"][k] for k in JOINTS]
    ax.bar(JOINTS, [rep["optimum"][side]["difference_deg"][k] for k in JOINTS],
           color="tab:blue", label="optimum - measured")
    ax.errorbar(JOINTS, np.zeros(4), yerr=sd, fmt="none", ecolor="0.3", capsize=4,
                label="measured step-to-step sd")
    ax.legend(fontsize=7)
    ax.axhline(0, color="0.3", lw=0.8)
    ax.set_ylabel("optimum - measured joint angle (deg)")
    ax.set_title(f"{name}: how far the optimum is, joint by joint", fontsize=10)


PARETO_ERROR = {"impact": "max relative error of T_c (-)",
                "landing": "max relative error of landing T_c (-)",
                "optimisation": "posture error of the optimum (deg)"}
# where a point's name may go: offsets (points) right of it, tried in turn
LABEL_SPOTS = ((4, 3), (4, -9), (4, 13), (4, -19), (-4, 3), (-4, -9))
FONT_PT = 6  # the names' font size; a character about 0.6 of it wide


def stride_cadence_figure(s: dict) -> Figure:
    """compare's stride section (compare_stride.StrideAnswer.to_dict): mechanical power and
    impact loss (W) against the imposed cadence, one line per variant of the band (the nominal
    bold, through its free optimum, or its sticking strides' own where that is given (`own_free_*`;
    through neither where that is null: it did not converge): the envelope), the runner's own cadence marked (dashed) and, on the power panel, each variant's free
    optimum (star) where it has one; a panel's title names the stars only when it draws them."""
    fig, axes = _subplots(1, 2, figsize=(12, 4.4))
    for key, ax, title in (("mechanical_power_W", axes[0], "mechanical power W+ / T"),
                           ("impact_loss_W", axes[1], "impact loss (T_c per step x step rate)")):
        stars = 0
        for k, c in enumerate(s["curves"]):
            if not c["converged"]:
                continue
            free = (c.get("free_cadence_spm"), c.get(f"free_{key}"))
            own = (c.get("own_free_cadence_spm", free[0]), c.get(f"own_free_{key}", free[1]))
            on = k == 0 and None not in own  # the nominal curve passes through its own free optimum
            x, y = c["cadence_spm"] + [own[0]] * on, c[key] + [own[1]] * on
            order = np.argsort(x)
            line, = ax.plot(np.asarray(x)[order], np.asarray(y)[order], "o-", lw=2.2 if k == 0 else 0.9, ms=3,
                            label=c["name"])
            if key == "mechanical_power_W" and None not in free:
                ax.plot(*free, "*", ms=10, color=line.get_color())
                stars += 1
        ax.axvline(s["measured_cadence_spm"], color="0.3", ls="--", lw=1,
                   label=f"the runner, {s['measured_cadence_spm']:.0f} steps/min")
        ax.set_xlabel("imposed cadence (steps/min)")
        ax.set_ylabel(f"{title} (W)")
        ax.set_title(title + ("; star: the free optimum" if stars else ""), fontsize=9)  # only stars drawn
    axes[0].legend(fontsize=7)
    fig.suptitle(f"the stride of this body at {s['speed_mps']:.2f} m/s, {s['measured_strike']} strike",
                 fontsize=10)
    return fig


def _name_points(ax, named) -> None:
    """Write each (x, y, name) beside its point at the first spot of LABEL_SPOTS whose box
    overlaps no name written before (boxes estimated in points from the axes' transform)."""
    ax.get_xlim(), ax.get_ylim()  # the autoscaled limits the transform needs
    to_pt = 72 / ax.figure.dpi
    boxes: list[tuple[float, float, float, float]] = []
    for x, y, name in named:
        px, py = ax.transData.transform((x, y)) * to_pt
        width, height = 0.6 * FONT_PT * len(name), FONT_PT + 2
        for dx, dy in LABEL_SPOTS:
            x0 = px + dx if dx > 0 else px + dx - width
            box = (x0, py + dy, x0 + width, py + dy + height)
            if not any(box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3] for b in boxes):
                break
        boxes.append(box)
        ax.annotate(name, (x, y), fontsize=FONT_PT, xytext=(dx, dy), textcoords="offset points",
                    ha="left" if dx > 0 else "right",
                    bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none", "alpha": 0.7})


def pareto_figure(rows) -> Figure:
    """Time against error of every bench row, one panel per kind of work. The model ladder
    (errors against the full body) and the numerical options (errors against the paper's leg
    at its finest setting) are drawn apart, each with its Pareto front; every point named
    (`_name_points`: names that do not overlap)."""
    works = [w for w in ("impact", "landing", "optimisation") if any(r.work == w for r in rows)]
    fig, axes = _subplots(1, len(works), figsize=(5.5 * len(works), 4.8))
    groups = (("model ladder", "tab:orange", lambda r: r.option.startswith("ladder")),
              ("numerical options, paper's leg", "tab:blue", lambda r: not r.option.startswith("ladder")))
    for ax, work in zip(np.atleast_1d(axes), works):
        named = []
        for name, color, member in groups:
            pts = sorted((r.time_s, max(r.error, 1e-16), r.level if name == "model ladder"
                          else r.option) for r in rows
                         if r.work == work and member(r) and np.isfinite(r.error))
            if not pts:
                continue
            front, best = [], np.inf
            for t, e, label in pts:
                if e < best:
                    front.append((t, e, label))
                    best = e
            ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=18, color=color, label=name)
            ax.plot([p[0] for p in front], [p[1] for p in front], "--", color=color, lw=1)
            named += pts
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.margins(x=0.15, y=0.15)
        _name_points(ax, named)
        ax.set_xlabel("time per unit of work (s)")
        ax.set_ylabel(PARETO_ERROR[work])
        ax.set_title(f"{work} (error 1e-16 stands for exact)", fontsize=10)
    handles = {h.get_label(): h for ax in np.atleast_1d(axes) for h in ax.collections}
    fig.legend(handles.values(), handles.keys(), loc="lower center", ncol=2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


def optimum_map_figure(rows: list[dict], params: list[str], variables) -> Figure:
    """The optimum against the parameters: T_c and each optimal angle. One parameter: curves;
    two: maps. Interior optima filled, optima held by a limit hollow, points without an
    optimum as red crosses."""
    def value(r, key):
        return float(r[key]) if r.get(key) not in ("", None) and r["success"] == "True" else np.nan

    keys = [("T_c", "T_c at the optimum (J)")] + [(f"{v}_deg", f"optimal {v} (deg)") for v in variables]
    failed = [r for r in rows if r["success"] != "True"]
    held = [r for r in rows if r["success"] == "True" and r["verdict"] != "interior optimum"]
    fig, axes = _subplots(1, len(keys), figsize=(3.6 * len(keys), 3.6 if len(params) == 1 else 3.4))
    axes = np.atleast_1d(axes)
    if len(params) == 1:
        (param,) = params
        rows = sorted(rows, key=lambda r: float(r[param]))
        x = np.array([float(r[param]) for r in rows])
        interior = np.array([r["verdict"] == "interior optimum" for r in rows])
        for ax, (key, label) in zip(axes, keys):
            y = np.array([value(r, key) for r in rows])
            ax.plot(x, y, "-", color="tab:blue", lw=1)
            ax.plot(x[interior], y[interior], "o", ms=3, color="tab:blue", label="interior")
            ax.plot(x[~interior], y[~interior], "o", ms=4, mfc="none", color="tab:orange",
                    label="held by a limit")
            ax.set_xlabel(_axis_label(param))
            ax.set_ylabel(label)
        axes[0].legend(fontsize=7)
    else:
        px, py = params[:2]
        xs = sorted({float(r[px]) for r in rows})
        ys = sorted({float(r[py]) for r in rows})
        for ax, (key, label) in zip(axes, keys):
            grid = np.full((len(ys), len(xs)), np.nan)
            for r in rows:
                grid[ys.index(float(r[py])), xs.index(float(r[px]))] = value(r, key)
            mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(grid), shading="nearest", cmap="viridis")
            fig.colorbar(mesh, ax=ax, label=label)
            if held:
                _rings(ax, [(float(r[px]), float(r[py])) for r in held], 4)
            if failed:
                ax.plot([float(r[px]) for r in failed], [float(r[py]) for r in failed], "x",
                        color="red", ms=4)
            ax.set_xlabel(_axis_label(px))
            ax.set_ylabel(_axis_label(py))
    fig.suptitle(f"{len(rows) - len(failed)} optima ({len(held)} held by a limit: hollow), "
                 f"{len(failed)} without an optimum (red x)", fontsize=9)
    fig.tight_layout()
    return fig
