"""Where the muscle-driven stride's metabolic energy goes (issue 33): RBDS001's body, heel strike,
the muscles' "metabolic" objective, the cadence imposed in turn.

    python problems/muscle_energy.py [--speed 3.5] [--cadences 171.4 222] [--nodes 24] [--weight W] [--power 1]
                                     [--grading 1] [--start search [--search-nodes 40] | --load FILE]
                                     [--save FILE] [--free] [--strength iliopsoas=1.5]
                                     [--duration flight=80-250] [--dorsiflexion 20] [--rate-smoothing 0.25]
                                     [--activation-smoothing 10] [--detail]

Per cadence: the objective's terms (per distance, as IPOPT sees them); the muscles' energy per
step (J) split by muscle, into stance (the right leg while it holds the ground) and swing (the
rest: the left leg throughout, the right in flight), and into Bhargava et al. 2004's terms
(activation A, maintenance M, shortening S heat, positive fibre work W; the floor's share is
E - A - M - S - W); the fibres' negative work, the tendons' stored energy; the reserves'
positive and negative work (J) and their share of the joint moments' impulse. Then a hand check
of mechanics.muscles.metabolic_rate: a soleus isometric at its optimal length, fully active, and
shortening at 0.2 v_max (A + M = m_M ((1 - f)(40 + 74) + f (133 + 111)) W; S and W from F v).

By default each cadence is solved from the generic start (local.optimum). With `--start search`
the free optimum is the global search's (search.global_optimum, spend 1) on `--search-nodes`
solved again on `--nodes` (refine.refined), and each cadence is solved warm from its neighbour,
walking out from the free optimum (refine.warm_options); `--save`/`--load` keep that free stride
(its blocks, pickled) so that a what-if starts from it; `--free`: the free optimum solved warm from
the loaded stride on this NLP (a what-if's own optimum). `--strength muscle=factor`: a throw-away
variant with that muscle's F_max (and so its volume and mass) scaled, not a default; `--duration
phase=low-high` (ms): that phase's duration bounds (StrideSettings.duration), a what-if;
`--dorsiflexion D` (deg): the ankle's range of motion ends at D (joint_space.RANGES, 30 deg: the
solve's bound D + 5 deg and the range wall there), a what-if; `--rate-smoothing EPS` (1/s): --power 1's
|F'| smoothing (mechanics.muscles.FORCE_RATE_SMOOTHING, 0.5), a what-if; `--activation-smoothing S`:
the activation rates' scale in the transcription's smoothing (StrideSettings.activation_rate_smoothing,
10; 0 leaves their null mode open), a what-if; `--cadences` with no value: the free stride alone;
`--nodes` past the scenes' 120 (as problems/muscle_mesh.py), for a --load'ed stride. `--detail`:
per cadence also the force-rate term's part of the objective by muscle, stance and swing, and each
muscle's time at activation > 0.9; at the end one line per cadence (the table of
docs/concepts/muscles.md, "Why the cadence is low at 2.5 m/s") and the relaxed ankle's passive
moment at 20-35 deg of dorsiflexion (`relaxed_ankle`).
"""

from __future__ import annotations

import argparse
import dataclasses
import pickle
import sys

import casadi as ca
import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics import joint_space
from formopt.mechanics import muscles as hill
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import GRAVITY, JOINTS, JointSpace
from formopt.optim.stride import ranges
from formopt.optim.stride.actuation import ACTIVATION_RATE_SMOOTHING
from formopt.optim.stride.collocation import NX, build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.ocp import INTEGRANDS, step_length
from formopt.optim.stride.problem import FORCE_RATE_POWERS, StrideSettings
from formopt.optim.stride.refine import refined, warm_options
from formopt.optim.stride.search import global_optimum

TERMS = ("activation", "maintenance", "shortening", "work")


