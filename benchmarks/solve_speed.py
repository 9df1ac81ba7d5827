"""Speed of the posture optimisation (the demo's gait-anchored problem), interpreted and compiled.

    python benchmarks/solve_speed.py [--scene formopt/scenes/demo.toml] [--repeats 30]

Prints medians (seed printed): building the NLP, generating and compiling it (cold cache) and
loading it again (cached); one IPOPT solve from the reference posture and from seeded random
starts, with CasADi's interpreted functions and with compiled ones; IPOPT with the exact
Hessian against its limited-memory (L-BFGS) approximation; and the landing objective
(formopt/scenes/landing_optimum.toml: both impacts and the contact phase). No peer tool solves this problem
(Pinocchio has no optimiser; bioptim and OpenSim Moco optimise trajectories, not the impact
map), so the reference figure is IPOPT's own with a quasi-Newton Hessian.
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from formopt import load
from formopt.optim.multistart import starts
from formopt.optim.posture import PostureProblem

ROOT = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "formopt" / "scenes" / "demo.toml"))
    parser.add_argument("--repeats", type=int, default=30)
    args = parser.parse_args()
    os.environ["FORMOPT_CACHE"] = tempfile.mkdtemp(prefix="formopt-bench-")  # a cold cache
    scene = load(args.scene)
    model = scene.model()
    seed = scene.problem.seed
    print(f"{scene.name}: {len(scene.problem.variables)} variables; seed {seed}; "
          f"medians of {args.repeats} solves; one core\n")
    rng = np.random.default_rng(seed)
    rows = []
    for label, compiled, hessian in (("interpreted, exact Hessian", False, "exact"),
                                     ("compiled (-O0), exact Hessian", True, "exact"),
                                     ("interpreted, limited-memory Hessian", False, "limited-memory")):
        t = time.perf_counter()
        problem = PostureProblem(model, scene.strike, scene.state, scene.problem, scene.slope,
                                 scene.friction, compiled=compiled, hessian=hessian, law=scene.contact)
        build = time.perf_counter() - t
        if compiled:
            t = time.perf_counter()
            PostureProblem(model, scene.strike, scene.state, scene.problem, scene.slope,
                           scene.friction, compiled=True, law=scene.contact)
            rows.append((label, "build + compile (cold cache)", f"{build:.2f} s"))
            rows.append((label, "build, cached", f"{time.perf_counter() - t:.3f} s"))
        else:
            rows.append((label, "build", f"{build:.3f} s"))
        u_ref = problem.to_unit(scene.state)
        times, iters, statuses, values = [], [], set(), []
        for _ in range(args.repeats):
            sol, stats, elapsed = problem.solve_from(u_ref)
            times.append(elapsed)
            iters.append(stats["iter_count"])
            statuses.add(stats["return_status"])
            values.append(float(problem.objective_function(sol["x"], problem.p0)))
        rows.append((label, "solve from the reference",
                     f"{statistics.median(times) * 1e3:.2f} ms   ({statistics.median(iters):.0f} "
                     f"iterations, {', '.join(sorted(statuses))}, objective {values[0]:.6g})"))
        times = []
        for u0 in rng.uniform(0, 1, (args.repeats, len(scene.problem.variables))):
            times.append(problem.solve_from(u0)[2])
        rows.append((label, "solve from a random start", f"{statistics.median(times) * 1e3:.2f} ms"))
    landing = load(ROOT / "formopt" / "scenes" / "landing_optimum.toml")
    label = "landing objective (T_c_total), limited-memory"
    t = time.perf_counter()
    problem = landing.posture_problem()
    rows.append((label, "build", f"{time.perf_counter() - t:.3f} s"))
    times, statuses = [], set()
    first = starts(problem)
    for w0 in first:
        for _ in range(max(1, args.repeats // 10)):
            sol, stats, elapsed = problem.solve_from(w0)
            times.append(elapsed)
            statuses.add(stats["return_status"])
    rows.append((label, "solve", f"{statistics.median(times) * 1e3:.0f} ms   ({', '.join(sorted(statuses))}, "
                                 f"{len(times)} solves from {len(first)} starts)"))
    width = max(len(r[0]) + len(r[1]) for r in rows) + 4
    for label, what, figure in rows:
        print(f"{label + ': ' + what:{width}s} {figure}")


if __name__ == "__main__":
    main()
