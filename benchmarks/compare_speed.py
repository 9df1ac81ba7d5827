"""Speed of `formopt compare` on a 30 s trial (RBDS001 T35: 4500 frames, 85 touchdowns) with an
optimum for every step, as a whole process (start-up, reading, checks, kinematics, the mean
step's multi-start optimum, 85 per-step optima, figure, CSV, JSON, OpenSim files).

    python benchmarks/compare_speed.py [--repeats 5]

Prints the median wall time of the whole process (target <= 3 s), and the time of its parts in
one process; side by side, the per-step optima done the way the NLP was built before the
reference became one of its parameters: one PostureProblem (symbolic build and solver) per
step. No peer tool computes this (OpenSim and Visual3D give the angles, not an optimum).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data" / "rbds"
ARGS = ["compare", "--trial", str(DATA / "RBDS001runT35.c3d"), "--static", str(DATA / "RBDS001static.c3d"),
        "--mass", "62", "--height", "1.81"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    exe = str(Path(sys.executable).with_name("formopt"))
    walls = []
    for _ in range(args.repeats):
        with tempfile.TemporaryDirectory() as out:
            t = time.perf_counter()
            subprocess.run([exe, *ARGS, "--out", out], check=True, capture_output=True)
            walls.append(time.perf_counter() - t)
    print(f"formopt compare, whole process, 30 s trial with per-step optima: median "
          f"{statistics.median(walls):.2f} s over {args.repeats} runs (target <= 3 s)")

    from formopt.io import mocap
    from formopt.measure import measure
    from formopt.mechanics.model import build_model
    from formopt.optim.posture import PostureProblem, Problem
    from formopt.studies.compare import compare

    t = time.perf_counter()
    trial, static = mocap.read(DATA / "RBDS001runT35.c3d"), mocap.read(DATA / "RBDS001static.c3d")
    measure(trial, static, 1.81)
    measured = time.perf_counter() - t
    t = time.perf_counter()
    c = compare(trial, static, 62.0, 1.81, friction=0.8, per_step=False)
    mean_only = time.perf_counter() - t
    t = time.perf_counter()
    c = compare(trial, static, 62.0, 1.81, friction=0.8)
    with_steps = time.perf_counter() - t
    n = len(c.per_step)
    print(f"  reading and measuring (checks, axes, kinematics, touchdowns): {measured:.2f} s")
    print(f"  compare, mean step's optimum only: {mean_only:.2f} s; with {n} per-step optima: "
          f"{with_steps:.2f} s ({(with_steps - mean_only) / n * 1e3:.1f} ms per step, one NLP, "
          f"the step in its parameters)")
    model = build_model(c.body, "leg")
    p = c.problem
    t = time.perf_counter()
    for k in c.per_step:
        one = Problem(p.variables, p.lower, p.upper, p.objective, starts=1, gait=p.gait)
        PostureProblem(model, c.strike, c.steps.touchdowns[k].state(), one, 0.0, 0.8).solve()
    rebuilt = time.perf_counter() - t
    print(f"  side by side: one PostureProblem per step (build + solve): {rebuilt:.2f} s "
          f"({rebuilt / n * 1e3:.1f} ms per step)")


if __name__ == "__main__":
    main()
