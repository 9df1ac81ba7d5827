"""The global search's answer against its spend and its mesh (issue 34): RBDS001's body (62 kg,
1.81 m), torque+springs (problem.RUNNER_TENDONS), effort objective, or with `--actuation muscles`
the muscle rung (io.muscle_table.body_muscles, "metabolic" objective, the default force-rate and
reserve weights, as problems/stride_ladder.py builds it), the free optimum found by
optim.stride.search at each speed, spend and node count.

    python problems/stride_search.py [--speeds 2.5 3.5 4.5] [--nodes 40] [--spend 1 2]
                                     [--strike heel] [--transcription trapezoid] [--starts 1 4]
                                     [--clearance 0.01] [--actuation torque+springs|muscles]
                                     [--tendons knee=0 (stride_mesh.py's: over RUNNER_TENDONS)]
                                     [--impact-weight 1 (1/m: StrideSettings.impact_weight)]
                                     [--approach-speed 0.05 (m/s: StrideSettings.approach_speed)]
                                     [--moment-time 0.012 (s: StrideSettings.moment_time)]
                                     [--torque-velocity (StrideSettings.torque_velocity)]
                                     [--state-rate 30 --acceleration 3000 (rad/s, rad/s^2:
                                      collocation.STATE_RATE and ACCELERATION, for this run)]

One row per speed, node count and spend (the spends innermost, then the node counts): cost
(the objective, per distance), cadence (steps/min), their change (%) from the row before at the
same speed (doubling the spend, or the nodes when --nodes gives two counts), solves, IPOPT
iterations and seconds spent, the distinct local optima met (cadence:objective; an invalid one
with its failed checks) and their spread (%), validity, the held contact points' drift (mm) and
the energy budget's balance (% of W+), the stance knee's deepest flexion (deg), the impacts' T_c (J), the forward simulation's largest error per phase (rad,
each phase from the NLP's state at its start), any phase on its duration bound and the grid's
least objective per cadence (cadence=objective), each forward-checked (an invalid one with its
failed checks). `--starts` adds, first, the local search's optimum with each
number of starts (optim.stride.optimum: the generic guess and seeded perturbations of it), for
comparison. `--clearance` (m): the swing foot's least height (StrideSettings.clearance); the
tables of docs/concepts/stride.md were measured before it existed, as `--clearance 0`. Each
row ends with the CPU seconds of its search (time.process_time, this process's cores together).
"""

from __future__ import annotations

import argparse
import sys
import time

from stride_mesh import tendon

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.optim.stride import collocation, problem
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import RUNNER_TENDONS, StrideSettings
from formopt.optim.stride.search import global_optimum


def row(label: str, speed: float, nodes: int, stride, before, spent: dict | None = None) -> str:
    """One table row; `before`: the row's stride to measure the change from (None: none);
    `spent`: a local search's solves and seconds (its iterations: the kept solve's)."""
    change = ("    -        -   " if before is None else
              f"{(stride.objective_value / before.objective_value - 1) * 100:+7.2f} "
              f"{(stride.cadence_spm / before.cadence_spm - 1) * 100:+7.2f}  ")
    s = stride.search or {**(spent or {}), "iterations": stride.iterations, "optima": [], "spread_pct": float("nan")}
    optima = " ".join(f"{o['cadence_spm']:.0f}:{o['objective']:.4f}"
                      + ("" if o["valid"] else f"(invalid: {'; '.join(o['failed'])})") for o in s["optima"])
    checked = zip(s.get("grid_spm", []), s.get("grid_objective", []), s.get("grid_valid", []),
                  s.get("grid_failed", []))
    profile = " ".join(f"{c:.0f}={'-' if v is None else f'{v:.4f}'}"
                       + ("" if ok is not False else f"(invalid: {'; '.join(failed)})") for c, v, ok, failed in checked)
    phases = " ".join(f"{e:.3f}" for e in stride.checks.get("forward_per_phase", []))
    bound = "; ".join(f"{b['phase']} {b['side']}" for b in stride.on_bound) or "-"
    drift, balance = stride.checks["drift_m"] * 1e3, stride.checks["balance_relative"] * 100
    return (f"{speed:4.1f} {nodes:5d} {label:>6s} {stride.objective_value:8.4f} {stride.cadence_spm:7.1f} {change}"
            f"{s['solves']:6d} {s['iterations']:6d} {s['seconds']:7.1f} {s['spread_pct']:7.2f}  "
            f"{'yes' if stride.valid else 'NO':>5s} {drift:8.3f} {balance:9.2e} {stride.stance_knee_deg:5.1f} {stride.budget['impacts_J']:6.2f}  [{phases}]  {bound}  "
            f"{{{optima}}}  grid {profile or '-'}")