def leg_terms(muscles: hill.Muscles) -> ca.Function:
    """(theta, theta', a, F, F') -> Bhargava's A, M, S, W, the total E (W, n each) and the fibres'
    negative work rate (W, n) for one leg's muscles."""
    n = len(muscles.names)
    angles, rates = ca.SX.sym("theta", 3), ca.SX.sym("theta_dot", 3)
    a, F, Fd = (ca.SX.sym(name, n) for name in ("a", "F", "F_dot"))
    length, velocity = hill.fibre_state(muscles, angles, rates, F, Fd)
    terms = hill.metabolic_terms(muscles, a, length, velocity)
    contractile = a * hill.active_force_length(length, ca.DM(muscles.width)) * hill.force_velocity(velocity)
    negative = ca.fmax(contractile * ca.DM(muscles.max_force) * velocity * ca.DM(muscles.max_velocity), 0.0)
    return ca.Function("terms", [angles, rates, a, F, Fd],
                       [*(terms[t] for t in TERMS), hill.metabolic_rate(muscles, a, length, velocity), negative])


def breakdown(nlp, stride) -> dict:
    """Per leg role (stance, swing) the integrals (J, n muscles) of A, M, S, W, E and W-, the
    reserves' work and moment impulses, and per muscle (`by_muscle`) int V_i |F'_i|^p / sum V dt
    (1/s^(p-1), p the force-rate power: mechanics.muscles.charged_force_rate) and the time at
    activation > 0.9 (s)."""
    act = nlp.ocp.models[0].actuation
    n, m, blocks = act.n, nlp.mass, stride.solved.blocks
    function = leg_terms(act.muscles)
    out = {role: np.zeros((6, n)) for role in ("stance", "swing")}
    volume = act.muscles.volume / act.muscles.volume.sum()
    rates = {f"{key}_{role}": 0.0 for key in ("force_rate", "activation_rate") for role in out}
    reserve = {"positive_J": 0.0, "negative_J": 0.0, "impulse": 0.0, "muscle_impulse": 0.0, "squared": 0.0}
    by_muscle = {key: {role: np.zeros(n) for role in out} for key in ("force_rate", "saturated_s")}
    for phase, (_, w) in zip(nlp.phases, nlp.integrands(blocks, stride.solved.parameters)):
        X, Z, U = (blocks[f"{key}_{phase.name}"] for key in "XZU")
        for k in range(2):
            joints = slice(3 + 3 * k, 6 + 3 * k)
            values = function.map(X.shape[1])(X[joints], X[NX:][joints], Z[2 * n * k:2 * n * k + n],
                                              Z[2 * n * k + n:2 * n * (k + 1)],
                                              act.RATE_SCALE * U[3 * n * k + 2 * n:3 * n * (k + 1)])
            role = "stance" if k == 0 and phase.rows else "swing"
            out[role] += np.vstack([np.asarray(v, float) @ w for v in values]).reshape(6, n)
            Fd, ad = act.RATE_SCALE * U[3 * n * k + 2 * n:3 * n * (k + 1)], act.ACTIVATION_SCALE * U[3 * n * k + n:3 * n * k + 2 * n]
            charged = np.asarray(hill.charged_force_rate(ca.DM(Fd), nlp.settings.force_rate_power), float)
            rates[f"force_rate_{role}"] += float(volume @ charged @ w)
            by_muscle["force_rate"][role] += volume * (charged @ w)
            by_muscle["saturated_s"][role] += (Z[2 * n * k:2 * n * k + n] > 0.9) @ w
            rates[f"activation_rate_{role}"] += float(volume @ ad ** 2 @ w)
        r = m * U[6 * n:]
        power = -r * X[NX + 3:]
        reserve["positive_J"] += float(np.maximum(power, 0).sum(axis=0) @ w)
        reserve["positive_by_joint"] = reserve.get("positive_by_joint", 0.0) + np.maximum(power, 0) @ w
        reserve["largest_by_joint"] = np.maximum(reserve.get("largest_by_joint", 0.0), np.abs(U[6 * n:]).max(axis=1))
        reserve["negative_J"] += float(np.maximum(-power, 0).sum(axis=0) @ w)
        reserve["impulse"] += float(np.abs(r).sum(axis=0) @ w)
        muscle = nlp.moments(blocks, nlp.phases.index(phase))[0] - r
        reserve["muscle_impulse"] += float(np.abs(muscle).sum(axis=0) @ w)
        reserve["squared"] += float((U[6 * n:] ** 2).sum(axis=0) @ w)
    return {"roles": out, "reserve": reserve, "names": act.muscles.names, "rates": rates, "by_muscle": by_muscle}


