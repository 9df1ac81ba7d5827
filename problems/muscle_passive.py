"""What the joints' passive moments give and take in the muscle-driven stride, per joint: RBDS001's
body, heel strike, the muscles' defaults, the cadence free and then imposed (each imposed solve
warm from the free optimum). The muscle rung's joints feel the range walls alone
(actuation.MuscleDriven.joint_passive); `--riener-edrich` gives them Riener & Edrich (1999)'s
relaxed-leg moments as well, as before 2026-11-27 (docs/concepts/muscles.md's table: a what-if).

    python problems/muscle_passive.py [--speed 3.5] [--nodes 24] [--mass 62] [--cadences 171.4]
                                      [--riener-edrich]

Per stride: cadence (steps/min), objective, the budget's passive term (J, the work the passive
moments take over the half stride), and per joint (R the stance leg, L the swing leg) the energy
the passive moment gives to the body and takes from it (J per step: the integrals of the positive
and negative parts of tau_passive theta', the trapezoid on the stride's nodes) and its largest
|tau_passive| (N m). A conservative passive moment gives back over the periodic stride what it
took; what matters is where: taken in one leg's stance and given to the other's swing, it is a
spring that swings the leg for free.
"""

from __future__ import annotations

import argparse
import sys

import casadi as ca
import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JOINTS
from formopt.optim.stride.actuation import MuscleDriven, Torques
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import StrideSettings


def passive_energy(nlp, stride) -> list[tuple[str, float, float, float]]:
    """Per joint: (name, J given, J taken, largest |tau| N m) of the passive moments over the stride."""
    passive = nlp.ocp.models[0].actuation.joint_passive
    tau = np.array([np.asarray(passive(nlp.js, ca.DM(theta)), float).ravel() for theta in stride.theta])[:, 3:]
    power = tau * stride.thetad[:, 3:]  # W: the passive moments' power on the body
    given = np.trapezoid(np.maximum(power, 0.0), stride.t, axis=0)
    taken = np.trapezoid(np.maximum(-power, 0.0), stride.t, axis=0)
    return [(name, float(g), float(k), float(np.abs(t).max())) for name, g, k, t in zip(JOINTS, given, taken, tau.T)]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--cadences", type=float, nargs="*", default=[171.4])
    parser.add_argument("--riener-edrich", action="store_true",
                        help="the muscles' joints with Riener & Edrich's passive moments (a what-if)")
    args = parser.parse_args(argv)
    if args.riener_edrich:
        MuscleDriven.joint_passive = Torques.joint_passive
    body = scaled_body(args.mass, 1.81)
    nlp = build(body, StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic", muscles=body_muscles(body)))
    free = optimum(nlp, args.speed, simulate=False)
    strides = [free] + [optimum(nlp, args.speed, cadence=c, guess=free.solved.blocks, simulate=False)
                        for c in args.cadences]
    for stride in strides:
        print(f"\n{stride.cadence_spm:.1f} steps/min, objective {stride.objective_value:.3f}, "
              f"budget's passive {stride.budget['passive_J']:+.2f} J")
        for name, given, taken, peak in passive_energy(nlp, stride):
            print(f"  {name:8s} gives {given:5.1f} J, takes {taken:5.1f} J, largest {peak:5.1f} N m")
    return 0


if __name__ == "__main__":
    sys.exit(main())
