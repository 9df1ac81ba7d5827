"""The actuation ladder's speed in one run (issue 33 item 6): torque, torque+springs and
muscles, the same body, strike, mesh and speed.

    python benchmarks/stride_muscles.py [--nodes 40] [--repeats 1] [--speed 3.5] [--compiled auto|true|false]
        [--rungs torque,torque+springs,muscles] [--ipopt JSON]

RBDS001's body (62 kg, 1.81 m), heel strike, each rung's default objective (effort; the
muscles' metabolic): build (the NLP's graph, IPOPT and its derivatives), cold (the torque rungs
from the generic guess; the muscles from their start, the torque+springs optimum split among
them, local.muscle_start, whose own solve is counted apart as `start`) and warm (speed + 0.1
m/s from the cold optimum with its multipliers, StrideNLP.resolve), medians of wall and CPU
seconds, IPOPT's iterations and the cadence; the NLPs' node models and derivatives compiled to C
or not (`--compiled`, StrideNLP's `compiled`: default true here, where StrideNLP's own is
collocation.COMPILED, "auto"; the libraries from the disk cache after a first build, which is
counted in build); `--rungs` a subset, `--ipopt` IPOPT options over collocation's
(e.g. '{"print_level": 7, "print_timing_statistics": "yes"}' for IPOPT's log). Issue 33's
targets for the muscles at 40 nodes: cold <= 30 s and warm <= 3 s on one core, judged on CPU
(user + system, the process's threads; cold counts the start's). Measure only.

Measured 2026-11-27 (2-core machine shared with two other helpers; one run each; CPU s, the
muscles' start + cold, then warm, with its iterations), before (main 4ed7000) and after:

| muscles, interpreted | 2.5 m/s | 3.5 m/s | 4.5 m/s |
| --- | --- | --- | --- |
| before | 96.8, 3.70 (23) | 96.0, 5.94 (56) | 118.5, 20.9 (181) |
| after, load 4-5 (warm from 1e-4) | 40.4, 1.63 (23) | 29.6, 1.97 (27) | 38.5, 8.12 (116) |
| after, load about 2 | 29.6, 1.68 (32) | 23.8, 1.41 (28) | 29.7, 1.54 (31) |

the same optima (172.0 / 177.8 / 192.0 steps/min); compiled at 3.5 m/s (`--compiled true
--rungs muscles`, its libraries built once, 55 s): 16.9 and 0.72 s. The torque rungs' rows
unchanged (217.2 and 169.5 steps/min in 183 and 79 iterations). What moved it (collocation.py):
MUMPS's workspace 100 % over its estimate instead of IPOPT's 1000 % (a 77 MB block mapped afresh
at each factorisation: a third of the CPU was system time), CasADi's OpenBLAS on one thread
(its second thread spun), METIS's ordering for the muscles' KKT matrix, the start's solve at
reserve weight 100 from a barrier of 1e-3 (CONTINUATION_IPOPT) and the muscles' warm start
from 3e-4 (MUSCLE_WARM_START).
"""

from __future__ import annotations

import argparse
import json
import statistics
from dataclasses import replace

from stride_speed import cell, timed

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.checks import half_period
from formopt.optim.stride.guess import ballistic
from formopt.optim.stride.local import muscle_start
from formopt.optim.stride.problem import RUNNER_TENDONS

TARGETS = {"cold": 30.0, "warm": 3.0}  # s, the muscles at 40 nodes (issue 33 item 6)


def rung_settings(rung: str, body, nodes: int) -> StrideSettings:
    base = StrideSettings(strike="heel", nodes=nodes)
    return {"torque": base, "torque+springs": replace(base, tendons=dict(RUNNER_TENDONS)),
            "muscles": replace(base, objective="metabolic", muscles=body_muscles(body))}[rung]


def once(rung: str, body, nodes: int, speed: float, compiled: bool | str, ipopt: dict | None = None) -> dict:
    def build():
        nlp = StrideNLP(JointSpace(body), rung_settings(rung, body, nodes), ipopt, compiled)
        assert nlp.solver is not None
        return nlp
    nlp, build_s, build_cpu = timed(build)
    start, start_s, start_cpu = timed(lambda: muscle_start(nlp, speed, 0.0, 0.8, None) if rung == "muscles"
                                      else ballistic(nlp, speed))
    cold, cold_s, cold_cpu = timed(lambda: nlp.solve(start, speed))
    warm, warm_s, warm_cpu = timed(lambda: nlp.resolve(cold, speed + 0.1))
    return {"build_s": build_s, "build_cpu": build_cpu, "start_s": start_s, "start_cpu": start_cpu, "cold_s": cold_s,
            "cold_cpu": cold_cpu, "cold_iterations": cold.iterations, "warm_s": warm_s, "warm_cpu": warm_cpu,
            "warm_iterations": warm.iterations, "cadence_spm": 60.0 / half_period(nlp, cold.blocks),
            "status": f"{cold.status} / {warm.status}"}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--nodes", type=int, default=40)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--compiled", choices=("auto", "true", "false"), default="true")
    parser.add_argument("--rungs", default="torque,torque+springs,muscles")
    parser.add_argument("--ipopt", type=json.loads, default=None, help="IPOPT options over the defaults (JSON)")
    args = parser.parse_args()
    compiled = {"true": True, "false": False}.get(args.compiled, "auto")
    body = scaled_body(62.0, 1.81)
    print(f"RBDS001's body, heel, {args.nodes} nodes, {args.speed:g} m/s, compiled {args.compiled}; "
          f"medians of {args.repeats}; wall s (CPU s)")
    print(f"{'rung':15s} {'build':>17s} {'start':>17s} {'cold':>17s} {'it':>5s} {'warm':>17s} {'it':>5s} {'cadence':>8s}")
    for rung in args.rungs.split(","):
        runs = [once(rung, body, args.nodes, args.speed, compiled, args.ipopt) for _ in range(args.repeats)]
        m = {k: statistics.median(r[k] for r in runs) for k in runs[0] if k != "status"}
        print(f"{rung:15s} {cell(m['build_s'])} ({cell(m['build_cpu'], 5)}) {cell(m['start_s'])} ({cell(m['start_cpu'], 5)}) "
              f"{cell(m['cold_s'])} ({cell(m['cold_cpu'], 5)}) {m['cold_iterations']:5.0f} "
              f"{cell(m['warm_s'])} ({cell(m['warm_cpu'], 5)}) {m['warm_iterations']:5.0f} {m['cadence_spm']:8.1f}"
              f"   {runs[0]['status']}", flush=True)
        if rung == "muscles":
            print("targets (CPU, one core): " + ", ".join(
                f"{k} <= {v:g} s: {'met' if m[f'{k}_cpu'] + (m['start_cpu'] if k == 'cold' else 0) <= v else 'missed'}"
                for k, v in TARGETS.items()) + f" (cold counts the start: {m['start_cpu'] + m['cold_cpu']:.1f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
