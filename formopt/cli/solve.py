"""formopt solve SCENE: the touchdown posture that absorbs the least energy."""

from __future__ import annotations

import dataclasses
import sys

from .. import api
from ..io.files import save_figure
from ..io.scene import landing_scene, load, touchdown_table
from ..mechanics.errors import InputError
from ..report.figures import indicator_figure, posture_figure
from ..report.tables import solve_table
from .common import add_format, emit, out_folder, scene_context


def add_parser(commands):
    cmd = commands.add_parser("solve", help="optimise the touchdown posture of a scene")
    add_format(cmd)
    cmd.add_argument("scene", help="scene file with an [optimize] table or a shipped scene's name, "
                     "e.g. demo (`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for figures and result files (default out/<scene>)")
    cmd.add_argument("--starts", type=int, help="number of starts (overrides the scene)")
    cmd.add_argument("--seed", type=int, help="seed of the random starts (overrides the scene)")
    cmd.add_argument("--compiled", action="store_true",
                     help="compile the NLP's functions to C (the scene's [numerics] compiled = true)")


def run(args) -> int:
    scene = landing_scene(load(args.scene), "formopt solve")
    if args.compiled:
        scene = dataclasses.replace(scene, numerics=dataclasses.replace(scene.numerics, compiled=True))
    if args.starts is not None and args.starts < 1:
        raise InputError("--starts must be at least 1")
    assert scene.problem is not None  # a scene without [optimize]: refused by cli.common.check_kind
    seed = args.seed if args.seed is not None else scene.problem.seed

    def progress(k, n, start):
        if k == 1:  # once the problem is built: a bad scene's error comes alone
            print(f"{scene.name}: seed {seed}", file=sys.stderr)
        print(f"  start {k}/{n}: {start.status}, objective {start.objective:.6g} "
              f"({start.iterations} iterations)", file=sys.stderr)

    out = out_folder(args, scene.path or scene.name)
    opt = api.solve(scene, progress=progress, starts=args.starts, seed=args.seed)
    postures = [(scene.state, "reference", "0.55"),
                (opt.state, "optimum" if opt.success else "not converged", "tab:blue")]
    figures = [save_figure(posture_figure(scene.body, scene.strike, scene.slope, postures),
                           out / f"posture.{args.format}"),
               save_figure(indicator_figure({"reference": opt.reference, "optimum": opt.impact}),
                           out / f"indicators.{args.format}")]
    result = opt.to_dict()
    report = {**scene_context(scene), "objective_terms": scene.problem.objective, **result,
              "touchdown": touchdown_table(scene.strike, opt.state),
              "reference": {"touchdown": scene.touchdown, **result["reference"]},
              "notes": list(scene.notes) + result["notes"], "figures": [str(f) for f in figures]}
    emit(args, report, solve_table(scene, opt), out / "result.json", figures)
    return 0 if opt.success else 1
