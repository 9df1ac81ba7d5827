"""formopt impact SCENE [--json]: the indicators of the foot strike a scene describes."""

from __future__ import annotations

from .. import api
from ..io.scene import landing_scene, load
from ..report.tables import impact_table
from .common import emit, scene_context


def add_parser(commands):
    cmd = commands.add_parser("impact", help="indicators of the foot strike a scene describes")
    cmd.add_argument("scene", help="scene file (TOML) or a shipped scene's name, e.g. forefoot_strike "
                     "(`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")


def run(args) -> int:
    scene = landing_scene(load(args.scene), "formopt impact")
    result = api.impact(scene)
    emit(args, {**scene_context(scene), **result.to_dict()}, impact_table(scene, result))
    return 0
