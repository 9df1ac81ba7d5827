"""Command line: `formopt impact SCENE [--json]`.

Bad input (a scene that does not validate, a posture the impact map cannot take) prints one
line naming the key and the reason and exits with status 2.
"""

from __future__ import annotations

import argparse
import json
import sys

from .impact import ImpactResult, impact
from .scene import Scene, SceneError, load


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="formopt", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    cmd = commands.add_parser("impact", help="indicators of the foot strike a scene describes")
    cmd.add_argument("scene", help="scene file (TOML), e.g. problems/forefoot_strike.toml")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = parser.parse_args(argv)
    try:
        scene = load(args.scene)
        result = impact(scene)
    except (SceneError, ValueError) as err:
        print(f"formopt: error: {args.scene}: {err}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps({"scene": scene.name, "model": scene.model, "body": scene.body.source,
                          "touchdown": scene.touchdown, "notes": list(scene.notes),
                          **result.to_dict()}, indent=2))
    else:
        print(impact_table(scene, result))
    return 0


def impact_table(scene: Scene, r: ImpactResult) -> str:
    """The indicators of one strike as a terminal table."""
    import math

    lines = [f"{scene.name}  ({scene.path})",
             f"model {scene.model}; body {scene.body.source}",
             f"{r.strike} strike on {math.degrees(scene.slope):+.1f} deg ground, friction {r.friction:g}",
             "",
             f"  {'kinetic energy before':30s} T     {r.T:10.3f} J",
             f"  {'absorbed (CMSKE)':30s} T_c   {r.T_c:10.3f} J   ({100 * r.T_c / r.T:.2f} % of T)",
             f"  {'kinetic energy after':30s} T_a   {r.T_a:10.3f} J"]
    for point, (t, n) in r.impulse.items():
        open_ = "" if all(r.impulse_determined[point]) else "   (split not determined)"
        lines.append(f"  {'ground impulse, ' + point:30s} t, n  {t:+10.4f} {n:+10.4f} N s{open_}")
    lines.append(f"  {'critical friction':30s} mu_c  {r.mu_c:10.4f}     (momentum check {r.mu_c_momentum:.4f})")
    if r.dv_trunk is not None:
        lines.append(f"  {'trunk velocity change':30s} dv    {r.dv_trunk[0]:+10.4f} {r.dv_trunk[1]:+10.4f} m/s")
    lines.append(f"  {'centre-of-mass velocity change':30s} dv    {r.dv_com[0]:+10.4f} {r.dv_com[1]:+10.4f} m/s")
    lines.append(f"  {'condition of Phi M^-1 Phi^T':30s}       {r.condition:10.3g}")
    lines += ["", f"valid: {'yes' if r.valid else 'no'}"]
    lines += [f"warning: {w}" for w in r.warnings] + [f"note: {n}" for n in scene.notes]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
