"""Figures and table of a half stride: stick figures, joint angles, moments and ground force
over the gait cycle (with RBDS001's measured mean beside them when given), the energy budget.
Each function returns a Matplotlib Figure (matplotlib.figure.Figure, not pyplot)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..mechanics.joint_space import JointSpace
from ..optim.stride.muscle_readings import RESERVE_WINDOW_S
from ..optim.stride.problem import FORCE_RATE_WEIGHTS
from ..studies.stride import CYCLE_JOINTS, StrideStudy, predicted_cycle
from .figures import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

BONES = (("shoulder", "hip"), ("hip", "knee"), ("knee", "ankle"), ("ankle", "heel"),
         ("heel", "forefoot"), ("forefoot", "ankle"), ("hip", "swing_knee"),
         ("swing_knee", "swing_ankle"), ("swing_ankle", "swing_heel"),
         ("swing_heel", "swing_forefoot"), ("swing_forefoot", "swing_ankle"))


def stick_figures(stride, js: JointSpace, every: int = 3) -> Figure:
    """The body about every `every`-th node's time over the half stride (right leg dark, left
    light): the nodes nearest to len(t) / every equally spaced times, so that a mesh graded
    toward the phases' ends (StrideSettings.grading) does not bunch the sticks there."""
    fig = new_figure((10, 3.6))
    ax = fig.add_subplot()
    names = js.landmark_names
    t = np.asarray(stride.t, float)
    times = np.linspace(t[0], t[-1], len(t))[::every]
    for k in np.unique([int(np.argmin(np.abs(t - time))) for time in times]):
        p = np.asarray(js.landmarks(stride.theta[k]), float)
        for a, b in BONES:
            i, j = names.index(a), names.index(b)
            ax.plot(p[0, [i, j]], p[1, [i, j]], color="0.65" if a.startswith("swing") or
                    b.startswith("swing") else "C0", lw=1.2)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(f"{stride.strike} strike, {stride.speed_mps:g} m/s: {stride.cadence_spm:.0f} "
                 f"steps/min, step {stride.step_length_m:.2f} m")
    return fig


MEASURED_MASS_KG = 62.0  # RBDS001, whose mean cycle studies.stride.measured_cycle reads
MEASURED_SPEEDS = (2.5, 3.5, 4.5)  # m/s: its trials


def measured_applies(stride) -> bool:
    """Whether RBDS001's measured cycle belongs beside this stride: the runner's body mass and
    one of the runner's speeds (another body at 3.5 m/s is not RBDS001)."""
    return abs(stride.mass_kg - MEASURED_MASS_KG) < 0.5 and round(stride.speed_mps, 2) in MEASURED_SPEEDS


def cycle_figure(stride, measured: dict | None, quantity: str) -> Figure:
    """Right-leg joint angles (deg), net joint moments (N m/kg: the actuators' and the
    tendons', as the measured net moments) or their powers (W/kg) over the gait cycle, or the ground force (N/kg:
    vertical and fore-aft, "vertical"); the measured mean beside them (dashed) when given (the
    measured force: vertical only)."""
    predicted = predicted_cycle(stride)
    fig = new_figure((10, 3.4))
    if quantity == "vertical":
        predicted = {**predicted, "horizontal": np.r_[stride.force[:, :, 0].sum(axis=1),  # as predicted_cycle
                                                      np.zeros(len(stride.t))] / stride.mass_kg}
    panels = CYCLE_JOINTS if quantity not in ("vertical",) else ("vertical", "horizontal")
    unit = {"angles": "deg", "moments": "N m/kg", "powers": "W/kg", "vertical": "N/kg"}[quantity]
    net = {"moments": "net moment", "powers": "power of the net moment"}.get(quantity)
    label = "predicted" if net is None else f"predicted, {net} (" + (
        "muscles + reserves)" if stride.muscles is not None else "active + tendons)")
    for k, name in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), k + 1)
        order = np.argsort(predicted["percent"], kind="stable")
        values = predicted[name] if quantity == "vertical" else predicted[quantity][name]
        ax.plot(predicted["percent"][order], values[order], "C0", label=label)
        if measured is not None and name != "horizontal":
            data = measured[quantity] if quantity == "vertical" else measured[quantity][name]
            ax.plot(measured["percent"], data, "k--",
                    label="RBDS001 measured" + (f", {net}" if net else ""))
        ax.set_xlabel("gait cycle (%)")
        ax.set_title(f"{name if name != 'horizontal' else 'fore-aft (forward +)'} ({unit})")
    handles, labels = fig.axes[0].get_legend_handles_labels()  # below the panels: no curve hidden
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


