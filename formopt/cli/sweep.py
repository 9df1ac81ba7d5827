"""formopt sweep SCENE --param NAME=START:STOP:COUNT: landings, posture optima or strides across a grid (resumable)."""

from __future__ import annotations

import os
import sys
from collections import Counter

from ..io.files import save_figure
from ..io.scene import load
from ..io.stride_scene import StrideScene
from ..mechanics.errors import InputError
from ..report.figures import optimum_map_figure, sweep_figure
from ..report.stride_sweep import stride_sweep_figures
from ..studies import stride_map, sweep
from .common import add_format


def add_parser(commands):
    cmd = commands.add_parser("sweep", help="landings, or the optimum of a scene with an [optimize] "
                                            "table, across a range of parameters (resumable)")
    add_format(cmd)
    cmd.add_argument("scene", help="scene file or a shipped scene's name, "
                     "e.g. landing_spring (`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--param", action="append", required=True,
                     help="NAME=START:STOP:COUNT (repeat for a grid); NAME one of "
                          + ", ".join(f"{n} ({u})" for n, u in sweep.UNITS.items())
                          + ". Choose a range the scene can take: a forefoot strike needs the "
                          "heel above the ground at touchdown. On a [stride] scene NAME one of "
                          + ", ".join(f"{n} ({u})" for n, u in stride_map.PARAMETERS.items()))
    cmd.add_argument("--out", help="CSV file, its name ending in .csv (default out/<scene>/sweep.csv; "
                     "the figures take its name); an existing one is resumed")
    cmd.add_argument("--no-progress", action="store_true", help="no progress bar")
    cmd.add_argument("--landings", action="store_true",
                     help="sweep the landing even when the scene has an [optimize] table "
                          "(otherwise the optimum is solved at every point)")
    cmd.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                     help="local processes (default: one per core)")
    cmd.add_argument("--scheduler", help="address of a Dask distributed scheduler, e.g. "
                                         "tcp://10.0.0.5:8786 (pip install 'formopt[dask]')")


def run(args) -> int:
    from pathlib import Path

    from ..io.files import OutputError, check_target

    scene = load(args.scene)
    params = [sweep.parse_param(p, scene) for p in args.param]
    out = check_target(args.out) if args.out is not None else Path("out") / Path(scene.path).stem / "sweep.csv"
    if out.suffix.lower() != ".csv":  # the figures take the CSV's name with their own suffix
        raise OutputError(f"{out}: a sweep writes CSV; give a file name ending in .csv (its figures "
                          f"are named after it, e.g. {out.stem}.{args.format})")
    if args.workers < 1:
        raise InputError("--workers must be at least 1")
    rows = sweep.run(scene, params, out, progress=not args.no_progress, workers=args.workers,
                     scheduler=args.scheduler, note=lambda text: print(f"note: {text}", file=sys.stderr),
                     landings=args.landings)
    if isinstance(scene, StrideScene):
        return _stride_summary(rows, params, out, args.format)
    if scene.problem is not None and not args.landings:
        return _optimum_summary(scene, rows, params, out, args.format)
    failed = [r for r in rows if r["error"]]
    good = [r for r in rows if sweep.valid(r)]
    print(f"{len(rows)} landings in {out}, in parameter order: {len(good)} valid, "
          f"{len(rows) - len(good) - len(failed)} invalid (a slip, a pulled contact or an unfinished "
          f"landing), {len(failed)} failed")
    if failed:
        reasons = Counter(r["error"].split(":")[0] if "below the ground" not in r["error"]
                          else "a foot point starts below the ground" for r in failed)
        print("  failed: " + "; ".join(f"{n} x {why}" for why, n in reasons.most_common(3))
              + " (the error column says each)")
    if good:
        totals = [float(r["T_c_total"]) for r in good]
        print(f"T_c_total of the valid landings from {min(totals):.4f} to {max(totals):.4f} J")
    if len(rows) > len(failed):
        figure = sweep_figure(rows, [name for name, _ in params])
        print(f"wrote {save_figure(figure, out.with_suffix(f'.{args.format}'))}")
    return 0


def _optimum_summary(scene, rows, params, out, fmt) -> int:
    """What an optimum map found: how many points converged, interior or held, and by what."""
    good = [r for r in rows if r["success"] == "True"]
    interior = [r for r in good if r["verdict"] == "interior optimum"]
    warm = [r for r in good if r["warm"] == "True"]
    print(f"{len(rows)} optima in {out}, in parameter order: {len(good)} converged "
          f"({len(interior)} interior, {len(good) - len(interior)} held by a limit), "
          f"{len(rows) - len(good)} without an optimum; {len(warm)} warm-started")
    held = Counter(name for r in good if r["verdict"].startswith("HELD BY")
                   for name in r["verdict"].removeprefix("HELD BY ").split(", "))
    if held:
        print("  held by: " + "; ".join(f"{name} at {n} points" for name, n in held.most_common(4)))
    if good:
        its = [int(r["iterations"]) for r in good]
        print(f"  IPOPT iterations per point: median {sorted(its)[len(its) // 2]}, max {max(its)}")
        T_c = [float(r["T_c"]) for r in good]
        print(f"  T_c at the optima from {min(T_c):.4f} to {max(T_c):.4f} J")
        figure = optimum_map_figure(rows, [name for name, _ in params], scene.problem.variables)
        print(f"wrote {save_figure(figure, out.with_suffix(f'.{fmt}'))}")
    return 0 if good else 1


def _stride_summary(rows, params, out, fmt) -> int:
    """What a stride map found: converged, valid, how each was started, the cost's range."""
    good = [r for r in rows if not r["error"] and r["success"] == "True"]
    valid = [r for r in good if r["valid"] == "True"]
    starts = Counter(r["start"] for r in good)
    print(f"{len(rows)} strides in {out}, in parameter order: {len(good)} converged "
          f"({len(valid)} valid: impacts and checks), {len(rows) - len(good)} without an optimum; started "
          + ", ".join(f"{n} from {how}" for how, n in starts.most_common()))
    failed = Counter(r["error"] or r["status"] for r in rows if r not in good)
    if failed:
        print("  failed: " + "; ".join(f"{n} x {why}" for why, n in failed.most_common(3)))
    if good:
        its = sorted(int(r["iterations"]) for r in good)
        print(f"  IPOPT iterations per stride: median {its[len(its) // 2]}, max {its[-1]}")
        for key, unit in (("mechanical_power_W", "W"), ("impact_loss_W", "W"), ("cadence_spm", "steps/min")):
            values = [float(r[key]) for r in good]
            print(f"  {key} from {min(values):.4g} to {max(values):.4g} {unit}")
        for name, figure in stride_sweep_figures(rows, [n for n, _ in params]).items():
            print(f"wrote {save_figure(figure, out.with_name(f'{out.stem}_{name}.{fmt}'))}")
    return 0 if good else 1