def rate_term(nlp):
    """The objective's force-rate term (costs.CostTerm), of either power."""
    return next(t for t in nlp.ocp.cost_terms if t.integral in ("force_rate", "force_rate_abs"))


def cost_terms(nlp, stride) -> dict:
    """Each cost term's value (per distance, as the objective), the impacts and smoothing as the rest."""
    sums = np.sum([L @ w for L, w in nlp.integrands(stride.solved.blocks, stride.solved.parameters)], axis=0)
    integrals = dict(zip(INTEGRANDS, sums))
    d = step_length(stride.speed_mps, stride.half_period_s)
    out = {term.integral: float(term(integrals, d)) for term in nlp.ocp.cost_terms if term.integral in integrals}
    out["impacts+smoothing"] = stride.objective_value - sum(out.values())
    return out


def detail(nlp, stride, parts: dict) -> None:
    """Per muscle (both legs' share of one step) the force-rate term's part of the objective,
    w s int V_i |F'_i|^p / sum V dt / d (costs.CostTerm), stance and swing, and the time at
    activation > 0.9 (s, the right leg's stance and the rest)."""
    term = rate_term(nlp)
    rates, saturated = parts["by_muscle"]["force_rate"], parts["by_muscle"]["saturated_s"]
    print(f"   {'force rate, a > 0.9':22s}{'FR stance':>10s}{'FR swing':>10s}{'a>0.9 st s':>11s}{'a>0.9 sw s':>11s}")
    for i, name in enumerate(parts["names"]):
        print(f"   {name:22s}" + "".join(f"{term.weight * term.scale * rates[r][i] / stride.step_length_m:10.4f}"
                                        for r in ("stance", "swing"))
              + "".join(f"{saturated[r][i]:11.3f}" for r in ("stance", "swing")))


def summary(nlp, stride) -> dict:
    """One cadence's row of the closing table (main): the objective's parts, the muscles'
    energy (J per step) and the force-rate term's part, stance and swing."""
    parts, terms = breakdown(nlp, stride), cost_terms(nlp, stride)
    term = rate_term(nlp)
    rates = parts["by_muscle"]["force_rate"]
    return {"cadence": stride.cadence_spm, "objective": stride.objective_value, **terms,
            "E stance J": parts["roles"]["stance"][4].sum(), "E swing J": parts["roles"]["swing"][4].sum(),
            **{f"FR {r}": term.weight * term.scale * rates[r].sum() / stride.step_length_m for r in rates},
            "stance s": stride.stance_s, "peak N/kg": stride.peak_vertical_grf_bw * GRAVITY,
            "reserve N m/kg": stride.muscles["reserve_nm_per_kg"], "valid": stride.valid}


def table(rows: list[dict]) -> None:
    """The closing table: one line per stride, sorted by cadence."""
    keys = list(rows[0])
    print("\n" + " | ".join(keys))
    for row in sorted(rows, key=lambda r: r["cadence"]):
        print(" | ".join(f"{row[k]:.4g}" if isinstance(row[k], float) else str(row[k]) for k in keys))


