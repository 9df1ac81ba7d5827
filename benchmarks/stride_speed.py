"""The half stride's speed beside the peer's (issue 23 item 8), in one run.

    python benchmarks/stride_speed.py [--peer-venv DIR] [--no-peer]

formopt: the paper's body, heel strike, 40 nodes, 3.0 m/s, `effort`: build (the NLP's graph,
IPOPT and its derivatives), cold (from the generic guess) and warm (3.1 m/s from the 3.0 m/s optimum) seconds,
IPOPT iterations, cadence. Targets: build <= 5 s, cold <= 10 s, warm <= 1 s on one core.
The peer: opty's human-gait example on gait2d (../shared/peers/opty_gait2d, installed outside
the repository by its install.sh; default venv /work/wt/peer/.peer-venv), run cold (its zero
guess) and warm (its shipped solution) by its run_peer.py, in a subprocess each.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import time
from pathlib import Path

from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.checks import half_period
from formopt.optim.stride.guess import ballistic

PEER = Path(__file__).resolve().parents[2] / "shared" / "peers" / "opty_gait2d"
TARGETS = {"build_s": 5.0, "cold_s": 10.0, "warm_s": 1.0}


def formopt_side(speed=3.0, nodes=40) -> dict:
    start = time.perf_counter()
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=nodes))
    assert nlp.solver is not None  # the whole build: graph, IPOPT and its derivatives (built on first use)
    build = time.perf_counter() - start
    cold = nlp.solve(ballistic(nlp, speed), speed)
    warm = nlp.solve(cold.blocks, speed + 0.1)
    return {"build_s": build, "cold_s": cold.solve_s, "cold_iterations": cold.iterations,
            "cold_status": cold.status, "warm_s": warm.solve_s, "warm_iterations": warm.iterations,
            "warm_status": warm.status, "cadence_spm": 60.0 / half_period(nlp, cold.blocks)}


def peer_side(venv: Path) -> dict:
    out = {}
    for mode in ("cold", "warm"):
        done = subprocess.run([str(venv / "bin" / "python"), str(PEER / "run_peer.py"), mode],
                              capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(PEER)})
        lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
        out[mode] = json.loads(lines[-1]) if lines else {"error": done.stderr[-300:]}
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--peer-venv", default="/work/wt/peer/.peer-venv")
    parser.add_argument("--no-peer", action="store_true")
    args = parser.parse_args()
    ours = formopt_side()
    print(f"{'':28s} {'build s':>8s} {'cold s':>8s} {'cold it':>8s} {'warm s':>8s} {'warm it':>8s} {'cadence':>8s}")
    print(f"{'formopt (heel, exact impacts)':28s} {ours['build_s']:8.2f} {ours['cold_s']:8.2f} "
          f"{ours['cold_iterations']:8d} {ours['warm_s']:8.2f} {ours['warm_iterations']:8d} "
          f"{ours['cadence_spm']:8.1f}   cold: {ours['cold_status']}, warm: {ours['warm_status']}")
    print("targets: " + ", ".join(f"{k} <= {v:g}: {'met' if ours[k] <= v else 'missed'}"
                                   for k, v in TARGETS.items()))
    if not args.no_peer:
        peer = peer_side(Path(args.peer_venv))
        cold, warm = peer["cold"], peer["warm"]
        def fmt(d, k):
            return f"{d[k]:8.2f}" if isinstance(d.get(k), (int, float)) else f"{'-':>8s}"
        print(f"{'opty + gait2d (smooth contact)':28s} {fmt(cold, 'build_s')} {fmt(cold, 'solve_s')} "
              f"{'-':>8s} {fmt(warm, 'solve_s')} {'-':>8s} {fmt(warm, 'cadence_spm')}   "
              f"cold: {cold.get('status_msg', cold.get('error'))}, warm: {warm.get('status_msg', warm.get('error'))}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
