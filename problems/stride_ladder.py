"""The actuation ladder on RBDS001 (issue 33): torque, torque+springs and muscles, each at the
runner's speeds, against the runner's processed mean cycle (its joint powers the data set's) and measured cadence.

    python problems/stride_ladder.py [--speeds 2.5 3.5 4.5] [--rungs torque torque+springs muscles]
                                     [--strike heel] [--nodes 40] [--mass 62] [--start-mass M] [--start-speed S]
                                     [--weight W] [--reserve-weight R]
                                     [--objectives effort] [--cadences 150 171.4] [--starts 1]

Prints per rung and speed: cadence (steps/min; measured 156.5 at 2.5 and 171.4 at 3.5 m/s,
runners choose about 175-183 at 4.5), stance (s), peak vertical force (N/kg), the joint angles'
RMS against the mean cycle (deg) and their RMS with the mean offset removed (`Sh`: the data
set's hip is against the pelvis, formopt's against the trunk; studies.stride.compare_cycle),
the peak ankle power (W/kg, positive), the tendons' energy stored per step (J: soleus and
gastrocnemius, all), reserves (N m/kg, their largest 10 ms mean), the muscles' metabolic energy
(J/kg/m), the swing foot's least height (m, while
the other foot is down: Stride.swing_clearance_m), the stance ankle's largest dorsiflexion (deg,
`ankDF`), the objective J (per distance), validity,
iterations and seconds (build, solve), and the phases a duration bound holds; for the muscles
last their forward check (rad, the excitations replayed through the muscles: the validity's) and
their net joint moments replayed (checks.forward's `moments_reset_theta`: a figure).
`--mass` scales the body to another mass at the same height (a heavier runner), `--start-mass`
and `--start-speed` start each solve from the optimum of the body at that mass and speed (a
continuation in one step; the other from --mass and the speed solved); `--weight`
sets the muscles' force-rate weight (StrideSettings.force_rate_weight) for a calibration run,
`--reserve-weight` their reserves' (StrideSettings.reserve_weight; the muscles' start continues
to it from problem.RESERVE_CONTINUATION's weights below it) for a what-if;
`--objectives` the torque rungs' objectives (problem.OBJECTIVES; the muscles keep "metabolic"), each
solved in turn; `--cadences` imposes each cadence (steps/min) in turn instead of leaving it free;
`--starts` the generic guess and starts - 1 seeded perturbations of it, the best kept (local.optimum).
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.optim.stride import problem
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import RUNNER_TENDONS, StrideSettings
from formopt.studies.stride import compare_cycle, measured_cycle, predicted_cycle

RBDS = Path(__file__).resolve().parents[1] / "data" / "rbds" / "RBDS001processed.txt"
MEASURED_CADENCE = {2.5: 156.5, 3.5: 171.4}  # steps/min, RBDS001's trials (formopt compare)
# the cadence that times the mean cycle's stance: at 4.5 m/s, with no trial
# of RBDS001's, the middle of the 175-183 steps/min runners choose there
CYCLE_CADENCE = {**MEASURED_CADENCE, 4.5: 179.0}


def settings(rung: str, body, strike: str, nodes: int, weight: float, objective: str = "effort",
             reserve_weight: float = problem.RESERVE_WEIGHT) -> StrideSettings:
    base = StrideSettings(strike=strike, nodes=nodes, objective=objective)
    if rung == "torque+springs":
        return replace(base, tendons=dict(RUNNER_TENDONS))
    if rung == "muscles":
        return replace(base, objective="metabolic", muscles=body_muscles(body), force_rate_weight=weight,
                       reserve_weight=reserve_weight)
    return base


def header(first: str = "rung objective") -> str:
    """The columns `row` prints, `first` naming its first."""
    return (f"{first:30s} {'v':>4s} {'spm':>7s} {'meas':>6s} {'stance':>6s} {'GRF':>6s} {'m.st':>6s} {'m.GRF':>6s}"
            f" {'hipRMS':>5s} {'knRMS':>5s} {'anRMS':>5s} {'hipSh':>5s} {'knSh':>5s} {'anSh':>5s} {'P+ank':>5s} {'m.P+':>5s} {'Ach J':>5s} {'all J':>5s}"
            f" {'res':>5s} {'E/kg/m':>6s} {'ankDF':>5s} {'swing':>6s} {'J':>6s} {'valid':>5s} {'iter':>5s} {'build':>5s} {'solve':>6s}")


def row(rung, speed, stride, measured) -> str:
    rung = f"{rung} {stride.objective}"
    cycle = compare_cycle(stride, measured) if measured else None
    pred = predicted_cycle(stride)
    power = float(np.max(pred["powers"]["ankle"]))
    swing = stride.swing_clearance_m
    text = (f"{rung:30s} {speed:4.1f} {stride.cadence_spm:7.1f} {MEASURED_CADENCE.get(speed, float('nan')):6.1f} "
            f"{stride.stance_s:6.3f} {stride.peak_vertical_grf_bw * 9.81:6.1f}")
    if cycle:
        rms = cycle["angle_rms_deg"]
        measured_stance = cycle["stance_share_measured"] * 120.0 / CYCLE_CADENCE[speed]
        m_power = float(np.nanmax(measured["powers"]["ankle"]))  # the data set's own joint power
        text += (f" {measured_stance:6.3f} {cycle['peak_vertical_n_per_kg']['measured']:6.1f}"
                 f" {rms['hip']:5.1f} {rms['knee']:5.1f} {rms['ankle']:5.1f}"
                 + "".join(f" {cycle['angle_rms_shape_deg'][j]:5.1f}" for j in ("hip", "knee", "ankle"))
                 + f" {power:5.1f} {m_power:5.1f}")
    m = stride.muscles
    energy = m["metabolic_J"] / (stride.mass_kg * stride.step_length_m) if m else float("nan")
    tendons = (f"{m['achilles_stored_J']:5.1f} {m['tendon_stored_J']:5.1f} {m['reserve_nm_per_kg']:5.2f} {energy:6.2f}"
               if m else " " * 24)
    return (text + f" {tendons} {peak_dorsiflexion(stride):5.1f} {swing:6.3f} {stride.objective_value:6.4f} {'yes' if stride.valid else 'NO':>5s}"
            f" {stride.iterations:5d} {stride.build_s:5.1f} {stride.solve_s:6.1f}"
            + ("" if stride.valid else f"  ({'; '.join(stride.failed_checks) or stride.status})")
            + (f"  [{stride.bound_text()}]" if stride.on_bound else ""))


def peak_dorsiflexion(stride) -> float:
    """The stance ankle's largest dorsiflexion (deg) while it holds the ground (the runner's:
    22 deg at 3.5 m/s, RBDS001's mean cycle)."""
    stance = [k for k, name in enumerate(stride.phase) if name != "flight"]
    return float(np.degrees(stride.theta[stance, 5].max()))