def report(nlp, stride, details: bool = False) -> None:
    m, d = nlp.mass, stride.step_length_m
    parts = breakdown(nlp, stride)
    roles, names = parts["roles"], parts["names"]
    total = sum(roles.values())
    print(f"\n== {stride.cadence_spm:.1f} steps/min: step {d:.3f} m, stance {stride.stance_s:.3f} s, "
          f"peak vertical force {stride.peak_vertical_grf_bw * GRAVITY:.1f} N/kg, objective {stride.objective_value:.4f}, "
          f"valid {stride.valid} ({'; '.join(stride.failed_checks)})")
    print("   objective terms (per distance): "
          + ", ".join(f"{k} {v:.4f}" for k, v in cost_terms(nlp, stride).items()))
    energy = total[4].sum()
    print(f"   muscles' energy {energy:.1f} J per step = {energy / (m * d):.3f} J/kg/m "
          f"({energy / stride.half_period_s / m:.2f} W/kg); joints' W+ {stride.budget['positive_work_J']:.1f} J, "
          f"W- {stride.budget['negative_work_J']:.1f} J; fibres' W+ {total[3].sum():.1f} J, W- {total[5].sum():.1f} J; "
          f"tendons store {stride.muscles['tendon_stored_J']:.1f} J")
    print(f"   {'J per step':22s}" + "".join(f"{t[:5]:>8s}" for t in (*TERMS, "floor", "total", "fibW-")))
    for label, values in [*((role, roles[role]) for role in roles), ("both", total)]:
        floor = values[4] - values[:4].sum(axis=0)
        print(f"   {label:22s}" + "".join(f"{x:8.1f}" for x in (*values[:4].sum(axis=1), floor.sum(),
                                                                 values[4].sum(), values[5].sum())))
    for i, name in enumerate(names):
        floor = total[4, i] - total[:4, i].sum()
        print(f"   {name:22s}" + "".join(f"{x:8.1f}" for x in (*total[:4, i], floor, total[4, i], total[5, i]))
              + f"   stance {roles['stance'][4, i]:5.1f} swing {roles['swing'][4, i]:5.1f}")
    print("   volume-weighted rates per step, int sum V_i x_i^p / sum V dt (F' to the force-rate power, a' squared): "
          + ", ".join(f"{k} {v:.2f}" for k, v in parts["rates"].items())
          + f"; per distance, both roles: F' {sum(v for k, v in parts['rates'].items() if k.startswith('force')) / d:.3f},"
          f" a' {sum(v for k, v in parts['rates'].items() if k.startswith('activation')) / d:.3f} /m")
    r = parts["reserve"]
    print(f"   reserves: W+ {r['positive_J']:.2f} J, W- {r['negative_J']:.2f} J, |moment| impulse "
          f"{r['impulse']:.2f} N m s = {100 * r['impulse'] / (r['impulse'] + r['muscle_impulse']):.1f} % of the joints'; "
          f"largest over 10 ms {stride.muscles['reserve_nm_per_kg']:.2f} N m/kg "
          f"({stride.muscles['reserve_peak_nm_per_kg']:.2f} at a node)")
    print("   reserves by joint (R = the stance leg): W+ J " + ", ".join(
        f"{j} {x:.1f}" for j, x in zip(JOINTS, r["positive_by_joint"])) + "; largest N m/kg " + ", ".join(
        f"{j} {x:.2f}" for j, x in zip(JOINTS, r["largest_by_joint"])))
    if details:
        detail(nlp, stride, parts)


def hand_check(body) -> None:
    """The soleus at l_opt, a = 1: isometric, then shortening at 0.2 v_max (module docstring)."""
    leg = hill.subset(body_muscles(body), ("soleus",))
    mass, fast, F, vmax = leg.mass[0], leg.fast_twitch[0], leg.max_force[0], leg.max_velocity[0]
    hand = mass * ((1 - fast) * (40 + 74) + fast * (133 + 111))
    model = float(hill.metabolic_rate(leg, 1.0, 1.0, 0.0))
    print(f"\nhand check, soleus ({mass:.2f} kg, {fast:.2f} fast, F_max {F:.0f} N, v_max {vmax:.2f} m/s):")
    print(f"   isometric, a = 1: hand {hand:.1f} W, model {model:.1f} W")
    fv = float(hill.force_velocity(-0.2))
    v = 0.2 * vmax
    shortening = (0.16 * F + 0.18 * F * fv) * v
    work = F * fv * v
    model = float(hill.metabolic_rate(leg, 1.0, 1.0, -0.2))
    print(f"   shortening at 0.2 v_max (f_V {fv:.3f}): hand A + M {hand:.1f} + S {shortening:.1f} + W {work:.1f} "
          f"= {hand + shortening + work:.1f} W (efficiency W/E {work / (hand + shortening + work):.2f}), model {model:.1f} W")
    held = hand * 0.15
    print(f"   the soleus fully active for 0.15 s (a stance): {held:.1f} J; a runner's net "
          f"4 J/kg/m at 3.5 m/s and 171 steps/min: {4 * JointSpace(body).mass_total * 3.5 * 60 / 171.4:.0f} J per step")


