"""Is the free-cadence optimum a minimum or an early exit (issue 34's N against 2N)? RBDS001's
body (62 kg, 1.81 m), heel strike, torque+springs (problem.RUNNER_TENDONS), effort, as
problems/stride_mesh.py builds it.

    python problems/stride_creep.py [--speed 3.5] [--nodes 40] [--transcription trapezoid]
                                    [--moment-time 0 (s)] [--approach-speed 0 (m/s)]
                                    [--ipopt tol=1e-8 obj_scaling_factor=100] ...

Per set of IPOPT options (`--ipopt`, one set a flag; none: the stride's defaults) four solves:
the free cadence from the generic start (1), the cadence imposed at (1)'s from (1)'s blocks (2),
the free cadence from (2)'s blocks (3), and the free cadence from (1)'s own blocks again (4).
Prints for each: the objective (per distance), its change from (1) in %, the cadence
(steps/min), the phase durations (ms), IPOPT's status, iterations and CPU seconds, and for (2)
the multiplier of the imposed period, dJ/dT (1/s; 0 at a free optimum: the slope of the
imposed-cadence curve there).
"""

from __future__ import annotations

import argparse
import sys
import time

from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride.collocation import StrideNLP
from formopt.optim.stride.local import generic_start
from formopt.optim.stride.problem import RUNNER_TENDONS, StrideSettings


def ipopt_options(text: str) -> dict:
    """'key=value,key=value' as IPOPT options (numbers where they parse)."""
    def value(v: str):
        for kind in (int, float):
            try:
                return kind(v)
            except ValueError:
                pass
        return v
    pairs = [kv.split("=", 1) for kv in text.split(",") if kv]
    if any(len(kv) != 2 for kv in pairs):
        raise argparse.ArgumentTypeError(f"--ipopt {text!r}: key=value[,key=value]")
    return {k: value(v) for k, v in pairs}


def period_multiplier(nlp: StrideNLP, solved) -> float:
    """d objective / d period (1/s) at an imposed period: minus its row's multiplier (CasADi's
    Lagrangian f + lam g, so dV/dc = -lam for the row g = c)."""
    k = sum(len(e) for e in nlp.node_rows.lower + nlp.rows.lower[:nlp.period_row])
    return -float(solved.lam_g[k])


def line(label: str, nlp: StrideNLP, solved, seconds: float, reference: float | None) -> str:
    """One solve's summary (module docstring)."""
    period = sum(solved.blocks[f"T_{p.name}"].item() for p in nlp.phases)
    change = "" if reference is None else f" ({(solved.objective / reference - 1) * 100:+.3f} %)"
    durations = " ".join(f"{solved.blocks[f'T_{p.name}'].item() * 1e3:.1f}" for p in nlp.phases)
    return (f"  {label}: objective {solved.objective:.6f}{change} at {60 / period:.2f} steps/min, "
            f"phases {durations} ms; {solved.status} in {solved.iterations} iterations, {seconds:.1f} s CPU")


def timed(nlp: StrideNLP, start: dict, speed: float, cadence: float | None = None):
    """nlp.solve from `start`, and its CPU seconds (the solver built before the clock)."""
    nlp.solver  # noqa: B018 (built on first use: its derivatives are not the solve's time)
    clock = time.process_time()
    solved = nlp.solve(start, speed, cadence=cadence)
    return solved, time.process_time() - clock


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--nodes", type=int, default=40)
    parser.add_argument("--moment-time", type=float, default=0.0, help="StrideSettings.moment_time (s)")
    parser.add_argument("--approach-speed", type=float, default=0.0, help="StrideSettings.approach_speed (m/s)")
    parser.add_argument("--transcription", default="trapezoid")
    parser.add_argument("--ipopt", action="append", type=ipopt_options, default=None,
                        help="one set of IPOPT options per flag, key=value[,key=value]")
    args = parser.parse_args(argv)
    body = scaled_body(62.0, 1.81)
    settings = StrideSettings(strike="heel", nodes=args.nodes, tendons=dict(RUNNER_TENDONS),
                              moment_time=args.moment_time, approach_speed=args.approach_speed,
                              transcription=args.transcription)
    v = args.speed
    for options in args.ipopt or [{}]:
        nlp = StrideNLP(JointSpace(body), settings, options)
        print(f"IPOPT options {options or 'the stride defaults'}:", flush=True)
        free, s = timed(nlp, generic_start(nlp, v), v)
        print(line("(1) free, generic start", nlp, free, s, None), flush=True)
        cadence = 60 / sum(free.blocks[f"T_{p.name}"].item() for p in nlp.phases)
        fixed, s = timed(nlp, free.blocks, v, cadence)
        print(line("(2) imposed at (1)'s cadence", nlp, fixed, s, free.objective)
              + f"; dJ/dT {period_multiplier(nlp, fixed):+.3e} 1/s", flush=True)
        again, s = timed(nlp, fixed.blocks, v)
        print(line("(3) free from (2)", nlp, again, s, free.objective), flush=True)
        same, s = timed(nlp, free.blocks, v)
        print(line("(4) free from (1)", nlp, same, s, free.objective), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
