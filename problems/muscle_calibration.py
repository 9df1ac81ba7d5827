"""Calibrate the muscles' one cost weight (issue 33): the free cadence of RBDS001's body (heel,
the muscles' "metabolic" objective) against the weight, bisected on the weight until the
cadence lands within --tolerance of the runner's.

    python problems/muscle_calibration.py [--speed 3.5] [--target 171.4] [--weights 16 32 64 80]
                                          [--steps 4] [--tolerance 2] [--nodes 24] [--mass 62]
                                          [--power 1] [--transcription hermite-simpson]

The --weights are solved first (the first from the generic start, local.optimum's; each next
from the solution of the nearest weight solved, its blocks as the guess); then, while a lower
and a higher weight bracket the target, the geometric mean of the bracket, warm started from
the nearer of the two (at most --steps solves). Prints per solve: weight, cadence (steps/min),
stance (s), peak vertical force (N/kg), the muscles' energy (J/kg/m), reserves (N m/kg, their
largest 10 ms mean), the objective, validity, iterations, CPU seconds (time.process_time) and the
phases on a duration bound (bounds.on_bounds: low or high). With `--transcription
hermite-simpson`, --nodes are its intervals.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import replace

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import GRAVITY
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import FORCE_RATE_POWERS, RESERVE_WEIGHT, TRANSCRIPTIONS, StrideSettings


def log_weight(weight: float) -> float:
    """log(1 + w): the scale the weights are compared and bisected on."""
    return math.log1p(weight)


def solve(body, base: StrideSettings, weight: float, speed: float, guess):
    """The free optimum at `weight` from `guess` (None: the generic start), and its line."""
    clock = time.process_time()
    nlp = build(body, replace(base, force_rate_weight=weight))
    stride = optimum(nlp, speed, guess=guess)
    energy = stride.muscles["metabolic_J"] / (nlp.mass * stride.step_length_m)
    print(f"{weight:8.3f} {stride.cadence_spm:7.1f} {stride.stance_s:6.3f} {stride.peak_vertical_grf_bw * GRAVITY:6.1f}"
          f" {energy:6.2f} {stride.muscles['reserve_nm_per_kg']:5.2f} {stride.objective_value:7.4f}"
          f" {'yes' if stride.valid else 'NO':>5s} {stride.iterations:5d} {time.process_time() - clock:6.1f}"
          f" {' '.join(b['phase'] + ' ' + b['side'] for b in stride.on_bound)}", flush=True)
    return stride


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--target", type=float, default=171.4)
    parser.add_argument("--weights", type=float, nargs="+", default=[16.0, 32.0, 64.0, 80.0])
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--tolerance", type=float, default=2.0)
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--reserve-weight", type=float, default=RESERVE_WEIGHT)
    parser.add_argument("--power", type=int, default=2, choices=FORCE_RATE_POWERS, help="the force-rate term's power")
    parser.add_argument("--transcription", default="trapezoid", choices=TRANSCRIPTIONS)
    args = parser.parse_args(argv)
    body = scaled_body(args.mass, 1.81)
    base = StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic", muscles=body_muscles(body),
                          reserve_weight=args.reserve_weight, force_rate_power=args.power,
                          transcription=args.transcription)
    print(f"{args.mass:g} kg, 1.81 m, heel, {args.nodes} {'intervals ' if args.transcription != 'trapezoid' else 'nodes'}"
          f"{args.transcription if args.transcription != 'trapezoid' else ''}, {args.speed} m/s, target {args.target} steps/min, "
          f"reserve weight {args.reserve_weight:g}, force-rate power {args.power}")
    print(f"{'weight':>8s} {'spm':>7s} {'stance':>6s} {'GRF':>6s} {'J/kg/m':>6s} {'res':>5s} {'J':>7s} {'valid':>5s}"
          f" {'iter':>5s} {'cpu s':>6s} on a bound", flush=True)
    solved: dict[float, object] = {}

    def nearest(weight):
        return solved[min(solved, key=lambda w: abs(log_weight(w) - log_weight(weight)))].solved.blocks if solved else None

    for weight in args.weights:
        solved[weight] = solve(body, base, weight, args.speed, nearest(weight))
    for _ in range(args.steps):
        low = [w for w, s in solved.items() if s.cadence_spm > args.target]
        high = [w for w, s in solved.items() if s.cadence_spm <= args.target]
        if not low or not high or min(abs(s.cadence_spm - args.target) for s in solved.values()) <= args.tolerance:
            break
        weight = math.expm1(0.5 * (log_weight(max(low)) + log_weight(min(high))))
        solved[weight] = solve(body, base, weight, args.speed, nearest(weight))
    return 0


if __name__ == "__main__":
    sys.exit(main())