def relaxed_ankle(body) -> None:
    """The ankle's passive plantarflexion moment (N m) at 20-35 deg of dorsiflexion, the hip at
    20 deg and the knee at 20 and 50 deg: the muscles at activation 0.01 in isometric equilibrium
    (mechanics.muscles.isometric_force, their parallel elements and tendons) and the range wall
    (joint_space.range_wall), what resists a stance ankle's dorsiflexion up to its bound."""
    leg = body_muscles(body)
    angles = (20.0, 25.0, 30.0, 35.0)
    print("\nrelaxed ankle, plantarflexion moment N m at " + ", ".join(f"{a:g}" for a in angles) + " deg:")
    for knee in (20.0, 50.0):
        muscle = [float(hill.joint_moments(leg, hill.isometric_force(leg, np.full(len(leg.names), 0.01),
                                                                     np.radians([20.0, knee, a])))[2])
                  for a in angles]
        wall = [-float(joint_space.range_wall(np.radians(a), *joint_space.RANGES["ankle"])) for a in angles]
        print(f"   knee {knee:g} deg: muscles " + ", ".join(f"{m:.1f}" for m in muscle)
              + "; range wall " + ", ".join(f"{w:.1f}" for w in wall))


def what_if(muscles: hill.Muscles, items: list[str], field: str, option: str, scale: bool) -> hill.Muscles:
    """`muscles` with each named muscle's parameter `field` (hill.Muscles') times the value
    (`scale`) or set to it, from "name=value" items of the command-line `option`: a what-if
    ("iliopsoas=1.5" with --strength: F_max times 1.5; "soleus=0.56" with --width: its width)."""
    values = getattr(muscles, field).copy()
    for item in items:
        name, _, value = item.partition("=")
        if name not in muscles.names:
            raise SystemExit(f"{option} {item}: no muscle {name!r}; expected one of {', '.join(muscles.names)}")
        k = muscles.names.index(name)
        values[k] = values[k] * float(value) if scale else float(value)
    return dataclasses.replace(muscles, **{field: values})


def free_start(nlp, args) -> tuple:
    """The free optimum the cadences walk out from, as (stride or None, its blocks, its cadence):
    the search's on --search-nodes solved again on the NLP's nodes, or the --load'ed stride's
    blocks, solved warm on this NLP with --free."""
    if args.load:
        with open(args.load, "rb") as file:
            saved = pickle.load(file)
        if not args.free:
            return None, saved["blocks"], saved["cadence"]
        stride = optimum(nlp.variant(warm_options(nlp)), args.speed, guess=saved["blocks"])
    else:
        coarse = nlp.variant(nodes=args.search_nodes)
        stride = refined(nlp, global_optimum(coarse, args.speed), coarse)
    if args.save:
        with open(args.save, "wb") as file:
            pickle.dump({"blocks": stride.solved.blocks, "cadence": stride.cadence_spm}, file)
    return stride, stride.solved.blocks, stride.cadence_spm


def walk(nlp, args, start: tuple):
    """The free stride (where solved here), then each cadence solved warm from its neighbour,
    walking up and down from the free optimum (`free_start`'s)."""
    stride, blocks, free = start
    if stride is not None:
        yield stride
    warm = nlp.variant(warm_options(nlp))
    for chain in (sorted(c for c in args.cadences if c >= free),
                  sorted((c for c in args.cadences if c < free), reverse=True)):
        previous = blocks
        for cadence in chain:
            stride = optimum(warm, args.speed, cadence=cadence, guess=previous)
            previous = stride.solved.blocks
            yield stride


