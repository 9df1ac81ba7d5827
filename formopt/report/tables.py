"""Text reports: the terminal tables of every command (plain strings, no printing).

Each function takes results (and the scene that produced them) and returns the table a
person reads; the JSON reports beside them hold the same numbers for other tools.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..io.scene import Scene, touchdown_table
from ..measure.plate import COP_WINDOW_S
from ..mechanics.contact import LAWS
from ..mechanics.impact import ImpactResult
from ..optim.objective import UNITS
from ..optim.solution import explain
from ..studies.compare import JOINTS, Comparison


def _mass_lines(im: dict | None, law: str) -> list[str]:
    """A side's rigid effective mass and normal impulse beside the plate's two-mass fit."""
    if not im:
        return []
    out = [f"  {'':22s} the rigid impact (medians): m_eff {im['m_eff_kg']:.2f} kg ({im['m_eff_pct_body_mass']:.1f} % of "
           f"body mass; running's 5-8 %), approach {-im['v_n_mps']:.2f} m/s, p_n = m_eff v_n {im['p_n_Ns']:.2f} N s "
           f"({law}: {im['p_n_law_Ns']:.2f})"]
    pl = im.get("plate")
    if pl:
        pct = pl["J1_per_v_n_pct_body_mass"]
        out.append(f"  {'':22s} the plate's two-mass fit (touchdown to 50 N; a half sine peaking at t1 within "
                   f"5-60 ms + a half sine over the contact): J1 {pl['J1_Ns']:.1f} N s, J1/v_n "
                   + (f"{pct:.0f} % of body mass" if pct is not None else "-")
                   + f", t1 {pl['t1_ms']:.0f} ms (on its bound in {pl['t1_on_bound']}/{pl['steps']}); R^2 "
                   f"{pl['r2_median']:.3f} (least {pl['r2_least']:.3f}; the body's half sine alone "
                   f"{pl['r2_half_sine_alone']:.3f})")
        share = 100 * im["p_n_Ns"] / pl["J1_Ns"] if pl["J1_Ns"] > 0 else float("inf")
        if 2 * pl["t1_on_bound"] > pl["steps"]:
            out.append(f"  {'':22s} read: the plate shows no impact pulse the fit separates (its first pulse runs to "
                       f"the bound and takes up the stance's loading); the rigid p_n is {share:.0f} % of that J1: the "
                       "plate and the map agree the impact is small, and the loading the fit sees is what the rigid "
                       "map (an instant, free joints) does not model")
        else:
            out.append(f"  {'':22s} read: the rigid p_n is {share:.0f} % of the plate's J1, m_eff "
                       f"{im['m_eff_pct_body_mass']:.1f} % against J1/v_n "
                       + (f"{pl['J1_per_v_n_pct_body_mass']:.1f} %" if pl["J1_per_v_n_pct_body_mass"] is not None else "-")
                       + " of body mass")
    return out


def impact_table(scene: Scene, r: ImpactResult) -> str:
    """The indicators of one strike as a terminal table."""
    lines = [f"{scene.name}  ({scene.path})",
             f"model {scene.kind}; body {scene.body.source}",
             f"{r.strike} strike on {math.degrees(r.slope):+.1f} deg ground, friction {r.friction:g}",
             ""]
    lines += [f"contact law: {r.law}" + (f" ({r.mode} at the end, slip {r.slip_velocity:+.3f} m/s)"
                                         if r.mode else ""),
              f"valid: {'yes' if r.valid else 'NO: ' + '; '.join(r.warnings)}", ""]
    lines += _indicator_lines(r)
    lines += [""] + contact_law_lines(r)
    lines += [f"warning: {w}" for w in r.warnings if r.valid] + [f"note: {n}" for n in scene.notes]
    return "\n".join(lines)


def contact_law_lines(r: ImpactResult) -> list[str]:
    """The same touchdown under each contact law, side by side (the scene's law marked *)."""
    laws = r.contact_laws
    lines = ["  the same touchdown under each contact law (* the scene's):",
             f"  {'':30s} " + " ".join(f"{(law + (' *' if law == r.law else '')):>14s}" for law in laws)]

    def row(name, value, fmt):
        cells = [fmt.format(value(v)) for v in laws.values()]
        return f"  {name:30s} " + " ".join(f"{c:>14s}" for c in cells)

    total = lambda v, k: sum(p[k] for p in v.impulse.values())  # noqa: E731
    lines += [row("absorbed T_c (J)", lambda v: v.T_c, "{:.4f}"),
              row("impulse t (N s)", lambda v: total(v, 0), "{:+.4f}"),
              row("impulse n (N s)", lambda v: total(v, 1), "{:+.4f}"),
              row("|t| / n", lambda v: abs(total(v, 0)) / total(v, 1) if total(v, 1) > 0 else float("nan"), "{:.3f}"),
              row("slip after (m/s)", lambda v: v.slip_velocity, "{:+.3f}"),
              row("mode", lambda v: v.mode or "-", "{}")]
    if r.dv_trunk is not None:
        lines.append(row("trunk dv x, z (m/s)", lambda v: v.dv_trunk,
                         "{0[0]:+.3f} {0[1]:+.3f}"))
    lines.append(row("valid", lambda v: "yes" if v.valid else "no", "{}"))
    if r.mu_c_posture is not None:
        lines.append(f"  posture-only critical friction (eq. 7) |W_tn / W_tt| = {r.mu_c_posture:.3f}")
    return lines


def _indicator_lines(r: ImpactResult, other: ImpactResult | None = None) -> list[str]:
    """Indicator rows; with `other`, a second column (reference, then this one)."""
    def row(name, symbol, value, unit, fmt="{:+10.4f}"):
        cells = fmt.format(value(other)) + " " if other else ""
        return f"  {name:30s} {symbol:5s} {cells}{fmt.format(value(r))} {unit}"

    lines = [row("kinetic energy before", "T", lambda z: z.T, "J", "{:10.3f}"),
             row("absorbed (CMSKE)", "T_c", lambda z: z.T_c, "J", "{:10.3f}"),
             row("kinetic energy after", "T_a", lambda z: z.T_a, "J", "{:10.3f}")]
    for point in r.impulse:
        if other is None or point in other.impulse:
            open_ = "" if all(r.impulse_determined[point]) else "   (split not determined)"
            lines.append(row(f"ground impulse t, {point}", "t", lambda z, p=point: z.impulse[p][0], "N s")
                         + open_)
            lines.append(row(f"ground impulse n, {point}", "n", lambda z, p=point: z.impulse[p][1], "N s"))
    if r.mu_c is not None and (other is None or other.mu_c is not None):
        lines.append(row("critical friction", "mu_c", lambda z: z.mu_c, "", "{:10.4f}")
                     + ("" if other else f"   (momentum check {r.mu_c_momentum:.4f})"))
    else:
        lines.append(f"  {'critical friction':30s} mu_c  undefined: the ground does not push")
    if r.dv_trunk is not None:
        lines.append(row("trunk velocity change x", "dv", lambda z: z.dv_trunk[0], "m/s"))
        lines.append(row("trunk velocity change z", "dv", lambda z: z.dv_trunk[1], "m/s"))
    lines.append(row("centre-of-mass change x", "dv", lambda z: z.dv_com[0], "m/s"))
    lines.append(row("centre-of-mass change z", "dv", lambda z: z.dv_com[1], "m/s"))
    lines.append(row("condition of Phi M^-1 Phi^T", "", lambda z: z.condition, "", "{:10.3g}"))
    return lines


def solve_table(scene: Scene, opt) -> str:
    """The optimum against the reference posture, what it is (interior, or held by named
    limits), the gait held, the objective's terms, the sensitivities."""
    ok = "converged" if opt.success else "NOT CONVERGED"
    problem = scene.problem
    assert problem is not None  # an optimum comes from a scene's [optimize] table
    lines = [f"{scene.name}  ({scene.path})",
             f"model {scene.kind}; body {scene.body.source}; {scene.strike} strike on "
             f"{math.degrees(scene.slope):+.1f} deg ground, friction {scene.friction:g}, "
             f"contact law {scene.contact}",
             f"objective {_objective_text(problem.objective)}: {opt.objective:.6g} "
             f"({ok}: {opt.status}): {opt.verdict}", ""]
    lines += gait_lines(problem, opt)
    ref, best = touchdown_table(scene.strike, scene.state), touchdown_table(scene.strike, opt.state)
    lines.append(f"  {'posture (deg)':36s} {'reference':>10s} {'optimum':>10s}")
    for k in ref["angles_deg"]:
        mark = "  *" if k in problem.variables else ""
        lines.append(f"  {k:36s} {ref['angles_deg'][k]:10.2f} {best['angles_deg'][k]:10.2f}{mark}")
    for k in ref["angular_velocity_dps"]:
        if "omega_" + k in problem.variables:
            lines.append(f"  {'omega ' + k + ' (deg/s)':36s} {ref['angular_velocity_dps'][k]:10.1f} "
                         f"{best['angular_velocity_dps'][k]:10.1f}  *")
    lines += ["  (* decision variable)", "", f"  {'indicators':36s} {'reference':>10s} {'optimum':>10s}"]
    lines += _indicator_lines(opt.impact, opt.reference)
    lines += ["", f"valid at the optimum: {'yes' if opt.impact.valid else 'no'}"]
    lines += [f"warning: {w}" for w in opt.impact.warnings]
    lines += [""] + optimum_lines(opt)
    converged = sum(st.converged for st in opt.starts)
    lines += ["", f"multi-start: {len(opt.starts)} starts (seed {opt.seed}), {converged} converged, "
                  f"{opt.local_optima} distinct optima; median solve {opt.solve_time * 1e3:.1f} ms, "
                  f"build {opt.build_time * 1e3:.0f} ms"]
    for st in opt.starts:
        if not st.converged:
            lines.append(f"  start {st.index}: {st.status} (objective {st.objective:.4g}), not used: "
                         f"{explain(st.status)}")
    lines += [f"note: {n}" for n in list(scene.notes) + list(opt.notes)]
    return "\n".join(lines)


def gait_lines(problem, opt) -> list[str]:
    """What the gait holds, when it is held: the hip's place, its velocity, the cadence."""
    if problem.gait is None:
        return []
    held = {c.name: c for c in opt.active if c.equality}
    x, z = (held[k].bound if k in held else float("nan") for k in ("hip_from_strike_x", "hip_from_strike_z"))
    lines = [f"gait held: hip {x:+.3f} m along and {z:.3f} m above the strike point, hip velocity "
             f"({opt.state[4]:+.2f}, {opt.state[5]:+.2f}) m/s, segment rates of the touchdown"]
    if problem.gait.foot_velocity is not None:
        lines.append(f"  strike point velocity along the ground {problem.gait.foot_velocity:+.2f} m/s")
    if problem.gait.cadence_spm:
        lines.append(f"  cadence {problem.gait.cadence_spm:g} steps/min")
    return lines + [""]


def optimum_lines(opt) -> list[str]:
    """What the optimum is and what it is worth: the objective's terms, what holds it (with
    multipliers), the headline, the local mode's marginal values, the sensitivities."""
    lines = []
    if opt.terms:
        lines.append("per step, reference -> optimum: " + ", ".join(
            f"{k} {opt.reference_terms[k]:.4g} -> {v:.4g} {UNITS[k]}" for k, v in opt.terms.items()))
    if opt.success:
        if opt.held_by:
            lines.append("HELD BY (multiplier = objective change per unit of the bound):")
            for c in opt.held_by:
                lines.append(f"  {c.name:22s} at {c.bound:+.4g}  multiplier {c.multiplier:+.4g}: {c.meaning}")
        else:
            lines.append("interior optimum: no bound or limit is active")
        fixed = [c for c in opt.active if c.equality]
        if fixed:
            lines.append("what the fixed gait costs (multiplier = objective change per unit):")
            for c in fixed:
                lines.append(f"  {c.name:22s} = {c.bound:+.4g}  multiplier {c.multiplier:+.4g}: {c.meaning}")
    if opt.success:
        lines += ["", headline(opt)]
    if opt.local:
        lines.append("  marginal value at the reference (objective per deg, the other angles held): "
                     + ", ".join(f"{k} {v:+.4g}" for k, v in opt.local.marginal.items()))
    if opt.sensitivity:
        s = opt.sensitivity
        lines += ["", f"sensitivity of the optimum: objective {s['d_objective_d_speed']:+.4g} per m/s "
                      f"of running speed, {s['d_objective_d_friction']:+.4g} per unit of friction"]
        for name, unit in (("speed", "m/s"), ("friction", "unit of friction")):
            if f"d_posture_d_{name}_deg" in s:
                moves = ", ".join(f"{k} {v:+.3g}" for k, v in s[f"d_posture_d_{name}_deg"].items())
                lines.append(f"  posture per {unit}: {moves} deg")
    return lines


def headline(opt) -> str:
    """The optimum's headline: the quantity it optimised (Optimum.quantity, unweighted) at the
    reference and the optimum, per step and in W at the gait's cadence; a weighted objective's
    drop is named as such, never a saving."""
    where = f"within {opt.local.radius_deg:g} deg of the reference" if opt.local else "against the reference"
    q, s = opt.quantity, opt.saving
    if q not in opt.terms or q not in opt.reference_terms:
        return f"{where}: the objective falls by {s:.4g} per step"
    unit = UNITS.get(q, "")
    text = (f"{where}: {q} per step {opt.reference_terms[q]:.4g} -> {opt.terms[q]:.4g} {unit}, "
            f"{abs(s):.4g} {unit} {'less' if s >= 0 else 'more'}")
    if opt.power is not None:
        text += f" ({abs(opt.power):.3g} W at {opt.cadence_spm:g} steps/min)"
    if len(opt.weights) > 1 or set(opt.weights.values()) - {1.0}:
        text += (f"; the objective {_objective_text(opt.weights)} falls by "
                 f"{opt.reference_objective - opt.objective:.4g}, a weighted sum, not an energy saved")
    return text


def _objective_text(terms: dict) -> str:
    return " + ".join(f"{w:g} {k}" if w != 1 else k for k, w in terms.items())


def comparison_table(c: Comparison, rep: dict) -> str:
    """A comparison as a terminal table; `rep` its JSON report (Comparison.to_dict)."""
    st = c.steps
    lines = [f"{rep['source']}: {len(st.touchdowns)} touchdowns ({st.method}), {len(st.valid)} with "
             f"sound markers; cadence {st.cadence_spm:.1f} steps/min; speed {st.speed:.2f} m/s "
             f"(belt {st.belt_speed:.2f})",
             f"lab axes found: {rep['axes']}", f"model: the paper's leg, {c.body.source}",
             "settings: " + ", ".join(f"{k} {v}" for k, v in c.settings.items() if k != "bounds_deg"), ""]
    lines.append(f"  {'':22s} {'steps':>5s} {'strike':>9s} {'trunk':>7s} {'hip':>7s} {'knee':>7s} "
                 f"{'ankle':>7s} {'FSA':>7s} {'T_c (J)':>12s}")
    for side, s in rep["summary"].items():
        a, sd = s["angles_deg_mean"], s["angles_deg_sd"]
        lines.append(f"  {'measured, ' + ('right' if side == 'R' else 'left'):22s} {s['steps']:5d} "
                     f"{s['strike']:>9s} " + " ".join(f"{a[k]:7.1f}" for k in JOINTS)
                     + f" {s['foot_strike_angle_deg_mean']:7.1f} {s['T_c_mean']:6.2f} ± {s['T_c_sd']:.2f}"
                     + f" ({s['T_c_point']} steps)"
                     + f"  valid {s['laws'][c.law]['valid']}/{s['steps']}"
                     + (" (NOT ONE VALID)" if not s['laws'][c.law]['valid'] else "")
                     + (f"; {s['left_out']} left out (markers)" if s["left_out"] else ""))
        lines.append(f"  {'   sd':22s} {'':5s} {'':9s} " + " ".join(f"{sd[k]:7.1f}" for k in JOINTS)
                     + f" {s['foot_strike_angle_deg_sd']:7.1f}")
        lines.append(f"  {'':22s} impact point " + ", ".join(
            f"{p} {n} ({100 * s['impact_point_share'][p]:.0f} %)" for p, n in s["impact_points"].items())
            + "; the markers' contact order " + ", ".join(f"{p} {n}" for p, n in s["contact_order"].items())
            + "; the model's sole " + ", ".join(f"{p} {n}" for p, n in s["model_sole"].items()))
        cop = s.get("centre_of_pressure")
        if cop:
            lines.append(f"  {'':22s} the plate's centre of pressure over the first {COP_WINDOW_S * 1e3:.0f} ms (0 heel, 1 forefoot): "
                         f"median {cop['index_median']:.2f} (10-90 %: {cop['index_10_90'][0]:.2f}-"
                         f"{cop['index_10_90'][1]:.2f}); " + ", ".join(f"{p} {n}" for p, n in cop["points"].items())
                         + f"; the markers agree in {cop['contact_order_agrees']}/{cop['steps']}, the model's sole in "
                         f"{cop['model_sole_agrees']}/{cop['steps']}")
        pl = s.get("plate")
        if pl:
            laws = ", ".join(f"{law} {v:+.2f}" for law, v in pl["laws_impulse_ratio"].items() if v is not None)
            lines.append(f"  {'':22s} the plate over the impact ({pl['window_ms_mean']:.0f} ms, to the impact peak "
                         f"in {pl['impact_peaks']}/{pl['steps']} steps, else 30 ms): horizontal/vertical impulse, medians, "
                         f"{pl['impulse_ratio_median']:+.2f} (sd {pl['impulse_ratio_sd']:.2f}) against the rigid impact's "
                         f"{laws}: nearest {pl['nearest_law']}; impact peak {pl['impact_peak_bw_mean']:.2f} BW, "
                         f"loading rate {pl['loading_rate_bw_per_s_mean']:.0f} BW/s")
        lines += _mass_lines(s.get("impact_mass"), c.law)
    for side, o in rep["optimum"].items():
        lines += _side_lines(c, side, o, st.cadence_spm)
    lines += ["", f"  every touchdown under each contact law (T_c mean, J; valid touchdowns; * {c.law}, "
                  "the law above):",
              f"  {'':22s} " + " ".join(f"{law + (' *' if law == c.law else ''):>20s}" for law in LAWS)]
    for side, s in rep["summary"].items():
        lines.append(f"  {'measured, ' + ('right' if side == 'R' else 'left'):22s} " + " ".join(
            f"{s['laws'][law]['T_c_mean']:8.2f} {s['laws'][law]['valid']:4d}/{s['steps']:<4d}  "
            for law in LAWS))
    lines += [f"  left out: {x}" for x in st.left_out]
    lines += [f"note: {n}" for n in rep["notes"]]
    if "stride" in rep:
        lines += stride_lines(rep["stride"])
    return "\n".join(lines)


def knee_text(deg: float | None) -> str:
    """", stance knee N deg" (the deepest stance flexion), or "" where it is unknown."""
    return "" if deg is None or math.isnan(deg) else f", stance knee {deg:.0f} deg"


def stride_lines(s: dict) -> list[str]:
    """compare's stride section (compare_stride.StrideAnswer.to_dict) in words: the runner
    against the stride optimum, then each what-if cadence with its band; a change whose band
    holds zero is said to be unresolved, never advised."""
    lines = ["", f"  the stride: the half-stride optimum of this body at {s['speed_mps']:.2f} m/s "
                 f"({'model ' + s['model'] + ': ' if s.get('model') else ''}{s.get('transcription', 'trapezoid')} at "
                 f"{s['nodes']} intervals, {s['law']} impacts, objective effort)",
             f"    the runner:  cadence {s['measured_cadence_spm']:6.1f} steps/min, step "
             f"{s['measured_step_length_m']:.3f} m, strike point {s['measured_placement_m']:.3f} m "
             f"ahead of the hip, {s['measured_strike']} strike{knee_text(s.get('measured_stance_knee_deg'))}"]
    if s["optimum_cadence_spm"] is None:
        return lines + [f"    no stride optimum: {'; '.join(s['notes'])}"]
    mark = "" if s.get("optimum_valid", True) else " INVALID (see the notes)"
    lines.append(f"    the optimum{mark}: cadence {s['optimum_cadence_spm']:6.1f} steps/min, step "
                 f"{s['optimum_step_length_m']:.3f} m, strike point {s['optimum_placement_m']:.3f} m "
                 f"ahead of the hip, {s['measured_strike']} strike{knee_text(s.get('optimum_stance_knee_deg'))}; "
                 f"mechanical power "
                 f"{s['optimum_mechanical_power_W']:.0f} W, impact loss {s['optimum_impact_loss_W']:.0f} W")
    lines += [f"      ({remark})" for remark in s.get("optimum_remarks", [])]
    if s.get("sticking_optimum_cadence_spm") is not None:
        lines.append(f"    the sticking strides' optimum (the what-ifs' reference): cadence "
                     f"{s['sticking_optimum_cadence_spm']:6.1f} steps/min; mechanical power "
                     f"{s['sticking_optimum_mechanical_power_W']:.0f} W")
    strikes = ", ".join(f"{k} {v['objective_value']:.3f}" + ("" if v["valid"] else " (INVALID" + (
        ": " + "; ".join(v["failed_checks"]) if v.get("failed_checks") else "" if v["success"] else ": not converged")
        + ")") for k, v in s["strikes"].items() if v is not None)
    best = s["best_strike"] or "none valid"
    lines.append(f"    each strike's free optimum (objective per distance): {strikes}; best valid: {best}")
    if s["what_if"]:
        lines.append("    what if the cadence changed (against the stride at the runner's own cadence; each "
                     f"cadence's least costly optimum found; band over {s['band']}):")
    for w in s["what_if"]:
        lo, hi = w["impact_loss_band_W"]
        parts = ", ".join(f"{p} {share * 100:.0f} %" for p, share in w.get("band_shares", {}).items())
        family = "" if w.get("same_family", True) else " (between two families of strides)"
        lines.append(f"      {w['cadence_change_pct']:+5.0f} % ({w['cadence_spm']:5.1f} steps/min): mechanical "
                     f"power {w['mechanical_power_change_W']:+6.1f} W [{w['low_W']:+.1f}, {w['high_W']:+.1f}]"
                     f"{f' (band: {parts})' if parts else ''}, impact loss {w['impact_loss_change_W']:+6.1f} W "
                     f"[{lo:+.1f}, {hi:+.1f}]: {w['words']}{family}")
    lines += [f"    note: {n}" for n in s["notes"]]
    return lines


def _side_lines(c: Comparison, side: str, o: dict, cadence: float) -> list[str]:
    """One side's optimum: its mean touchdown, the optimum, the saving with its band."""
    name = "right" if side == "R" else "left"
    ref = o["reference"]
    lines = ["", f"  {name}: {o['headline']}",
             f"  {'mean ' + o['point'] + ' touchdown':22s} {o['steps']:5d} {'':9s} "
             + " ".join(f"{ref['angles_deg'][k]:7.1f}" for k in JOINTS) + f" {'':7s} {ref['T_c']:6.2f}"
             + ("" if ref["valid"] else "  INVALID: " + "; ".join(ref["warnings"]))]
    if "touchdown" not in o:
        return lines
    lines.append(f"  {'optimum, same gait':22s} {'':5s} {o['point']:>9s} "
                 + " ".join(f"{o['touchdown']['angles_deg'][k]:7.1f}" for k in JOINTS)
                 + f" {'':7s} {o['T_c']:6.2f}  {o['verdict']}")
    lines.append(f"  {'optimum - measured':22s} {'':5s} {'':9s} "
                 + " ".join(f"{o['difference_deg'][k]:+7.1f}" for k in JOINTS)
                 + f" {'':7s} {o['T_c'] - ref['T_c']:+6.2f}")
    ps = o["per_step"]
    if ps.get("converged"):
        m = ps["angles_deg_mean"]
        lines.append(f"  {'optimum per step':22s} {ps['converged']:5d} {'':9s} {'':7s} "
                     + " ".join(f"{m[k]:7.1f}" for k in ("hip", "knee", "ankle"))
                     + f"  saving {ps['saving_J_mean']:.3f} ± {ps['saving_J_sd']:.3f} J")
    if o["success"]:
        g = o["gait"]
        lines.append(f"  ({c.law}, objective {_objective_text(o['objective_terms'])}; held: hip "
                     f"{g['hip_from_strike_m'][0]:+.3f} m along, {g['hip_from_strike_m'][1]:.3f} m above "
                     f"the {o['point']}, hip velocity ({g['hip_velocity'][0]:+.2f}, {g['hip_velocity'][1]:+.2f}) "
                     f"m/s, the measured segment rates)")
    else:
        lines.append(f"  the optimum ({c.law}): {o['verdict']}: {explain(o['status'])}")
    if o["saving_J_per_step"] is not None:
        lo, hi = o["saving_band_J"]
        lines.append(f"  T_c per step {ref['T_c']:.3f} -> {o['T_c']:.3f} J: saving {o['saving_J_per_step']:.3f} J "
                     f"({o['saving_W']:.2f} W at {cadence:.1f} steps/min), band {lo:+.3f} to {hi:+.3f} J "
                     f"(T_c moves {o['T_c_uncertainty_J']:.3f} J with the filter and the touchdown frame)"
                     + ("" if o["resolvable"] else ": no change that the measurement can resolve"))
    return lines


def trials_table(rows) -> str:
    """The table across trials (compare with several trials): one line per trial and side."""
    head = rows[0]
    pick = ["trial", "side", "steps", "impact_point", "foot_strike_angle_deg", "hip_deg", "knee_deg",
            "ankle_deg", "cadence_spm", "speed_mps", "T_c_J", "saving_J_per_step", "saving_low_J",
            "saving_high_J", "optimum_headline"]
    idx = [head.index(k) for k in pick]
    width = {k: max(len(k), 10) for k in pick}
    width["trial"] = max(len(Path(r[head.index("trial")]).name) for r in rows[1:])
    out = ["  ".join(f"{k:>{width[k]}s}" for k in pick)]
    for row in rows[1:]:
        cells = []
        for k, i in zip(pick, idx):
            v = Path(row[i]).name if k == "trial" else row[i]
            cells.append(f"{v:{width[k]}.2f}" if isinstance(v, float) else f"{v!s:>{width[k]}s}")
        out.append("  ".join(cells))
    return "\n".join(out)


def bench_table(result) -> str:
    """The bench's rows (studies.bench.Bench), the ground they were measured on, the batch."""
    rows = result.rows
    lines = [f"ground: friction {result.friction:g}, slope {math.degrees(result.slope):+.1f} deg "
             "(the bench scene's, data/full_body.toml)", "",
             f"{'level':15s} {'option':28s} {'work':13s} {'time':>11s} {'error':>10s} "
             f"{'mu_c err':>9s} {'dv err':>9s}  note"]
    for r in rows:
        unit = f"{r.time_s * 1e6:9.1f} us" if r.time_s < 1e-2 else f"{r.time_s * 1e3:9.2f} ms"
        lines.append(f"{r.level:15s} {r.option:28s} {r.work:13s} {unit:>11s} {r.error:10.2e} "
                     f"{r.error_mu_c:9.2e} {r.error_dv:9.2e}  {r.note}")
    lines.append(f"\ncompiled mapped batch, paper's leg: {result.batch_states_per_s:,.0f} states/s "
                 "(one core)")
    return "\n".join(lines)


def joints_text(joints) -> str:
    """The joint model and its values as a scene gives them (N m/deg, N m s/deg, N m)."""
    if joints.model == "spring-damper":
        per_deg = math.pi / 180
        return "spring-damper: " + "; ".join(
            f"{j} k {joints.stiffness.get(j, 0.0) * per_deg:.2f} N m/deg, c "
            f"{joints.damping.get(j, 0.0) * per_deg:.3f} N m s/deg, preload "
            f"{joints.preload.get(j, 0.0):+.1f} N m" for j in joints.stiffness)
    if joints.model == "torque":
        return (f"torque: {', '.join(sorted(joints.moments))} moments over "
                f"{joints.times[-1] * 1e3:g} ms ({len(joints.times)} samples)")
    if joints.model == "locked":
        return f"locked: {', '.join(joints.locked)}"
    return "free hinges"


def landing_table(scene: Scene, landing) -> str:
    """The impacts of a landing, what it absorbed, and the checks of its assumptions."""
    verdict = "valid" if landing.valid else "INVALID: " + "; ".join(landing.violations)
    lines = [f"{scene.name}  ({scene.path})",
             f"landing: T_c_total {landing.T_c_total:.4f} J, {verdict}",
             f"model {scene.kind}; {scene.strike} strike; friction {scene.friction:g}; slope "
             f"{math.degrees(scene.slope):+.1f} deg; contact law {landing.law}; integrator "
             f"{scene.numerics.integrator} (dt {scene.integration.dt * 1e3:g} ms)",
             f"joints {joints_text(scene.joints)}", "",
             f"  {'time (ms)':>10s} {'contact':>10s} {'T_c (J)':>10s} {'t (N s)':>9s} "
             f"{'n (N s)':>9s} {'mu_c':>7s} {'dv trunk x, z (m/s)':>22s} {'leaves':>8s} {'slip (m/s)':>10s}"]
    for e in landing.impacts:
        dv = f"{e.dv_trunk[0]:+.4f} {e.dv_trunk[1]:+.4f}" if e.dv_trunk else "-"
        mu = f"{e.mu_c:7.3f}" if e.mu_c is not None else "  n < 0"
        lines.append(f"  {e.time * 1e3:10.3f} {e.contact:>10s} {e.T_c:10.4f} {e.impulse[0]:+9.4f} "
                     f"{e.impulse[1]:+9.4f} {mu} {dv:>22s} {e.mode:>8s} {e.slip:+10.3f}")
    held = ("not checked: the law lets the foot slide" if landing.law != "no-slip" else "yes") \
        if landing.no_slip_held else \
        (f"no: mu_c exceeds the friction at {len(landing.slip_at)} instants, first at "
         f"{landing.slip_at[0] * 1e3:.2f} ms")
    lines += ["", f"  absorbed in all      T_c_total {landing.T_c_total:.4f} J ({verdict})",
              f"  largest mu_c         {landing.mu_c_max:.3f} (friction {scene.friction:g})",
              f"  no-slip held         {held}",
              f"  slid                 {landing.sliding_time * 1e3:.2f} ms on the ground"]
    shown = landing.releases if len(landing.releases) <= 4 else landing.releases[:2]
    lines += [f"  released             {p} at {t * 1e3:.3f} ms: the ground would have pulled it "
              f"({f:.1f} N)" for t, p, f in shown]
    if len(shown) < len(landing.releases):
        t, p, f = landing.releases[-1]
        lines.append(f"  released             ... {len(landing.releases) - len(shown)} more, the last "
                     f"{p} at {t * 1e3:.3f} ms ({f:.1f} N)")
    lines += [f"  energy balance error {landing.energy_error:.2e} J; constraint drift "
              f"{landing.drift:.1e} m",
              f"  ended                {landing.ended} at {landing.t[-1] * 1e3:.2f} ms"]
    lines += [f"warning: {w}" for w in landing.warnings]
    return "\n".join(lines)
