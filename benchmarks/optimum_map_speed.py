"""Speed of an optimum map: 10,000 gait-anchored optima on 2 cores, warm-started chains
against cold solves.

    python benchmarks/optimum_map_speed.py [--scene formopt/scenes/demo.toml] [--side 100] [--workers 2]

Sweeps the running speed (2-6 m/s) and the friction (0.4-1.0) on a side x side grid with
`formopt sweep`'s machinery (studies.sweep.run: serpentine chains, IPOPT warm starts, rows
written as they finish) and prints the wall time, the time per optimum and IPOPT's iterations
per point. The peer figure is the same problem solved cold (from the reference posture, no
warm start) at 200 points of the grid, in the same run: its iterations and time per point.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from formopt import load
from formopt.optim.solution import CONVERGED
from formopt.studies import sweep

ROOT = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "formopt" / "scenes" / "demo.toml"))
    parser.add_argument("--side", type=int, default=100)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    scene = load(args.scene)
    params = [("speed_mps", np.linspace(2.0, 6.0, args.side)),
              ("friction", np.linspace(0.4, 1.0, args.side))]
    print(f"{scene.name}: {args.side ** 2} optima (speed 2-6 m/s x friction 0.4-1.0) on "
          f"{args.workers} workers; seed {scene.problem.seed}")
    path = Path(tempfile.mkdtemp(prefix="formopt-map-")) / "map.csv"
    t = time.perf_counter()
    rows = sweep.run(scene, params, path, progress=False, workers=args.workers)
    wall = time.perf_counter() - t
    good = [r for r in rows if r["success"] == "True"]
    warm = [int(r["iterations"]) for r in good if r["warm"] == "True"]
    print(f"map: {wall:.1f} s wall ({wall / len(rows) * 1e3:.2f} ms per optimum); {len(good)} "
          f"converged, {sum(r['verdict'] == 'interior optimum' for r in good)} interior; "
          f"{len(warm)} warm-started, median {statistics.median(warm):.0f} iterations "
          f"(mean {statistics.mean(warm):.1f})")
    pp = scene.posture_problem()
    w0 = pp.start(scene.state)
    rng = np.random.default_rng(scene.problem.seed)
    sample = rng.choice(len(rows), 200, replace=False)
    iterations, times, ok = [], [], 0
    for k in sample:
        p = np.array([float(rows[k]["speed_mps"]), float(rows[k]["friction"])])
        _sol, stats, elapsed = pp.solve_from(w0, p)
        iterations.append(stats["iter_count"])
        times.append(elapsed)
        ok += stats["return_status"] in CONVERGED
    print(f"cold, same run (200 points from the reference posture, one core): median "
          f"{statistics.median(iterations):.0f} iterations (mean {statistics.mean(iterations):.1f}), "
          f"{statistics.median(times) * 1e3:.2f} ms per solve, {ok}/200 converged; a cold map of "
          f"{len(rows)} points on {args.workers} cores would take about "
          f"{statistics.mean(times) * len(rows) / args.workers:.0f} s of solves")


if __name__ == "__main__":
    main()
