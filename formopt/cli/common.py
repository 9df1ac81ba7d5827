"""What every command shares: where its output goes."""

from __future__ import annotations

import json
from pathlib import Path

from ..io.files import output_folder, write_json


def out_folder(args, default_name: str) -> Path:
    """--out if given, else out/<default_name> (a scene's or a trial's file stem), created
    now: a command checks where its output goes before it computes anything."""
    return output_folder(Path(args.out) if getattr(args, "out", None)
                         else Path("out") / Path(default_name).stem)


FORMATS = ("png", "svg", "pdf")


def add_format(cmd) -> None:
    """--format: the figures' file format."""
    cmd.add_argument("--format", choices=FORMATS, default="png",
                     help="figure format: png (default), svg or pdf (vector, for publication)")


def emit(args, report: dict, json_path, table: str, files) -> None:
    """Write the JSON report, then print it (--json) or the table and the files written."""
    write_json(json_path, report)
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(table)
        print(f"\nwrote {', '.join(str(f) for f in [*files, json_path])}")
