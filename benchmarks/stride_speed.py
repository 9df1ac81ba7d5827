"""The half stride's speed beside the peer's (issue 23 item 8, issue 34 item 5), in one run.

    python benchmarks/stride_speed.py [--repeats N] [--peer VENV | --no-peer]

formopt: the paper's body, heel strike, 40 nodes, 3.0 m/s, `effort` (the torque stride): build
(the NLP's graph, IPOPT and its derivatives), cold (from the generic guess) and warm (3.1 m/s
from the 3.0 m/s optimum), each the median of N repeats (default 3) of wall and CPU seconds,
with IPOPT's iterations and the cadence. Issue 34's targets: cold <= 1 s and warm <= 0.2 s of
CPU. The peer: opty's human-gait example on gait2d (torque-driven, planar, 3 m/s, 40 nodes,
smooth contact; ../shared/peers/opty_gait2d), run cold (its zero guess) and warm (its shipped
solution) by its run_peer.py in the venv that its install.sh makes (`--peer VENV`, else the
environment variable FORMOPT_PEER_VENV), a subprocess each, medians of the same N repeats. Without
that venv the peer's rows are skipped with the command that makes it. Measure only: neither side
is tuned here.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import time
from pathlib import Path

from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.checks import half_period
from formopt.optim.stride.guess import ballistic

PEER = Path(__file__).resolve().parents[2] / "shared" / "peers" / "opty_gait2d"
PEER_ENV = "FORMOPT_PEER_VENV"
TARGETS_CPU = {"cold": 1.0, "warm": 0.2}  # s of CPU (issue 34 item 5)


def cpu(children: bool = False) -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN if children else resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def timed(run):
    """(result, wall s, CPU s) of run()."""
    wall, used = time.perf_counter(), cpu()
    out = run()
    return out, time.perf_counter() - wall, cpu() - used


def formopt_once(speed=3.0, nodes=40) -> dict:
    """One build, cold and warm solve (wall and CPU seconds, iterations, status, cadence)."""
    def build():
        nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=nodes))
        assert nlp.solver is not None  # the whole build: graph, IPOPT and its derivatives
        return nlp
    nlp, build_s, build_cpu = timed(build)
    cold, cold_s, cold_cpu = timed(lambda: nlp.solve(ballistic(nlp, speed), speed))
    warm, warm_s, warm_cpu = timed(lambda: nlp.solve(cold.blocks, speed + 0.1))
    return {"build_s": build_s, "build_cpu": build_cpu, "cold_s": cold_s, "cold_cpu": cold_cpu,
            "cold_iterations": cold.iterations, "cold_status": cold.status, "warm_s": warm_s,
            "warm_cpu": warm_cpu, "warm_iterations": warm.iterations, "warm_status": warm.status,
            "cadence_spm": 60.0 / half_period(nlp, cold.blocks)}


def peer_once(venv: Path, mode: str) -> dict:
    """run_peer.py `mode` in the peer's venv: its JSON line, with the subprocess's CPU seconds."""
    used = cpu(children=True)
    done = subprocess.run([str(venv / "bin" / "python"), str(PEER / "run_peer.py"), mode],
                          capture_output=True, text=True, env={**os.environ, "PYTHONPATH": str(PEER)})
    lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
    out = json.loads(lines[-1]) if lines else {"error": done.stderr.strip().splitlines()[-1:] or ["no output"]}
    return {**out, "process_cpu": cpu(children=True) - used}


def median(runs: list[dict], key: str):
    values = [r[key] for r in runs if isinstance(r.get(key), (int, float))]
    return statistics.median(values) if values else None


def peer_venv(given: str | None) -> Path | None:
    """The peer's venv (--peer, else $FORMOPT_PEER_VENV) when its python exists."""
    path = given or os.environ.get(PEER_ENV)
    return Path(path) if path and (Path(path) / "bin" / "python").exists() else None


def cell(value, width=9) -> str:
    return f"{value:{width}.2f}" if isinstance(value, (int, float)) else f"{'-':>{width}s}"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--peer", help=f"the peer's venv (default: ${PEER_ENV})")
    parser.add_argument("--no-peer", action="store_true")
    args = parser.parse_args()
    ours = [formopt_once() for _ in range(args.repeats)]
    print(f"medians of {args.repeats} repeats; wall s (CPU s)")
    print(f"{'':31s} {'build':>17s} {'cold':>17s} {'cold it':>8s} {'warm':>17s} {'warm it':>8s} {'cadence':>8s}")
    m = {k: median(ours, k) for k in ours[0]}
    print(f"{'formopt (heel, exact impacts)':31s} {cell(m['build_s'])} ({cell(m['build_cpu'], 5)}) "
          f"{cell(m['cold_s'])} ({cell(m['cold_cpu'], 5)}) {m['cold_iterations']:8.0f} "
          f"{cell(m['warm_s'])} ({cell(m['warm_cpu'], 5)}) {m['warm_iterations']:8.0f} {m['cadence_spm']:8.1f}"
          f"   cold: {ours[0]['cold_status']}, warm: {ours[0]['warm_status']}")
    print("targets (CPU): " + ", ".join(f"{k} <= {v:g} s: {'met' if m[f'{k}_cpu'] <= v else 'missed'}"
                                         for k, v in TARGETS_CPU.items()))
    venv = None if args.no_peer else peer_venv(args.peer)
    if venv is None:
        print("" if args.no_peer else f"the peer skipped: no venv at --peer or ${PEER_ENV} "
              f"(make one: bash {PEER}/install.sh VENV, needs root, about 2 minutes)")
        return 0
    runs = {mode: [peer_once(venv, mode) for _ in range(args.repeats)] for mode in ("cold", "warm")}
    cold, warm = ({k: median(r, k) for k in ("derive_s", "build_s", "solve_s", "cadence_spm", "process_cpu")}
                  for r in runs.values())
    status = {mode: r[0].get("status_msg", r[0].get("error")) for mode, r in runs.items()}
    print(f"{'opty + gait2d (smooth contact)':31s} {cell(cold['build_s'])} {'':7s} {cell(cold['solve_s'])} "
          f"{'':7s} {'-':>8s} {cell(warm['solve_s'])} {'':7s} {'-':>8s} {cell(warm['cadence_spm'], 8)}"
          f"   cold: {status['cold']}, warm: {status['warm']}")
    print(f"the peer's symbolic derivation {cell(cold['derive_s'], 5).strip()} s per run (before its build); its "
          f"process CPU per run: cold {cell(cold['process_cpu'], 5).strip()} s, warm {cell(warm['process_cpu'], 5).strip()} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
