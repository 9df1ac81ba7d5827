"""Where the muscle-driven stride's metabolic energy goes (issue 33): RBDS001's body, heel strike,
the muscles' "metabolic" objective, the cadence imposed in turn.

    python problems/muscle_energy.py [--speed 3.5] [--cadences 171.4 222] [--nodes 24] [--weight W]

Per cadence: the objective's terms (per distance, as IPOPT sees them); the muscles' energy per
step (J) split by muscle, into stance (the right leg while it holds the ground) and swing (the
rest: the left leg throughout, the right in flight), and into Bhargava et al. 2004's terms
(activation A, maintenance M, shortening S heat, positive fibre work W; the floor's share is
E - A - M - S - W); the fibres' negative work, the tendons' stored energy; the reserves'
positive and negative work (J) and their share of the joint moments' impulse. Then a hand check
of mechanics.muscles.metabolic_rate: a soleus isometric at its optimal length, fully active, and
shortening at 0.2 v_max (A + M = m_M ((1 - f)(40 + 74) + f (133 + 111)) W; S and W from F v).
"""

from __future__ import annotations

import argparse
import sys

import casadi as ca
import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics import muscles as hill
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import GRAVITY, JOINTS, JointSpace
from formopt.optim.stride import problem
from formopt.optim.stride.collocation import NX, build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.ocp import INTEGRANDS, step_length
from formopt.optim.stride.problem import StrideSettings

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
    """Per leg role (stance, swing) the integrals (J, n muscles) of A, M, S, W, E and W-, and the
    reserves' work and moment impulses."""
    act = nlp.ocp.models[0].actuation
    n, m, blocks = act.n, nlp.mass, stride.solved.blocks
    function = leg_terms(act.muscles)
    out = {role: np.zeros((6, n)) for role in ("stance", "swing")}
    volume = act.muscles.volume / act.muscles.volume.sum()
    rates = {f"{key}_{role}": 0.0 for key in ("force_rate", "activation_rate") for role in out}
    reserve = {"positive_J": 0.0, "negative_J": 0.0, "impulse": 0.0, "muscle_impulse": 0.0, "squared": 0.0}
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
            rates[f"force_rate_{role}"] += float(volume @ Fd ** 2 @ w)
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
    return {"roles": out, "reserve": reserve, "names": act.muscles.names, "rates": rates}


def cost_terms(nlp, stride) -> dict:
    """Each cost term's value (per distance, as the objective), the impacts and smoothing as the rest."""
    sums = np.sum([L @ w for L, w in nlp.integrands(stride.solved.blocks, stride.solved.parameters)], axis=0)
    integrals = dict(zip(INTEGRANDS, sums))
    d = step_length(stride.speed_mps, stride.half_period_s)
    out = {term.integral: float(term(integrals, d)) for term in nlp.ocp.cost_terms if term.integral in integrals}
    out["impacts+smoothing"] = stride.objective_value - sum(out.values())
    return out


def report(nlp, stride) -> None:
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
    print("   volume-weighted squared rates per step, int sum V_i x_i^2 / sum V dt (1/s): "
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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--cadences", type=float, nargs="+", default=[171.4, 222.0])
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--weight", type=float, default=problem.FORCE_RATE_WEIGHT)
    args = parser.parse_args(argv)
    body = scaled_body(args.mass, 1.81)
    settings = StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic",
                              muscles=body_muscles(body), force_rate_weight=args.weight)
    nlp = build(body, settings)
    print(f"RBDS001's height, {args.mass:g} kg, heel, {args.nodes} nodes, {args.speed} m/s, "
          f"force-rate weight {args.weight:g}")
    for cadence in args.cadences:
        report(nlp, optimum(nlp, args.speed, cadence=cadence))
    hand_check(body)
    return 0


if __name__ == "__main__":
    sys.exit(main())
