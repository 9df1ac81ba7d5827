"""formopt scenes [list | copy NAME DIR]: the scenes shipped with formopt, one line each, and a copy
of one to edit (every command also takes a shipped scene's name in place of a file)."""

from __future__ import annotations

from pathlib import Path

from .. import api
from ..io.files import OutputError, output_folder


def add_parser(commands):
    cmd = commands.add_parser("scenes", help="list the shipped scenes; `scenes copy NAME DIR` "
                              "copies one to edit")
    actions = cmd.add_subparsers(dest="action")
    actions.add_parser("list", help="the shipped scenes, one line each (the default)")
    copy = actions.add_parser("copy", help="copy the shipped scene NAME into the folder DIR")
    copy.add_argument("name", help="a shipped scene's name (`formopt scenes` lists them)")
    copy.add_argument("dir", help="folder to copy it into (created if needed)")


def run(args) -> int:
    if args.action != "copy":
        names = api.scenes()
        width = max(map(len, names))
        for name, title in names.items():
            print(f"{name:<{width}}  {title}")
        return 0
    source = api.scene_path(args.name)
    if source.parent != api.SCENES:
        raise api.SceneError("", f"{args.name}: not a shipped scene ({', '.join(api.scenes())})")
    target = output_folder(args.dir) / source.name
    try:  # "x": a new file only; a file, folder or symbolic link (even a dangling one) is refused
        fh = target.open("xb")
    except FileExistsError:
        raise OutputError(f"{target}: exists already (remove it or copy into another folder)") from None
    except OSError as err:
        raise OutputError(f"{target}: cannot write ({err.strerror})") from None
    try:
        with fh:
            fh.write(source.read_bytes())
    except OSError as err:  # a full disk: the file this copy created goes
        target.unlink()
        raise OutputError(f"{target}: cannot write ({err.strerror})") from None
    print(f"wrote {target}  (run it: formopt {command(source)} {target})")
    return 0


def command(path: Path) -> str:
    """The command a scene is made for: stride with a [stride] table, solve with an [optimize]
    one, simulate with a [landing] one, else impact."""
    text = path.read_text()
    if "\n[stride" in text:
        return "stride"
    return "solve" if "\n[optimize" in text else "simulate" if "\n[landing" in text else "impact"
