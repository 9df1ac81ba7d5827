"""Command line of formopt.

    formopt impact SCENE [--json]        the indicators of the foot strike a scene describes
    formopt solve SCENE [--json] [--out DIR] [--starts N] [--seed S] [--compiled]
                                         the touchdown posture that absorbs the least energy

Bad input (a scene that does not validate, a posture the impact map cannot take) prints one
line naming the key and the reason and exits with status 2. `solve` exits with status 1 when
no start converged: IPOPT's status is printed, and no optimum is claimed.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import sys
from pathlib import Path

from .impact import ImpactResult, impact
from .scene import Scene, SceneError, load, touchdown_table


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="formopt", description="The running form that wastes "
                                     "the least energy at foot strike.")
    commands = parser.add_subparsers(dest="command", required=True)
    cmd = commands.add_parser("impact", help="indicators of the foot strike a scene describes")
    cmd.add_argument("scene", help="scene file (TOML), e.g. problems/forefoot_strike.toml")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd = commands.add_parser("solve", help="optimise the touchdown posture of a scene")
    cmd.add_argument("scene", help="scene file with an [optimize] table, e.g. problems/demo.toml")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for figures and result files (default out/<scene>)")
    cmd.add_argument("--starts", type=int, help="number of starts (overrides the scene)")
    cmd.add_argument("--seed", type=int, help="seed of the random starts (overrides the scene)")
    cmd.add_argument("--compiled", action="store_true",
                     help="generate, compile (cached) and run the NLP's functions as C")
    cmd = commands.add_parser("simulate", help="follow the landing from the touchdown")
    cmd.add_argument("scene", help="scene file, e.g. problems/landing_spring.toml")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for figures, CSV and JSON (default out/<scene>)")
    cmd = commands.add_parser("sweep", help="landings across a range of parameters (resumable)")
    cmd.add_argument("scene", help="scene file, e.g. problems/landing_spring.toml")
    cmd.add_argument("--param", action="append", required=True,
                     help="NAME=START:STOP:COUNT, e.g. ankle_deg=-20:20:41 (repeat for a grid)")
    cmd.add_argument("--out", help="CSV file (default out/<scene>/sweep.csv); an existing one is resumed")
    cmd.add_argument("--no-progress", action="store_true", help="no progress bar")
    cmd.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                     help="local processes (default: one per core)")
    cmd.add_argument("--scheduler", help="address of a Dask distributed scheduler, e.g. "
                                         "tcp://10.0.0.5:8786 (pip install 'formopt[dask]')")
    cmd = commands.add_parser("compare", help="measured touchdowns of a motion-capture trial "
                                               "against the optimum")
    cmd.add_argument("--trial", required=True, help="running trial: C3D, or RBDS marker text")
    cmd.add_argument("--static", required=True, help="standing calibration trial (C3D or text)")
    cmd.add_argument("--forces", help="force text file for a text trial (RBDS layout)")
    cmd.add_argument("--mass", type=float, required=True, help="runner's mass (kg)")
    cmd.add_argument("--height", type=float, required=True, help="runner's stature (m)")
    cmd.add_argument("--sex", default="male", choices=["male", "female"])
    cmd.add_argument("--friction", type=float, default=0.8, help="the ground's friction (default 0.8)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for the figure, CSV and JSON (default out/<trial>)")
    cmd = commands.add_parser("bench", help="time and accuracy of each model level and numerical "
                                             "option (problems/bench)")
    cmd.add_argument("--quick", action="store_true", help="a reduced set, under a minute")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", default="out/bench", help="folder for bench.csv and pareto.png")
    args = parser.parse_args(argv)
    if args.command == "compare":
        return _compare(args)
    if args.command == "bench":
        return _bench(args)
    try:
        scene = load(args.scene)
        if args.command == "impact":
            return _impact(scene, args)
        if args.command == "simulate":
            return _simulate(scene, args)
        if args.command == "sweep":
            return _sweep(scene, args)
        return _solve(scene, args)
    except (SceneError, ValueError) as err:
        print(f"formopt: error: {args.scene}: {err}", file=sys.stderr)
        return 2


def _impact(scene: Scene, args) -> int:
    result = impact(scene)
    if args.json:
        print(json.dumps({"scene": scene.name, "model": scene.model, "body": scene.body.source,
                          "touchdown": scene.touchdown, "notes": list(scene.notes),
                          **result.to_dict()}, indent=2))
    else:
        print(impact_table(scene, result))
    return 0


def _solve(scene: Scene, args) -> int:
    from .optimize import solve
    from .plots import indicator_figure, posture_figure

    if args.starts is not None and args.starts < 1:
        raise ValueError("--starts must be at least 1")
    problem = scene.problem
    seed = args.seed if args.seed is not None else problem.seed if problem else 0
    print(f"{scene.name}: seed {seed}", file=sys.stderr)

    def progress(k, n, start):
        print(f"  start {k}/{n}: {start.status}, objective {start.objective:.6g} "
              f"({start.iterations} iterations)", file=sys.stderr)

    opt = solve(scene, compiled=args.compiled, progress=progress, starts=args.starts, seed=args.seed)
    out = Path(args.out) if args.out else Path("out") / Path(scene.path).stem
    figures = [posture_figure(out / "posture.png", scene.body, scene.strike, scene.slope,
                              [(scene.state, "reference", "0.55"),
                               (opt.state, "optimum" if opt.success else "not converged",
                                "tab:blue")]),
               indicator_figure(out / "indicators.png", {"reference": opt.reference,
                                                         "optimum": opt.impact})]
    report = solve_report(scene, opt, [str(f) for f in figures])
    _write_json(out / "result.json", report)
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(solve_table(scene, opt))
        print(f"\nwrote {', '.join(str(f) for f in figures)}, {out / 'result.json'}")
    return 0 if opt.success else 1


def _simulate(scene: Scene, args) -> int:
    import csv

    from .landing import history_rows, land
    from .plots import landing_figures

    landing = land(scene)
    model = scene.build_model()
    out = Path(args.out) if args.out else Path("out") / Path(scene.path).stem
    figures = landing_figures(out, landing, scene.body, model, scene.slope, scene.strike)
    out.mkdir(parents=True, exist_ok=True)
    tmp = out / ".landing.csv.tmp"
    with tmp.open("w", newline="") as fh:
        csv.writer(fh).writerows(history_rows(landing, model))
    tmp.replace(out / "landing.csv")
    report = {"scene": scene.name, "model": scene.model, "joints": dataclasses.asdict(scene.joints),
              "touchdown": scene.touchdown, **landing.to_dict(),
              "files": [str(f) for f in figures] + [str(out / "landing.csv")]}
    _write_json(out / "landing.json", report)
    if args.json:
        print(json.dumps(report, indent=2))
        return 0
    print(f"{scene.name}  ({scene.path})\nmodel {scene.model}; joints {scene.joints.model}; "
          f"{scene.strike} strike; friction {scene.friction:g}; slope {math.degrees(scene.slope):+.1f} deg\n")
    print(f"  {'time (ms)':>10s} {'contact':>10s} {'T_c (J)':>10s} {'t (N s)':>9s} {'n (N s)':>9s} "
          f"{'mu_c':>7s} {'dv trunk x, z (m/s)':>22s}")
    for e in landing.impacts:
        dv = f"{e.dv_trunk[0]:+.4f} {e.dv_trunk[1]:+.4f}" if e.dv_trunk else "-"
        mu = f"{e.mu_c:7.3f}" if e.mu_c is not None else "  n < 0"
        print(f"  {e.time * 1e3:10.3f} {e.contact:>10s} {e.T_c:10.4f} {e.impulse[0]:+9.4f} "
              f"{e.impulse[1]:+9.4f} {mu} {dv:>22s}")
    print(f"\n  absorbed in all      T_c_total {landing.T_c_total:.4f} J")
    print(f"  largest mu_c         {landing.mu_c_max:.3f} (friction {scene.friction:g})")
    held = "yes" if landing.no_slip_held else \
        f"no: mu_c exceeds the friction at {len(landing.slip_at)} instants, first at {landing.slip_at[0] * 1e3:.2f} ms"
    print(f"  no-slip held         {held}")
    for t, p, f in landing.releases:
        print(f"  released             {p} at {t * 1e3:.3f} ms: the ground would have pulled it ({f:.1f} N)")
    print(f"  energy balance error {landing.energy_error:.2e} J; constraint drift {landing.drift:.1e} m")
    print(f"  ended                {landing.ended} at {landing.t[-1] * 1e3:.2f} ms")
    for w in landing.warnings:
        print(f"warning: {w}")
    print(f"\nwrote {', '.join(report['files'])}, {out / 'landing.json'}")
    return 0


def _sweep(scene: Scene, args) -> int:
    from . import sweep

    params = [sweep.parse_param(p) for p in args.param]
    out = Path(args.out) if args.out else Path("out") / Path(scene.path).stem / "sweep.csv"
    if args.workers < 1:
        raise ValueError("--workers must be at least 1")
    rows = sweep.run(scene, params, out, progress=not args.no_progress, workers=args.workers,
                     scheduler=args.scheduler)
    failed = [r for r in rows if r["error"]]
    totals = [float(r["T_c_total"]) for r in rows if not r["error"]]
    print(f"{len(rows)} landings in {out}" + (f", {len(failed)} failed (see the error column)"
                                              if failed else ""))
    if totals:
        print(f"T_c_total from {min(totals):.4f} to {max(totals):.4f} J")
    if len(params) == 1 and totals:
        from .plots import sweep_figure
        print(f"wrote {sweep_figure(out.with_suffix('.png'), rows, params[0][0])}")
    return 0


def _compare(args) -> int:
    import csv

    from . import mocap
    from .compare import compare, report, table
    from .plots import comparison_figure

    try:
        if not 1.0 <= args.mass <= 500.0 or not 0.5 <= args.height <= 2.5:
            raise ValueError("--mass must be 1 to 500 kg and --height 0.5 to 2.5 m")
        if not args.friction > 0:
            raise ValueError("--friction must be > 0")
        trial = mocap.read(args.trial, args.forces)
        static = mocap.read(args.static)
        result = compare(trial, static, args.mass, args.height, args.sex, args.friction)
    except ValueError as err:  # MocapError included
        print(f"formopt: error: {err}", file=sys.stderr)
        return 2
    out = Path(args.out) if args.out else Path("out") / Path(args.trial).stem
    rep = report(result)
    rep["figure"] = str(comparison_figure(out / "comparison.png", result))
    out.mkdir(parents=True, exist_ok=True)
    tmp = out / ".touchdowns.csv.tmp"
    with tmp.open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(["time_s", "side", "strike", "trunk_deg", "hip_deg", "knee_deg", "ankle_deg",
                         "foot_angle_deg", "hip_vx", "hip_vz", "T_c_J", "valid"])
        for t in rep["touchdowns"]:
            a = t["angles_deg"]
            writer.writerow([t["time"], t["side"], t["strike"], a["trunk"], a["hip"], a["knee"],
                             a["ankle"], t["foot_angle_deg"], *t["hip_velocity"], t["T_c"], t["valid"]])
    tmp.replace(out / "touchdowns.csv")
    _write_json(out / "comparison.json", rep)
    if args.json:
        print(json.dumps(rep, indent=2))
    else:
        print(table(result))
        print(f"\nwrote {rep['figure']}, {out / 'touchdowns.csv'}, {out / 'comparison.json'}")
    return 0 if result.optimum.success else 1


def _bench(args) -> int:
    from . import bench
    from .plots import pareto_figure

    rows, batch = bench.run(args.quick, progress=lambda text: print(f"  {text}", file=sys.stderr))
    out = Path(args.out)
    files = [bench.write_csv(rows, out / "bench.csv"), pareto_figure(out / "pareto.png", rows)]
    report = {**bench.to_json(rows, batch), "files": [str(f) for f in files]}
    _write_json(out / "bench.json", report)
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(bench.table(rows, batch))
        print(f"wrote {', '.join(report['files'])}, {out / 'bench.json'}")
    return 0


def solve_report(scene: Scene, opt, figures) -> dict:
    """The JSON report of an optimisation."""
    from .optimize import explain

    return {
        "scene": scene.name, "model": scene.model, "success": opt.success, "status": opt.status,
        "status_explained": explain(opt.status),
        "objective": opt.objective, "objective_terms": scene.problem.objective,
        "touchdown": touchdown_table(scene.strike, opt.state),
        "T_c": opt.impact.T_c, "impulse": {k: list(v) for k, v in opt.impact.impulse.items()},
        "indicators": opt.impact.to_dict(),
        "reference": {"touchdown": scene.touchdown, "indicators": opt.reference.to_dict()},
        "active": [dataclasses.asdict(c) for c in opt.active],
        "sensitivity": opt.sensitivity,
        "starts": [dataclasses.asdict(s) for s in opt.starts],
        "local_optima": opt.local_optima, "seed": opt.seed,
        "solve_time_s": opt.solve_time, "build_time_s": opt.build_time,
        "notes": list(scene.notes) + list(opt.notes), "figures": figures,
    }


def _write_json(path: Path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(json.dumps(data, indent=2))
    tmp.replace(path)


def impact_table(scene: Scene, r: ImpactResult) -> str:
    """The indicators of one strike as a terminal table."""
    lines = [f"{scene.name}  ({scene.path})",
             f"model {scene.model}; body {scene.body.source}",
             f"{r.strike} strike on {math.degrees(scene.slope):+.1f} deg ground, friction {r.friction:g}",
             ""]
    lines += _indicator_lines(r)
    lines += ["", f"valid: {'yes' if r.valid else 'no'}"]
    lines += [f"warning: {w}" for w in r.warnings] + [f"note: {n}" for n in scene.notes]
    return "\n".join(lines)


def _indicator_lines(r: ImpactResult, other: ImpactResult | None = None) -> list[str]:
    """Indicator rows; with `other`, a second column (reference, then this one)."""
    def row(name, symbol, value, unit, fmt="{:+10.4f}"):
        cells = fmt.format(value(other)) + " " if other else ""
        return f"  {name:30s} {symbol:5s} {cells}{fmt.format(value(r))} {unit}"

    lines = [row("kinetic energy before", "T", lambda z: z.T, "J", "{:10.3f}"),
             row("absorbed (CMSKE)", "T_c", lambda z: z.T_c, "J", "{:10.3f}"),
             row("kinetic energy after", "T_a", lambda z: z.T_a, "J", "{:10.3f}")]
    for point in r.impulse:
        if other is None or point in other.impulse:
            open_ = "" if all(r.impulse_determined[point]) else "   (split not determined)"
            lines.append(row(f"ground impulse t, {point}", "t", lambda z, p=point: z.impulse[p][0], "N s")
                         + open_)
            lines.append(row(f"ground impulse n, {point}", "n", lambda z, p=point: z.impulse[p][1], "N s"))
    if r.mu_c is not None and (other is None or other.mu_c is not None):
        lines.append(row("critical friction", "mu_c", lambda z: z.mu_c, "", "{:10.4f}")
                     + ("" if other else f"   (momentum check {r.mu_c_momentum:.4f})"))
    else:
        lines.append(f"  {'critical friction':30s} mu_c  undefined: the ground does not push")
    if r.dv_trunk is not None:
        lines.append(row("trunk velocity change x", "dv", lambda z: z.dv_trunk[0], "m/s"))
        lines.append(row("trunk velocity change z", "dv", lambda z: z.dv_trunk[1], "m/s"))
    lines.append(row("centre-of-mass change x", "dv", lambda z: z.dv_com[0], "m/s"))
    lines.append(row("centre-of-mass change z", "dv", lambda z: z.dv_com[1], "m/s"))
    lines.append(row("condition of Phi M^-1 Phi^T", "", lambda z: z.condition, "", "{:10.3g}"))
    return lines


def solve_table(scene: Scene, opt) -> str:
    """The optimum against the reference posture, the active constraints, the sensitivities."""
    ok = "converged" if opt.success else "NOT CONVERGED"
    lines = [f"{scene.name}  ({scene.path})",
             f"model {scene.model}; body {scene.body.source}; {scene.strike} strike on "
             f"{math.degrees(scene.slope):+.1f} deg ground, friction {scene.friction:g}",
             f"objective {_objective_text(scene.problem.objective)}: {opt.objective:.6g} "
             f"({ok}: {opt.status})", ""]
    ref, best = touchdown_table(scene.strike, scene.state), touchdown_table(scene.strike, opt.state)
    lines.append(f"  {'posture (deg)':36s} {'reference':>10s} {'optimum':>10s}")
    for k in ref["angles_deg"]:
        mark = "  *" if k in scene.problem.variables else ""
        lines.append(f"  {k:36s} {ref['angles_deg'][k]:10.2f} {best['angles_deg'][k]:10.2f}{mark}")
    for k in ref["angular_velocity_dps"]:
        if "omega_" + k in scene.problem.variables:
            lines.append(f"  {'omega ' + k + ' (deg/s)':36s} {ref['angular_velocity_dps'][k]:10.1f} "
                         f"{best['angular_velocity_dps'][k]:10.1f}  *")
    lines += ["  (* decision variable)", "", f"  {'indicators':36s} {'reference':>10s} {'optimum':>10s}"]
    lines += _indicator_lines(opt.impact, opt.reference)
    lines += ["", f"valid at the optimum: {'yes' if opt.impact.valid else 'no'}"]
    lines += [f"warning: {w}" for w in opt.impact.warnings]
    if opt.active:
        lines += ["", "what holds the optimum where it is (multiplier = objective change per unit):"]
        for c in opt.active:
            lines.append(f"  {c.name:22s} at {c.bound:+.4g}  multiplier {c.multiplier:+.4g}: {c.meaning}")
    elif opt.success:
        lines += ["", "no constraint is active: an interior optimum"]
    if opt.sensitivity:
        s = opt.sensitivity
        lines += ["", f"sensitivity of the optimum: objective {s['d_objective_d_speed']:+.4g} per m/s "
                      f"of running speed, {s['d_objective_d_friction']:+.4g} per unit of friction"]
        for name, unit in (("speed", "m/s"), ("friction", "unit of friction")):
            if f"d_posture_d_{name}_deg" in s:
                moves = ", ".join(f"{k} {v:+.3g}" for k, v in s[f"d_posture_d_{name}_deg"].items())
                lines.append(f"  posture per {unit}: {moves} deg")
    converged = sum(st.converged for st in opt.starts)
    lines += ["", f"multi-start: {len(opt.starts)} starts (seed {opt.seed}), {converged} converged, "
                  f"{opt.local_optima} distinct optima; median solve {opt.solve_time * 1e3:.1f} ms, "
                  f"build {opt.build_time * 1e3:.0f} ms"]
    from .optimize import explain
    for st in opt.starts:
        if not st.converged:
            lines.append(f"  start {st.index}: {st.status} (objective {st.objective:.4g}), not used: "
                         f"{explain(st.status)}")
    lines += [f"note: {n}" for n in list(scene.notes) + list(opt.notes)]
    return "\n".join(lines)


def _objective_text(terms: dict) -> str:
    return " + ".join(f"{w:g} {k}" if w != 1 else k for k, w in terms.items())


if __name__ == "__main__":
    sys.exit(main())
