"""Why the muscle stride's stance ankle sits on its 35 deg dorsiflexion bound (issue 33): the
shipped muscle scene (formopt/scenes/stride_muscles.toml: RBDS001, 3.5 m/s, heel, 40 nodes)
solved once, then read at its stance nodes.

    python problems/ankle_bound.py [--speed 3.5] [--dorsiflexion 30] [--wall anderson-pandy]
                                   [--width soleus=0.56] [--strike heel] [--brief | --no-solve]

Per stance node (R the stance leg): the ankle angle (deg), the soleus's and gastrocnemius's
normalised fibre length l~ = l_M / l_opt, tendon strain l_T / l_Ts - 1, normalised tendon force F,
the parallel element's force f_PE (F_max), activation a; the muscles' ankle moment and the range
wall's (N m, plantarflexor positive); and IPOPT's multiplier on the ankle's upper bound (lam_x,
in the objective's units per rad: d(objective)/d(bound) = -lam_x, the envelope theorem).

Then, without a solve: the plantarflexors over RBDS001's own stance (its processed mean cycle,
data/rbds): at each sample of the runner's stance hip, knee and ankle angles, the soleus's and
gastrocnemius's l~ with their tendons slack (F = 0) and loaded to F = 1, beside the same at the
model's 35 deg bound; and the relaxed ankle's passive plantarflexion moment (the muscles at
activation 0.01, isometric: mechanics.muscles.isometric_force, plus the range wall) against
Riener & Edrich 1999's measured relaxed-leg moment (mechanics.joint_space.passive_moments).

What-ifs, none a default (this process only, read when the NLP is built): `--dorsiflexion D`
(deg): the ankle's range of motion ends at D (joint_space.RANGES, 30 deg: the solve's bound at
D + LIMIT_MARGIN and the range wall there); `--wall anderson-pandy`: the ankle's range wall
replaced by Anderson & Pandy 1999's non-muscle passive moment as 3dpredictsim tabulates it
(`anderson_pandy`); `--width muscle=w`: that muscle's active force-length width (gait2d's:
soleus 1.039, gastrocnemius 0.888).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
from pathlib import Path

import casadi as ca
import numpy as np
from muscle_energy import cost_terms, what_if  # problems/, this script's directory

from formopt.io.muscle_table import body_muscles
from formopt.io.scene import load
from formopt.mechanics import joint_space
from formopt.mechanics import muscles as hill
from formopt.optim.stride.bounds import held_text
from formopt.optim.stride.collocation import NX
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import STRIKES
from formopt.studies.stride import measured_cycle

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "formopt" / "scenes" / "stride_muscles.toml"
RBDS = ROOT / "data" / "rbds" / "RBDS001processed.txt"
PLANTARFLEXORS = ("soleus", "gastrocnemius")
ANKLE = 5  # ankle_R in THETA


# Anderson & Pandy 1999 (Comput Methods Biomech Biomed Engin 2:201), the ankle's passive moment of
# its non-muscle tissues, as 3dpredictsim's PassiveMoments/PassiveMomentsData.m tabulates it for
# a muscle-driven gait (Falisse et al. 2019, J R Soc Interface 16:20190402; its README says
# "Anderson & Pandy (2009)"): k1 exp(k2 (phi - high)) + k3 exp(k4 (phi - low)), phi the
# dorsiflexion (rad), (k1, k2, k3, k4, low, high); 2.03 N m at 29.8 deg, 65 N m at 35 deg.
ANDERSON_PANDY_ANKLE = (-2.03, 38.11, 0.18, -12.12, -0.74, 0.52)


def anderson_pandy(range_wall):
    """joint_space.range_wall with the ankle's (its range RANGES["ankle"]) Anderson & Pandy's."""
    def wall(phi, low, high):
        if (low, high) != joint_space.RANGES["ankle"]:
            return range_wall(phi, low, high)
        k1, k2, k3, k4, lo, hi = ANDERSON_PANDY_ANKLE
        return k1 * ca.exp(k2 * (phi - hi)) + k3 * ca.exp(k4 * (phi - lo))
    return wall


def tendon_strain(force):
    """l_T / l_Ts - 1 of De Groote's tendon at normalised force F (mechanics.muscles.tendon_length)."""
    return np.asarray(hill.tendon_length(ca.DM(force)), float).ravel() - 1.0


def node_state(leg: hill.Muscles, angles, rates, force, rate) -> dict:
    """l~, strain, f_PE of each muscle (n,) at one node."""
    length, _ = (np.asarray(v, float).ravel() for v in hill.fibre_state(leg, angles, rates, force, rate))
    passive = np.asarray(hill.passive_force_length(length, leg.passive_slack, leg.passive_stiffness), float).ravel()
    return {"length": length, "strain": tendon_strain(force), "passive": passive}


