"""Speed of a stride map: 41 speeds x 21 cadences (861 strides) on 2 workers, warm-started,
against cold solves in the same run.

    python benchmarks/stride_sweep_speed.py [--scene formopt/scenes/stride.toml]
        [--speeds 41] [--cadences 21] [--workers 2] [--nodes N] [--cold 5]

The grid: speeds 2.5-4.5 m/s and a fixed cadence band of 140-210 steps/min (the same band at
every speed, so that the grid is a product and `formopt sweep` walks it as one serpentine; the
free optima of the paper's body lie inside it at these speeds, about 160-190 steps/min). The
map runs with `formopt sweep`'s machinery (studies.sweep.run: serpentine chains warm-started
from solved neighbours, each chain's first stride from the free optimum at its speed, rows
written as they finish) at the scene's node count (40) unless --nodes says otherwise.

Printed: the wall time, the CPU seconds of the workers (all processes, RUSAGE_CHILDREN, so
a loaded machine shows its load in the wall time, not in these), per stride; the median IPOPT
time and iterations of the neighbour-started strides; then `--cold` strides of the grid solved
cold (from the generic guess, cadence imposed, one core), their median time and iterations, and
the warm-start gain: the cold solve's median CPU seconds against the map's CPU seconds per
stride (builds, seeds and summaries included, so the gain is not flattered), and the ratio of
the median iterations. CPU seconds, not wall: the warm solves run in the pool while the cold
ones run after it, so on a shared machine their wall clocks see different loads. The target (issue 27): the 861 strides in <= 5 min wall
on a quiet 2-core machine.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from formopt import load
from formopt.optim.stride.guess import ballistic
from formopt.studies import stride_map, sweep

ROOT = Path(__file__).resolve().parent.parent
BAND = (140.0, 210.0)  # steps/min
SPEEDS = (2.5, 4.5)  # m/s


def cpu_seconds() -> float:
    """CPU seconds (user + system) of this process and its finished children."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def cold_solves(scene, rows, count: int, seed: int = 0):
    """`count` grid points solved from the generic guess: (IPOPT seconds, CPU seconds,
    iterations, converged)."""
    nlp = scene.nlp()
    picks = np.random.default_rng(seed).choice(len(rows), count, replace=False)
    seconds, cpu, iterations, ok = [], [], [], 0
    for k in picks:
        speed, cadence = float(rows[k]["speed_mps"]), float(rows[k]["cadence_spm"])
        start = time.process_time()
        solved = nlp.solve(ballistic(nlp, speed), speed, scene.slope, scene.friction, cadence)
        cpu.append(time.process_time() - start)
        seconds.append(solved.solve_s)
        iterations.append(solved.iterations)
        ok += solved.success
    return seconds, cpu, iterations, ok


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "formopt" / "scenes" / "stride.toml"))
    parser.add_argument("--speeds", type=int, default=41)
    parser.add_argument("--cadences", type=int, default=21)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--nodes", type=int, help="collocation intervals (default: the scene's)")
    parser.add_argument("--cold", type=int, default=5, help="cold solves for the comparison")
    args = parser.parse_args()
    if args.cold < 1:
        parser.error(f"--cold {args.cold}: at least 1 (the warm-start gain is against cold solves)")
    scene = load(args.scene)
    if args.nodes:
        scene = stride_map.for_nodes(scene, args.nodes)
    params = [("speed_mps", np.linspace(*SPEEDS, args.speeds)),
              ("cadence_spm", np.linspace(*BAND, args.cadences))]
    n = args.speeds * args.cadences
    print(f"{scene.name}: {n} strides ({args.speeds} speeds {SPEEDS[0]}-{SPEEDS[1]} m/s x "
          f"{args.cadences} cadences {BAND[0]:g}-{BAND[1]:g} steps/min), {scene.settings.nodes} nodes, "
          f"{scene.strike} strike, {scene.settings.objective}; {args.workers} workers; "
          f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    path = Path(tempfile.mkdtemp(prefix="formopt-stride-map-")) / "map.csv"
    cpu, wall = cpu_seconds(), time.perf_counter()
    rows = sweep.run(scene, params, path, progress=False, workers=args.workers)
    wall, cpu = time.perf_counter() - wall, cpu_seconds() - cpu
    good = [r for r in rows if r["success"] == "True"]
    warm = [r for r in good if r["start"] == "neighbour"]
    warm_s = statistics.median(float(r["solve_s"]) for r in warm) if warm else float("nan")
    its = statistics.median(int(r["iterations"]) for r in warm) if warm else float("nan")
    print(f"map: {wall:.1f} s wall, {cpu:.1f} CPU s ({cpu / n:.3f} CPU s per stride, builds and "
          f"free seeds included); {len(good)}/{n} converged, {sum(r['valid'] == 'True' for r in good)} "
          f"valid; {len(warm)} started from a neighbour: median IPOPT {warm_s:.3f} s, {its:.0f} iterations")
    seconds, cpu_cold, iterations, ok = cold_solves(scene, rows, args.cold)
    cold_cpu = statistics.median(cpu_cold)
    print(f"cold, same run ({args.cold} grid points from the generic guess, one core): median "
          f"{cold_cpu:.3f} CPU s (IPOPT {statistics.median(seconds):.3f} s wall), "
          f"{statistics.median(iterations):.0f} iterations, {ok}/{args.cold} converged")
    print(f"warm-start gain: {cold_cpu / (cpu / n):.1f} x in CPU seconds per stride (cold solve "
          f"against the map's whole CPU per stride), {statistics.median(iterations) / its:.1f} x in "
          f"IPOPT iterations; a cold map would take about {cold_cpu * n:.0f} CPU s "
          f"({cold_cpu * n / args.workers:.0f} s on {args.workers} quiet cores)")
    print(f"rows: {path}")


if __name__ == "__main__":
    main()
