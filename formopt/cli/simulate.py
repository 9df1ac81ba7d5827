"""formopt simulate SCENE: the landing from touchdown (figures, CSV, JSON)."""

from __future__ import annotations

import dataclasses

from .. import api
from ..io.files import save_figure, write_csv
from ..io.scene import landing_scene, load
from ..mechanics.landing import history_rows
from ..report.figures import landing_figures
from ..report.tables import landing_table
from .common import add_format, emit, out_folder, scene_context


def add_parser(commands):
    cmd = commands.add_parser("simulate", help="follow the landing from the touchdown")
    add_format(cmd)
    cmd.add_argument("scene", help="scene file with a [landing] table or a shipped scene's name, "
                     "e.g. landing_spring (`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for figures, CSV and JSON (default out/<scene>)")


def run(args) -> int:
    scene = landing_scene(load(args.scene), "formopt simulate")
    out = out_folder(args, scene.path or scene.name)
    landing = api.simulate(scene)
    model = scene.model()
    files = [save_figure(fig, out / f"{name}.{args.format}")
             for name, fig in landing_figures(landing, model, scene.slope, scene.strike).items()]
    files.append(write_csv(out / "landing.csv", history_rows(landing, model)))
    report = {**scene_context(scene), "joints": dataclasses.asdict(scene.joints),
              **landing.to_dict(), "files": [str(f) for f in files]}
    emit(args, report, landing_table(scene, landing), out / "landing.json", files)
    return 1 if landing.unsound else 0  # its own numerical checks fail: not a result to use