def stance_table(nlp, stride) -> None:
    """The module docstring's per-node table over the stance phases."""
    act = nlp.ocp.models[0].actuation
    leg, n = act.muscles, act.n
    index = [leg.names.index(m) for m in PLANTARFLEXORS]
    lam = nlp.blocks.split(stride.solved.lam_x)
    high = joint_space.RANGES["ankle"][1] + joint_space.LIMIT_MARGIN
    print(f"\nthe stance nodes (the ankle's bound {math.degrees(high):.1f} deg; lam_x per rad of it)")
    head = "".join(f"{m[:4]:>5s} l~ strain    F  f_PE     a " for m in PLANTARFLEXORS)
    print(f"{'phase':>9s} {'node':>6s} {'ankle':>6s} {'knee':>6s} " + head + " tau_mus  wall  lam_x")
    for phase in nlp.phases:
        if not phase.rows:
            continue
        X, Z, U = (stride.solved.blocks[f"{key}_{phase.name}"] for key in "XZU")
        for j in range(X.shape[1]):
            theta, rates = X[3:6, j], X[NX + 3:NX + 6, j]
            a, F, Fd = Z[:n, j], Z[n:2 * n, j], act.RATE_SCALE * U[2 * n:3 * n, j]
            s = node_state(leg, theta, rates, F, Fd)
            muscle = float(hill.joint_moments(leg, F)[2])
            wall = -float(joint_space.range_wall(theta[2], *joint_space.RANGES["ankle"]))
            cells = "".join(f"{s['length'][i]:8.3f} {s['strain'][i]:6.4f} {F[i]:5.2f} {s['passive'][i]:5.3f} {a[i]:5.2f} "
                            for i in index)
            print(f"{phase.name:>9s} {j:6d} {math.degrees(theta[2]):6.1f} {math.degrees(theta[1]):6.1f} "
                  + cells + f"{muscle:8.1f} {wall:5.2f} {lam[f'X_{phase.name}'][ANKLE, j]:+.2e}")


def summary(nlp, stride) -> None:
    """One line: cadence, objective and its terms, stance (s) and contact length (m), peak force,
    the stance ankle's largest dorsiflexion and the wall's largest moment there, the largest
    multiplier of the ankle's upper bound, the tendons' energy, validity and what the bounds hold."""
    stance = [k for k, name in enumerate(stride.phase) if name != "flight"]
    ankle = stride.theta[stance, ANKLE]
    wall = -min(float(joint_space.range_wall(a, *joint_space.RANGES["ankle"])) for a in ankle)
    lam = max(float(nlp.blocks.split(stride.solved.lam_x)[f"X_{p.name}"][ANKLE].max()) for p in nlp.phases)
    terms = ", ".join(f"{k} {v:.4f}" for k, v in cost_terms(nlp, stride).items())
    print(f"\n{stride.cadence_spm:.1f} steps/min, objective {stride.objective_value:.4f} ({terms}); stance "
          f"{stride.stance_s:.3f} s, contact {stride.speed_mps * stride.stance_s:.2f} m, peak "
          f"{stride.peak_vertical_grf_bw * joint_space.GRAVITY:.1f} N/kg; stance ankle at most {np.degrees(ankle.max()):.1f} deg "
          f"(wall {wall:.1f} N m), lam_x {lam:.3g} /rad; tendons store {stride.muscles['tendon_stored_J']:.1f} J "
          f"(soleus and gastrocnemius {stride.muscles['achilles_stored_J']:.1f}); valid {stride.valid} "
          f"({'; '.join(stride.failed_checks)}); {held_text(stride.held) or 'no bound holds it'}")