SINKS = {"negative_work_J": "negative work", "impacts_J": "impacts (T_c)",
         "spring_J": "tendons let go at toe-off", "friction_J": "friction", "passive_J": "passive joint moments",
         "climb_J": "climb"}  # where the positive work goes: every term the budget balances


def budget_figure(stride) -> Figure:
    """The energy budget of the half stride (J): positive work against every term it balances
    (SINKS; a budget term not named there is drawn under its own key), the balance the bars'
    own difference."""
    b = stride.budget
    fig = new_figure((7, 3.6))
    ax = fig.add_subplot()
    sinks = [(SINKS.get(k, k), v) for k, v in b.items()
             if k not in ("positive_work_J", "balance_J", "metabolic_J")]
    bottom = 0.0
    for k, (name, value) in enumerate(sinks):
        ax.bar(1, value, bottom=bottom, color=f"C{k + 1}", label=f"{name} {value:.1f} J")
        bottom += value
    ax.bar(0, b["positive_work_J"], color="C0", label=f"positive work {b['positive_work_J']:.1f} J")
    ax.set_xticks([0, 1], ["in", "out"])
    ax.set_ylabel("J per half stride")
    ax.set_title(f"in - out {b['positive_work_J'] - bottom:+.2f} J, CoT {stride.cost_of_transport:.3f}, "
                 f"{stride.mechanical_power_W:.0f} W")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.tight_layout()
    return fig


