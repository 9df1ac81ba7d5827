"""formopt impact SCENE [--json]: the indicators of the foot strike a scene describes."""

from __future__ import annotations

import json

from .. import api
from ..io.scene import load
from ..report.tables import impact_table


def add_parser(commands):
    cmd = commands.add_parser("impact", help="indicators of the foot strike a scene describes")
    cmd.add_argument("scene", help="scene file (TOML) or a shipped scene's name, e.g. forefoot_strike "
                     "(`formopt scenes` lists them, `formopt scenes copy NAME DIR` copies one)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")


def run(args) -> int:
    scene = load(args.scene)
    result = api.impact(scene)
    if args.json:
        print(json.dumps({"scene": scene.name, "model": scene.kind, "body": scene.body.source,
                          "touchdown": scene.touchdown, "notes": list(scene.notes),
                          **result.to_dict()}, indent=2))
    else:
        print(impact_table(scene, result))
    return 0