def runner_lengths(body, speed: float) -> None:
    """The plantarflexors' l~ over RBDS001's stance (F = 0 and F = 1), and at the model's bound."""
    leg = body_muscles(body)
    cycle = measured_cycle(RBDS, speed)
    stance = cycle["vertical"] > 0.5
    last = int(np.argmin(stance[1:])) + 1 if not stance.all() else len(stance)
    rows = range(0, last, max(1, last // 10))
    index = [leg.names.index(m) for m in PLANTARFLEXORS]
    print(f"\nRBDS001 at {speed} m/s, its stance (0-{cycle['percent'][last - 1]:.0f} % of the cycle): "
          "the plantarflexors' l~ = l_M / l_opt with the tendon slack (F = 0) and at F = 1")
    print(f"{'%':>4s} {'hip':>6s} {'knee':>6s} {'ankle':>6s} "
          + "".join(f"{m[:4]:>6s} F=0 {m[:4]:>5s} F=1" for m in PLANTARFLEXORS) + "  runner's ankle N m/kg")
    for k in [*rows, int(np.argmax(np.where(stance, cycle["angles"]["ankle"], -99)))]:
        angles = np.radians([cycle["angles"][j][k] for j in ("hip", "knee", "ankle")])
        cells = ""
        for i in index:
            lengths = [float(hill.fibre_state(leg, angles, np.zeros(3), ca.DM(np.full(len(leg.names), f)), 0.0)[0][i])
                       for f in (0.0, 1.0)]
            cells += f"{lengths[0]:10.3f} {lengths[1]:9.3f}"
        print(f"{cycle['percent'][k]:4.0f} " + " ".join(f"{cycle['angles'][j][k]:6.1f}" for j in ("hip", "knee", "ankle"))
              + cells + f"  {cycle['moments']['ankle'][k]:6.2f}")
    print("   the last row: the runner's largest stance dorsiflexion")
    for knee in (20.0, 40.0):
        for ankle in (22.0, 30.0, 35.0):
            angles = np.radians([20.0, knee, ankle])
            out = []
            for i in index:
                for f in (0.0, 1.0):
                    out.append(float(hill.fibre_state(leg, angles, np.zeros(3), ca.DM(np.full(len(leg.names), f)), 0.0)[0][i]))
            print(f"   model, hip 20, knee {knee:g}, ankle {ankle:g} deg: soleus l~ {out[0]:.3f} / {out[1]:.3f}, "
                  f"gastrocnemius {out[2]:.3f} / {out[3]:.3f} (F = 0 / 1)")
    print("   the active force-length f_L = exp(-((l~ - 1)/w)^2), w: "
          + ", ".join(f"{m} {leg.width[i]:.3f}" for m, i in zip(PLANTARFLEXORS, index))
          + "; the parallel element from l~ = " + ", ".join(f"{leg.passive_slack[i]:.2f}" for i in index))


def relaxed(body) -> None:
    """The relaxed ankle's plantarflexion moment (N m): the model's muscles and wall against
    Riener & Edrich's measured one, the hip at 20 deg."""
    leg = body_muscles(body)
    angles = (10.0, 20.0, 25.0, 30.0, 35.0)
    print("\nrelaxed ankle, plantarflexion moment N m at " + ", ".join(f"{a:g}" for a in angles) + " deg of dorsiflexion:")
    for knee in (0.0, 20.0, 50.0):
        muscle = [float(hill.joint_moments(leg, hill.isometric_force(leg, np.full(len(leg.names), 0.01),
                                                                     np.radians([20.0, knee, a])))[2]) for a in angles]
        wall = [-float(joint_space.range_wall(math.radians(a), *joint_space.RANGES["ankle"])) for a in angles]
        measured = [-float(joint_space.passive_moments(np.radians([20.0, knee, a]))[2]) for a in angles]
        print(f"   knee {knee:4.0f} deg: model's muscles " + " ".join(f"{m:5.1f}" for m in muscle)
              + " | wall " + " ".join(f"{w:4.1f}" for w in wall)
              + " | Riener & Edrich " + " ".join(f"{m:5.1f}" for m in measured))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--dorsiflexion", type=float, help="deg: the ankle's range's end (a what-if; 30)")
    parser.add_argument("--wall", choices=("formopt", "anderson-pandy"), default="formopt",
                        help="the ankle's range wall (a what-if: anderson-pandy)")
    parser.add_argument("--width", nargs="*", default=[], help="muscle=w: its force-length width (a what-if)")
    parser.add_argument("--strike", default="heel", choices=STRIKES, help="the scene's strike (a what-if)")
    only = parser.add_mutually_exclusive_group()
    only.add_argument("--brief", action="store_true", help="the solve's one-line summary alone")
    only.add_argument("--no-solve", action="store_true", help="the runner's lengths and the relaxed ankle alone")
    args = parser.parse_args(argv)
    if args.dorsiflexion is not None:  # a what-if: this process's ranges, read when the NLP is built
        joint_space.RANGES["ankle"] = (joint_space.RANGES["ankle"][0], math.radians(args.dorsiflexion))
    if args.wall == "anderson-pandy":  # a what-if: JointSpace reads range_wall when built
        joint_space.range_wall = anderson_pandy(joint_space.range_wall)
    scene = load(SCENE)
    if args.width:
        scene = dataclasses.replace(scene, settings=dataclasses.replace(
            scene.settings, muscles=what_if(scene.settings.muscles, args.width, "width", "--width", False)))
    if not args.no_solve:
        nlp = scene.nlp(args.strike)
        stride = optimum(nlp, args.speed, scene.slope, scene.friction, starts=scene.starts)
        if not args.brief:
            stance_table(nlp, stride)
        summary(nlp, stride)
        if args.brief:
            return 0
    runner_lengths(scene.body, args.speed)
    relaxed(scene.body)
    return 0


if __name__ == "__main__":
    sys.exit(main())
