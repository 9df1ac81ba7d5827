"""formopt data [copy DIR]: the real trial shipped with formopt (RBDS001 at 3.5 m/s, the first
8 s, and its static trial; CC BY 4.0, credited in its README), and a copy of it to run compare
on after `pip install formopt`."""

from __future__ import annotations

import shutil
from pathlib import Path

from ..io.files import OutputError, output_folder

SHIPPED = Path(__file__).resolve().parent.parent / "data" / "rbds001"
TRIAL, STATIC = "RBDS001runT35_8s.c3d", "RBDS001static.c3d"
BODY = "--mass 62 --height 1.81"  # RBDS001 (RBDSinfo.txt)


def add_parser(commands):
    cmd = commands.add_parser("data", help="the shipped trial (RBDS001, 3.5 m/s); `data copy DIR` "
                              "copies it to run compare on")
    actions = cmd.add_subparsers(dest="action")
    copy = actions.add_parser("copy", help="copy the shipped trial, its static trial, README and "
                              "LICENSE into the folder DIR")
    copy.add_argument("dir", help="folder to copy them into (created if needed)")


def run(args) -> int:
    files = sorted(p for p in SHIPPED.iterdir() if p.is_file())
    if args.action != "copy":
        for p in files:
            print(f"{p.name:24s} {p.stat().st_size // 1024:5d} kB")
        print(f"(in {SHIPPED}; `formopt data copy DIR` copies them; CC BY 4.0: see README.md)")
        return 0
    folder = output_folder(args.dir)
    clash = [folder / p.name for p in files if (folder / p.name).exists()]
    if clash:
        raise OutputError(f"{clash[0]}: exists already (remove it or copy into another folder)")
    for p in files:
        shutil.copyfile(p, folder / p.name)
    print(f"wrote {', '.join(str(folder / p.name) for p in files)}\n(run it: formopt compare "
          f"--trial {folder / TRIAL} --static {folder / STATIC} {BODY})")
    return 0