def moments_replayed(stride) -> str:
    """A muscle stride's net joint moments replayed (rad; its forward check, the validity's,
    replays the excitations)."""
    return (f"  forward {stride.checks['forward_theta']:.3f} rad, moments replayed "
            f"{stride.checks['forward_moments_reset_theta']:.3f} rad")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[2.5, 3.5, 4.5])
    parser.add_argument("--rungs", nargs="+", default=list(problem.ACTUATIONS), choices=problem.ACTUATIONS)
    parser.add_argument("--strike", default="heel", choices=problem.STRIKES)
    parser.add_argument("--nodes", type=int, default=40)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--start-mass", type=float, default=None)
    parser.add_argument("--start-speed", type=float, default=None)
    parser.add_argument("--weight", type=float, default=None)
    parser.add_argument("--reserve-weight", type=float, default=problem.RESERVE_WEIGHT)
    parser.add_argument("--objectives", nargs="+", default=["effort"],
                        choices=[o for o in problem.OBJECTIVES if o != "activation"])
    parser.add_argument("--cadences", type=float, nargs="+", default=[None])
    parser.add_argument("--starts", type=int, default=1)
    args = parser.parse_args(argv)
    weight = problem.FORCE_RATE_WEIGHT if args.weight is None else args.weight
    body = scaled_body(args.mass, 1.81)
    print(f"RBDS001's height (1.81 m), {args.mass:g} kg, {args.strike} strike, {args.nodes} nodes, {args.starts} start(s), "
          f"force-rate weight {weight:g}, reserve weight {args.reserve_weight:g}", flush=True)
    print(header(), flush=True)
    runs = [(rung, objective) for rung in args.rungs
            for objective in (["metabolic"] if rung == "muscles" else args.objectives)]
    for rung, objective in runs:
        for speed in args.speeds:
            for cadence in args.cadences:
                clock = time.perf_counter()
                nlp = build(body, settings(rung, body, args.strike, args.nodes, weight, objective, args.reserve_weight))
                guess = None
                if args.start_mass is not None or args.start_speed is not None:
                    other = scaled_body(args.start_mass or args.mass, 1.81)
                    first = build(other, settings(rung, other, args.strike, args.nodes, weight, objective, args.reserve_weight))
                    guess = optimum(first, args.start_speed or speed, cadence=cadence, simulate=False).solved.blocks
                stride = optimum(nlp, speed, cadence=cadence, guess=guess, starts=args.starts)
                stride.solve_s = time.perf_counter() - clock - nlp.build_s  # the starts' solves too
                print(row(rung, speed, stride, measured_cycle(RBDS, speed))
                      + (moments_replayed(stride) if rung == "muscles" else ""), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
