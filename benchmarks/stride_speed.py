"""The half stride's speed beside the peer's (issue 23 item 8, issue 34 item 5), in one run.

    python benchmarks/stride_speed.py [--repeats N] [--peer VENV | --no-peer] [--first-build]
        [--paths both|interpreted|compiled] [--ipopt JSON] [--same]

formopt: the paper's body, heel strike, 40 nodes, 3.0 m/s, `effort` (the torque stride), with its
node models and derivatives interpreted (CasADi's virtual machine) and compiled to C
(collocation.COMPILED, StrideNLP(compiled=True); `--paths` one of them): build (the NLP's graph,
IPOPT and its derivatives; the compiled libraries from the disk cache; `--first-build` times
them into a fresh cache first, the C compiler's CPU included), cold (from the generic guess), warm
(3.1 m/s from the 3.0 m/s optimum's primal values, StrideNLP.solve) and resolve (the same from
its primal and dual values, StrideNLP.resolve: IPOPT's warm start), each the median of N repeats
(default 3) of wall and CPU seconds, with IPOPT's iterations and the cadence; then where a cold
solve's CPU goes per IPOPT iteration (IPOPT's own timing of the NLP's functions, the rest being
IPOPT and MUMPS); `--ipopt` sets IPOPT options over collocation's. Issue 34's targets: cold
<= 1 s and warm <= 0.2 s of CPU. Measured 2026-11-27 (2-core machine, load 1.4-1.8; one run;
docs/reference/performance.md): interpreted cold 2.30 s, warm 0.41 s; compiled cold 0.94 s (85
iterations: 1.6 ms of functions and 9.4 ms of IPOPT and MUMPS each), warm 0.15 s (15
iterations), resolve 0.13 s (16; 0.14 s and 17 since WARM_START's complementarity tolerance
1e-8); the first compiled build 28 s (2026-11-26). `--same` solves RBDS001's body (62 kg, 1.81
m; heel, 40 nodes) at 2.5, 3.5 and 4.5 m/s both ways and prints the iterations, objectives and
cadences side by side. The peer: opty's human-gait example on gait2d (torque-driven, planar, 3 m/s, 40 nodes, smooth
contact; ../shared/peers/opty_gait2d), run cold (its zero guess) and warm (its shipped
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
import tempfile
import time
from pathlib import Path

import numpy as np

from formopt.mechanics.body import paper_body, scaled_body
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
    """(result, wall s, CPU s) of run(); the CPU of its child processes (a C compiler) included."""
    wall, used = time.perf_counter(), cpu() + cpu(children=True)
    out = run()
    return out, time.perf_counter() - wall, cpu() + cpu(children=True) - used


def build(compiled: bool, nodes: int = 40, ipopt: dict | None = None) -> StrideNLP:
    """The NLP and its solver: graph, IPOPT (`ipopt`: options over the defaults) and its
    derivatives (`compiled`: in C)."""
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=nodes), ipopt, compiled)
    assert nlp.solver is not None
    return nlp


def per_iteration(stats: dict) -> dict:
    """ms per IPOPT iteration of the NLP's functions (IPOPT's t_proc_nlp_*, CPU) of a solve."""
    n = max(stats["iter_count"], 1)
    return {k: 1e3 * stats[f"t_proc_nlp_{k}"] / n for k in ("f", "g", "grad_f", "jac_g", "hess_l")}


def formopt_once(compiled: bool, speed=3.0, nodes=40, ipopt: dict | None = None) -> dict:
    """One build, cold, warm and resolved solve (wall and CPU seconds, iterations, status,
    cadence) and the cold solve's functions' ms per iteration."""
    nlp, build_s, build_cpu = timed(lambda: build(compiled, nodes, ipopt))
    cold, cold_s, cold_cpu = timed(lambda: nlp.solve(ballistic(nlp, speed), speed))
    functions = per_iteration(nlp.solver.stats())
    warm, warm_s, warm_cpu = timed(lambda: nlp.solve(cold.blocks, speed + 0.1))
    resolved, resolve_s, resolve_cpu = timed(lambda: nlp.resolve(cold, speed + 0.1))
    return {"build_s": build_s, "build_cpu": build_cpu, "cold_s": cold_s, "cold_cpu": cold_cpu,
            "cold_iterations": cold.iterations, "cold_status": cold.status, "warm_s": warm_s,
            "warm_cpu": warm_cpu, "warm_iterations": warm.iterations, "warm_status": warm.status,
            "resolve_s": resolve_s, "resolve_cpu": resolve_cpu, "resolve_iterations": resolved.iterations,
            "cadence_spm": 60.0 / half_period(nlp, cold.blocks), **{f"ms_{k}": v for k, v in functions.items()},
            "ms_ipopt": 1e3 * cold_cpu / max(cold.iterations, 1) - sum(functions.values())}


def first_build() -> float:
    """CPU s of the compiled build into a fresh cache (the C compiler's included)."""
    with tempfile.TemporaryDirectory() as cache:
        before = os.environ.get("FORMOPT_CACHE")
        os.environ["FORMOPT_CACHE"] = cache
        try:
            return timed(lambda: build(True))[2]
        finally:
            if before is None:
                del os.environ["FORMOPT_CACHE"]
            else:
                os.environ["FORMOPT_CACHE"] = before


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


def same(speeds=(2.5, 3.5, 4.5), nodes=40) -> None:
    """RBDS001's body solved cold, interpreted and compiled: the iterations, the objective and
    the cadence of each, and their largest relative differences."""
    body = scaled_body(62.0, 1.81)
    nlps = [StrideNLP(JointSpace(body), StrideSettings(strike="heel", nodes=nodes), compiled=c) for c in (False, True)]
    for speed in speeds:
        a, b = (nlp.solve(ballistic(nlp, speed), speed) for nlp in nlps)
        ca_, cb = (60.0 / half_period(nlp, s.blocks) for nlp, s in zip(nlps, (a, b)))
        print(f"RBDS001 {speed} m/s: interpreted {a.iterations} it, {a.objective:.10f}, {ca_:.6f} steps/min; "
              f"compiled {b.iterations} it, {b.objective:.10f}, {cb:.6f} steps/min; relative differences "
              f"{abs(b.objective / a.objective - 1):.1e} and {abs(cb / ca_ - 1):.1e}; max |dx| {np.max(np.abs(b.x - a.x)):.1e}")


def report(ours: dict[str, list[dict]]) -> None:
    """formopt's rows (medians), the targets, and where a cold solve's CPU goes."""
    print(f"{'':31s} {'build':>17s} {'cold':>17s} {'it':>4s} {'warm':>17s} {'it':>4s} {'resolve':>17s} "
          f"{'it':>4s} {'cadence':>8s}")
    for path, runs in ours.items():
        m = {k: median(runs, k) for k in runs[0]}
        print(f"{'formopt, ' + path:31s} {cell(m['build_s'])} ({cell(m['build_cpu'], 5)}) "
              f"{cell(m['cold_s'])} ({cell(m['cold_cpu'], 5)}) {m['cold_iterations']:4.0f} "
              f"{cell(m['warm_s'])} ({cell(m['warm_cpu'], 5)}) {m['warm_iterations']:4.0f} "
              f"{cell(m['resolve_s'])} ({cell(m['resolve_cpu'], 5)}) {m['resolve_iterations']:4.0f} "
              f"{m['cadence_spm']:8.1f}   cold: {runs[0]['cold_status']}, warm: {runs[0]['warm_status']}")
    for path, runs in ours.items():
        m = {k: median(runs, k) for k in runs[0]}
        print(f"{path}: a cold iteration's CPU, ms: f {m['ms_f']:.2f}, g {m['ms_g']:.2f}, grad_f {m['ms_grad_f']:.2f}, "
              f"jac_g {m['ms_jac_g']:.2f}, hess_l {m['ms_hess_l']:.2f}; IPOPT and MUMPS {m['ms_ipopt']:.2f}")
        print(f"{path}: targets (CPU): " + ", ".join(f"{k} <= {v:g} s: {'met' if m[f'{k}_cpu'] <= v else 'missed'}"
                                                   for k, v in TARGETS_CPU.items()))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--peer", help=f"the peer's venv (default: ${PEER_ENV})")
    parser.add_argument("--no-peer", action="store_true")
    parser.add_argument("--same", action="store_true", help="RBDS001 at 3 speeds, interpreted and compiled")
    parser.add_argument("--first-build", action="store_true", help="time the compiled build into a fresh cache")
    parser.add_argument("--paths", choices=("both", "interpreted", "compiled"), default="both")
    parser.add_argument("--ipopt", type=json.loads, default=None, help="IPOPT options over the defaults (JSON)")
    args = parser.parse_args()
    if args.same:
        same()
        return 0
    print(f"medians of {args.repeats} repeats; wall s (CPU s)")
    if args.first_build:
        print(f"the compiled build into a fresh cache: {first_build():.1f} s of CPU (the C compiler's included)")
    if args.ipopt:
        print(f"IPOPT options over the defaults: {args.ipopt}")
    report({path: [formopt_once(compiled, ipopt=args.ipopt) for _ in range(args.repeats)]
            for path, compiled in (("interpreted", False), ("compiled", True)) if args.paths in ("both", path)})
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
          f"{'':7s} {'-':>4s} {cell(warm['solve_s'])} {'':7s} {'-':>4s} {'-':>17s} {'-':>4s} {cell(warm['cadence_spm'], 8)}"
          f"   cold: {status['cold']}, warm: {status['warm']}")
    print(f"the peer's symbolic derivation {cell(cold['derive_s'], 5).strip()} s per run (before its build); its "
          f"process CPU per run: cold {cell(cold['process_cpu'], 5).strip()} s, warm {cell(warm['process_cpu'], 5).strip()} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
