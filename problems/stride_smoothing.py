"""The smoothing term's share of the stride's objective per mesh (issue 34's N against 2N): RBDS001's
body (62 kg, 1.81 m), heel strike, torque+springs (problem.RUNNER_TENDONS), effort, one start
(optim.stride.optimum) at an imposed cadence, so every mesh solves the same stride.

    python problems/stride_smoothing.py [--speed 3.5] [--cadence 130] [--clearance 0.01]
                                        [--meshes trapezoid:40 hermite-simpson:20 trapezoid:80]

Prints per mesh (`--meshes`, transcription:intervals; default trapezoid 40, Hermite-Simpson 20,
trapezoid 80): the objective as IPOPT sees it,
the smoothing term (problem.SMOOTHING times the transcription's sum, collocation; per distance) and its
share (%).
`--clearance` (m): the swing foot's least height (StrideSettings.clearance; docs/concepts/stride.md's
figures: 0, measured before it existed).
"""

from __future__ import annotations

import argparse
import sys

import casadi as ca

from formopt.mechanics.body import scaled_body
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.ocp import step_length
from formopt.optim.stride.problem import RUNNER_TENDONS, SMOOTHING, StrideSettings

MESHES = (("trapezoid", 40), ("hermite-simpson", 20), ("trapezoid", 80))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--cadence", type=float, default=130.0)
    parser.add_argument("--clearance", type=float, default=StrideSettings.clearance)
    parser.add_argument("--meshes", nargs="+", default=[f"{t}:{n}" for t, n in MESHES],
                        help="transcription:intervals, e.g. hermite-simpson:40")
    args = parser.parse_args(argv)
    body = scaled_body(62.0, 1.81)
    print(f"{'mesh':>20s} {'objective':>9s} {'smoothing':>9s} {'share %':>7s} converged", flush=True)
    for transcription, nodes in ((m.split(":")[0], int(m.split(":")[1])) for m in args.meshes):
        nlp = build(body, StrideSettings(strike="heel", nodes=nodes, tendons=dict(RUNNER_TENDONS),
                                         transcription=transcription, clearance=args.clearance))
        stride = optimum(nlp, args.speed, cadence=args.cadence, simulate=False)
        term = ca.Function("smoothing", [nlp.blocks.vector(), nlp.p],
                           [SMOOTHING * nlp.integral("smoothing") / step_length(nlp.p[0], nlp.period)])
        value = float(term(stride.solved.x, [args.speed, 0.0, 0.8]))
        print(f"{transcription + ' ' + str(nodes):>20s} {stride.objective_value:9.4f} {value:9.4f} "
              f"{value / stride.objective_value * 100:7.1f} {stride.success}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