def durations(items: list[str]) -> dict:
    """StrideSettings' duration bounds with each "phase=low-high" (ms) over them: a what-if."""
    out = dict(StrideSettings().duration)
    for item in items:
        phase, _, span = item.partition("=")
        low, _, high = span.partition("-")
        if phase not in out:
            raise SystemExit(f"--duration {item}: no phase {phase!r}; expected one of {', '.join(out)}")
        out[phase] = (float(low) * 1e-3, float(high) * 1e-3)
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--cadences", type=float, nargs="*", default=[171.4, 222.0])
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--weight", type=float, help="the force-rate weight (default: the power's calibrated one)")
    parser.add_argument("--power", type=int, default=2, choices=FORCE_RATE_POWERS, help="the force-rate term's power")
    parser.add_argument("--grading", type=float, default=0.0, help="StrideSettings.grading")
    parser.add_argument("--start", default="generic", choices=("generic", "search"),
                        help="each cadence from the generic start, or warm from its neighbour from the free optimum")
    parser.add_argument("--search-nodes", type=int, default=40, help="the search's mesh (--start search)")
    parser.add_argument("--save", help="pickle the free stride's blocks here")
    parser.add_argument("--load", help="walk from this pickled free stride (implies --start search)")
    parser.add_argument("--free", action="store_true", help="the free optimum solved warm from --load's")
    parser.add_argument("--strength", nargs="*", default=[], help="muscle=factor: F_max scaled (a what-if)")
    parser.add_argument("--duration", nargs="*", default=[], help="phase=low-high (ms): its bounds (a what-if)")
    parser.add_argument("--dorsiflexion", type=float, help="deg: the ankle's range's end (a what-if; 30)")
    parser.add_argument("--rate-smoothing", type=float, help="1/s: --power 1's eps (a what-if; 0.5)")
    parser.add_argument("--activation-smoothing", type=float,
                        help="a' scale in the transcription's smoothing (a what-if; StrideSettings.activation_rate_smoothing)")
    parser.add_argument("--detail", action="store_true", help="force rate by muscle, time at a > 0.9, a table")
    args = parser.parse_args(argv)
    if args.rate_smoothing is not None and (args.power != 1 or not args.rate_smoothing > 0):
        parser.error("--rate-smoothing: |F'|'s eps (1/s, > 0) with --power 1")
    if args.dorsiflexion is not None:  # a what-if: this process's ranges, read when the NLP is built
        joint_space.RANGES["ankle"] = (joint_space.RANGES["ankle"][0], np.radians(args.dorsiflexion))
    if args.rate_smoothing is not None:  # a what-if: this process's |F'| smoothing, read when the NLP is built
        hill.FORCE_RATE_SMOOTHING = args.rate_smoothing
    ranges.allow_nodes(args.nodes)
    body = scaled_body(args.mass, 1.81)
    settings = StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic", grading=args.grading,
                              muscles=what_if(body_muscles(body), args.strength, "max_force", "--strength", True), force_rate_weight=args.weight,
                              force_rate_power=args.power, duration=durations(args.duration),
                              activation_rate_smoothing=(ACTIVATION_RATE_SMOOTHING if args.activation_smoothing is None
                                                         else args.activation_smoothing))
    nlp = build(body, settings)
    print(f"RBDS001's height, {args.mass:g} kg, heel, {args.nodes} nodes"
          f"{f' graded {args.grading:g}' if args.grading else ''}, {args.speed} m/s, force-rate weight {settings.rate_weight:g}, power {args.power}"
          + (f", F_max x {' '.join(args.strength)}" if args.strength else "")
          + (f", durations (ms) {' '.join(args.duration)}" if args.duration else "")
          + (f", ankle range to {args.dorsiflexion:g} deg" if args.dorsiflexion is not None else "")
          + (f", |F'| smoothing {args.rate_smoothing:g} /s" if args.rate_smoothing is not None else "")
          + f", a' smoothing scale {settings.activation_rate_smoothing:g}", flush=True)
    if args.start == "search" or args.load:
        strides = walk(nlp, args, free_start(nlp, args))
    else:
        strides = (optimum(nlp, args.speed, cadence=cadence) for cadence in args.cadences)
    rows = []
    for stride in strides:
        report(nlp, stride, args.detail)
        rows += [summary(nlp, stride)] if args.detail else []
        sys.stdout.flush()
    if rows:
        table(rows)
        relaxed_ankle(body)
    hand_check(body)
    return 0


if __name__ == "__main__":
    sys.exit(main())
