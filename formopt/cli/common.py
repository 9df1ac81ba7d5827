"""What every command shares: where its output goes."""

from __future__ import annotations

import json
from pathlib import Path

from ..io.files import output_folder, write_json
from ..io.stride_scene import StrideScene
from ..mechanics.errors import InputError


def out_folder(args, default_name: str) -> Path:
    """--out if given (an empty --out "" is refused by output_folder, not taken as "not
    given"), else out/<default_name> (a scene's or a trial's file stem), created now: a
    command checks where its output goes before it computes anything."""
    out = getattr(args, "out", None)
    return output_folder(out if out is not None else Path("out") / Path(default_name).stem)


def check_kind(command: str, scene, landings: bool = False) -> None:
    """Refuse, in one line naming the command to use, a scene `command` cannot take: a stride
    scene anywhere but stride and sweep (its --landings too: a stride has no touchdown to
    land from), a touchdown scene in stride, a scene without [optimize] in solve."""
    if isinstance(scene, StrideScene):
        if command in ("impact", "simulate", "solve") or landings:
            what = "sweep --landings" if landings else command
            raise InputError(f"a stride scene (a [stride] table): run `formopt stride` on it, or "
                             f"`formopt sweep` over its stride values; `formopt {what}` needs a "
                             "[touchdown] table")
    elif command == "stride":
        use = "`formopt solve`" if scene.problem is not None else "`formopt simulate` or `formopt impact`"
        raise InputError(f"not a stride scene (no [stride] table): run {use} on it; `formopt stride` "
                         "needs a [stride] table (`formopt scenes copy stride DIR` copies one)")
    elif command == "solve" and scene.problem is None:
        raise InputError("no [optimize] table, nothing to optimise: run `formopt simulate` or "
                         "`formopt impact` on it, or add an [optimize] table (`formopt scenes copy "
                         "demo DIR` copies one)")


FORMATS = ("png", "svg", "pdf")


def add_format(cmd) -> None:
    """--format: the figures' file format."""
    cmd.add_argument("--format", choices=FORMATS, default="png",
                     help="figure format: png (default), svg or pdf (vector, for publication)")


def scene_context(scene) -> dict:
    """What a scene's report says about the run: the scene, model, body, its touchdown (the
    scene file's schema, degrees) and the loader's notes."""
    return {"scene": scene.name, "model": scene.kind, "body": scene.body.source,
            "touchdown": scene.touchdown, "notes": list(scene.notes)}


def emit(args, report: dict, table: str, json_path=None, files=(), show: bool = True) -> None:
    """The one way a report leaves a command: written whole to `json_path` (when given), then
    printed as JSON (--json: nothing else on stdout) or as the table and the files written;
    `show` False writes only (one trial of several)."""
    files = [*files, *([write_json(json_path, report)] if json_path else [])]
    if not show:
        return
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(table)
        if files:
            print(f"\nwrote {', '.join(str(f) for f in files)}")