def parse(argv) -> argparse.Namespace:
    """The command line (module docstring); the rates' and accelerations' bounds set for the run."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[2.5, 3.5, 4.5])
    parser.add_argument("--nodes", type=int, nargs="+", default=[40])
    parser.add_argument("--spend", type=int, nargs="*", default=[1, 2])
    parser.add_argument("--strike", default="heel", choices=problem.STRIKES)
    parser.add_argument("--transcription", default="trapezoid", choices=problem.TRANSCRIPTIONS)
    parser.add_argument("--starts", type=int, nargs="*", default=[])
    parser.add_argument("--clearance", type=float, default=StrideSettings.clearance)
    parser.add_argument("--tendons", nargs="*", default=[], type=tendon)
    parser.add_argument("--impact-weight", type=float, default=0.0, help="StrideSettings.impact_weight (1/m)")
    parser.add_argument("--approach-speed", type=float, default=0.0, help="StrideSettings.approach_speed (m/s)")
    parser.add_argument("--moment-time", type=float, default=0.0, help="StrideSettings.moment_time (s)")
    parser.add_argument("--torque-velocity", action="store_true", help="StrideSettings.torque_velocity")
    parser.add_argument("--state-rate", type=float, default=collocation.STATE_RATE,
                        help="the rates' bound (rad/s, collocation.STATE_RATE) for this run")
    parser.add_argument("--acceleration", type=float, default=collocation.ACCELERATION,
                        help="the accelerations' bound (rad/s^2, collocation.ACCELERATION) for this run")
    parser.add_argument("--actuation", default="torque+springs", choices=("torque+springs", "muscles"))
    args = parser.parse_args(argv)
    collocation.STATE_RATE, collocation.ACCELERATION = args.state_rate, args.acceleration
    if args.tendons and args.actuation == "muscles":
        parser.error("--tendons: springs in parallel are the torque rung's; the muscles' tendons are in series")
    if args.torque_velocity and args.actuation == "muscles":
        parser.error("--torque-velocity: the torque rung's limit; the muscles' force-velocity is their own")
    return args


def main(argv=None) -> int:
    args = parse(argv)
    body = scaled_body(62.0, 1.81)
    actuation = ({"muscles": body_muscles(body), "objective": "metabolic"} if args.actuation == "muscles"
                 else {"tendons": {**RUNNER_TENDONS, **dict(args.tendons)}})
    model = StrideSettings(impact_weight=args.impact_weight, approach_speed=args.approach_speed,
                           moment_time=args.moment_time, torque_velocity=args.torque_velocity, **actuation)
    rung = ("muscles, metabolic" if args.actuation == "muscles" else
            f"{model.actuation} {({j: k for j, k in model.tendons.items() if k})}, effort, "
            f"impact weight {args.impact_weight:g}, approach speed {args.approach_speed:g} m/s, "
            f"moment time {args.moment_time:g} s, torque-velocity {args.torque_velocity}, rate bound "
            f"{args.state_rate:g} rad/s, acceleration bound {args.acceleration:g} rad/s^2")
    print(f"RBDS001's body (62 kg, 1.81 m), {args.strike} strike, "
          f"{rung}, {args.transcription}, "
          f"swing clearance {args.clearance:g} m",
          flush=True)
    print(f"{'v':>4s} {'nodes':>5s} {'spend':>6s} {'cost':>8s} {'spm':>7s} {'dcost%':>7s} {'dspm%':>7s}  "
          f"{'solves':>6s} {'iter':>6s} {'s':>7s} {'spread%':>7s}  {'valid':>5s} {'drift mm':>8s} {'balance%':>9s} {'knee':>5s} {'T_c J':>6s}  "
          "[forward rad per phase]  "
          "on bound  {optima cadence:cost}  grid cadence=cost  cpu s", flush=True)
    for speed in args.speeds:
        before = None
        for nodes in args.nodes:
            settings = StrideSettings(strike=args.strike, nodes=nodes, transcription=args.transcription,
                                      clearance=args.clearance, impact_weight=args.impact_weight,
                                      approach_speed=args.approach_speed, moment_time=args.moment_time,
                                      torque_velocity=args.torque_velocity,
                                      **actuation)
            nlp = build(body, settings)
            for starts in args.starts:
                clock, cpu = time.perf_counter(), time.process_time()
                local = optimum(nlp, speed, starts=starts)
                spent = {"solves": starts, "seconds": time.perf_counter() - clock}
                print(row(f"s{starts}", speed, nodes, local, None, spent) + f"  cpu {time.process_time() - cpu:.1f}",
                      flush=True)
            for spend in args.spend:
                cpu = time.process_time()
                stride = global_optimum(nlp, speed, spend=spend, check_grid=True)
                print(row(str(spend), speed, nodes, stride, before) + f"  cpu {time.process_time() - cpu:.1f}",
                      flush=True)
                before = stride
    return 0


if __name__ == "__main__":
    sys.exit(main())