def muscle_figure(stride) -> Figure:
    """The right leg's muscle activations over the gait cycle (its left leg gives the second
    half, by symmetry), each muscle's tendon energy stored per step in its title; the reserves'
    largest moment and the metabolic energy in the figure's title."""
    m = stride.muscles
    percent = np.r_[stride.t / stride.half_period_s * 50.0, 50.0 + stride.t / stride.half_period_s * 50.0]
    order = np.argsort(percent, kind="stable")
    n = len(m["names"]) // 2
    fig = new_figure((11, 4.6))
    for k, name in enumerate(m["names"][:n]):
        ax = fig.add_subplot(2, (n + 1) // 2, k + 1)
        cycle = np.r_[m["activation"][:, k], m["activation"][:, n + k]]
        ax.plot(percent[order], cycle[order], "C3")
        ax.set_ylim(0.0, 1.02)
        ax.set_title(f"{name[:-2].replace('_', ' ')}: {m['stored_J'][name] + m['stored_J'][m['names'][n + k]]:.1f} J",
                     fontsize=9)
        if k >= n - (n + 1) // 2:
            ax.set_xlabel("gait cycle (%)")
    fig.suptitle(f"activation (0-1) and tendon energy stored per stride; metabolic {m['metabolic_J']:.0f} J per step, "
                 f"reserves up to {m['reserve_nm_per_kg']:.2f} N m/kg over {RESERVE_WINDOW_S * 1e3:g} ms", fontsize=10)
    fig.tight_layout()
    return fig


def stride_figures(stride, js: JointSpace, measured: dict | None) -> dict[str, Figure]:
    """The stride's figures; `measured` (RBDS001's mean cycle) drawn only where it applies
    (measured_applies); the muscles' where the stride has them."""
    measured = measured if measured is not None and measured_applies(stride) else None
    out = {"stick": stick_figures(stride, js), "angles": cycle_figure(stride, measured, "angles"),
           "moments": cycle_figure(stride, measured, "moments"), "powers": cycle_figure(stride, measured, "powers"),
           "grf": cycle_figure(stride, measured, "vertical"), "budget": budget_figure(stride)}
    if stride.muscles is not None:
        out["muscles"] = muscle_figure(stride)
    return out


def stride_table(study: StrideStudy) -> str:
    """One line per strike solved, the best first (optim.stride.rank); under it, what makes a
    stride invalid (IPOPT's status, an impact that breaks the contact law, a failed check), and
    how sure it is of its mesh (each stride's mesh check, or the study's note)."""
    lines = [f"{study.scene}: solved at {study.best.speed_mps:g} m/s",
             f"{'strike':9s} {'valid':>5s} {'cadence':>8s} {'step m':>7s} {'stance s':>9s} "
             f"{'flight s':>9s} {'duty':>5s} {'GRF BW':>7s} {'T_c J':>7s} {'CoT':>6s} {'W':>6s} "
             f"{'swing cm':>8s} {'knee max':>8s} {'balance J':>10s} {'iter':>5s} {'s':>6s}"]
    for s in study.strides:
        lines.append(f"{s.strike:9s} {'yes' if s.valid else 'NO':>5s} {s.cadence_spm:8.1f} "
                     f"{s.step_length_m:7.3f} {s.stance_s:9.3f} {s.flight_s:9.3f} {s.duty_factor:5.2f} "
                     f"{s.peak_vertical_grf_bw:7.2f} {s.budget['impacts_J']:7.2f} "
                     f"{s.cost_of_transport:6.3f} {s.mechanical_power_W:6.0f} {s.swing_clearance_m * 100:8.1f} "
                     f"{s.stance_knee_deg:8.0f} {s.budget['balance_J']:10.3f} {s.iterations:5d} {s.solve_s:6.1f}")
    lines += [search_text(s) for s in study.strides if s.search is not None]
    if not study.best.valid:
        lines.append("no valid stride: " + ("none of the strikes gives one; the first above ranks best "
                                            "(converged, then the least objective)" if len(study.strides) > 1
                                            else "read its numbers as the model's, not a runner's"))
    for s in study.strides:
        if s.muscles is not None:
            m = s.muscles
            lines.append(f"muscles {s.strike}: metabolic {m['metabolic_J']:.0f} J per step "
                         f"({m['metabolic_J'] / (s.mass_kg * s.step_length_m):.2f} J/kg/m), tendons store "
                         f"{m['tendon_stored_J']:.1f} J (soleus and gastrocnemius {m['achilles_stored_J']:.1f} J) "
                         f"and return {m['tendon_returned_J']:.1f} J, reserves up to {m['reserve_nm_per_kg']:.3f} N m/kg "
                         f"over {RESERVE_WINDOW_S * 1e3:g} ms ({m['reserve_peak_nm_per_kg']:.3f} at a node)"
                         + rate_text(s))
    for s in study.strides:
        if not s.valid:
            why = s.failed_checks if s.success else [f"IPOPT: {s.status}", *s.failed_checks]
            lines.append(f"INVALID {s.strike}: {'; '.join(why)}")
    lines += [f"NOTE strikes: {study.tie}"] if study.tie else []
    lines += [f"NOTE best: {study.unlike}"] if study.unlike else []
    lines += [f"NOTE {s.strike}: {remark}" for s in study.strides for remark in s.remarks]
    lines += [f"NOTE search: {study.search}"] if study.search else []
    checked = [f"NOTE mesh {s.strike}: {s.mesh_check.text()}" for s in study.strides if s.mesh_check is not None]
    lines += checked or ([f"NOTE mesh: {study.mesh}; --mesh-check measures this stride"] if study.mesh else [])
    lines += [f"NOTE transcription: {study.transcription}"] if study.transcription else []
    return "\n".join(lines)


def rate_text(stride) -> str:
    """The muscles' line's word on its force-rate term where it is not the default (problem.
    FORCE_RATE_WEIGHTS: the power 2 at its calibrated weight), empty otherwise."""
    rate = stride.muscles["force_rate_term"]
    if stride.objective != "metabolic" or (rate["power"], rate["weight"]) == (2, FORCE_RATE_WEIGHTS[2]):
        return ""
    term = "|F'|" if rate["power"] == 1 else "F'^2"
    return f"; its force-rate term {term} at weight {rate['weight']:g}"


def search_text(stride) -> str:
    """What the global search (optim.stride.search) spent and met, in one line: each distinct
    local optimum (cadence, objective, its difference from the answer's, invalid ones named),
    their spread."""
    g = stride.search
    met = ", ".join(f"{o['cadence_spm']:.0f} steps/min {o['objective']:.4g}"
                    + (" (the answer)" if o["answer"] else
                       f" ({(o['objective'] / stride.objective_value - 1) * 100:+.1f} %)")
                    + ("" if o["valid"] else " invalid") for o in g["optima"])
    what = "at the imposed cadence" if g["procedure"] == "imposed cadence" else "with the cadence free"
    return (f"search {stride.strike}: global, spend {g['spend']}: {g['solves']} solves, {g['iterations']} "
            f"IPOPT iterations, {g['seconds']:.0f} s; {len(g['optima'])} distinct "
            f"{'optimum' if len(g['optima']) == 1 else 'optima'} {what}: {met or 'none'}"
            + (f" (spread {g['spread_pct']:.1f} %)" if g["spread_pct"] is not None else ""))
