"""What every command shares: where its output goes."""

from __future__ import annotations

from pathlib import Path


def out_folder(args, default_name: str) -> Path:
    """--out if given, else out/<default_name> (a scene's or a trial's file stem)."""
    return Path(args.out) if getattr(args, "out", None) else Path("out") / Path(default_name).stem
