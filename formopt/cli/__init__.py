"""Command line of formopt: one module per command, one error path for all.

    formopt impact SCENE      the indicators of the foot strike a scene describes
    formopt solve SCENE       the touchdown posture that absorbs the least energy
    formopt simulate SCENE    the landing from touchdown
    formopt sweep SCENE       landings across a grid of parameters (resumable)
    formopt compare ...       measured touchdowns of a motion-capture trial against the optimum
    formopt bench             time and accuracy of each model level and numerical option
    formopt stride SCENE      the periodic running half stride: cadence, placement, budget

Exit status: 0 success; 1 a run that did not reach its goal (no start converged, a diverged
landing), with the reason; 2 bad input (scene, data, option or output path), in one line
naming the file, key or path; 130 interrupted. Any other error is a bug in formopt and shows
its traceback.
"""

from __future__ import annotations

import argparse
import sys

from .. import __version__
from ..io.files import OutputError
from ..mechanics.errors import InputError, one_line
from ..mechanics.landing import Diverged
from . import bench, compare, impact, simulate, solve, stride, sweep

COMMANDS = {"impact": impact, "solve": solve, "simulate": simulate, "sweep": sweep,
            "compare": compare, "bench": bench, "stride": stride}


def parser() -> argparse.ArgumentParser:
    top = argparse.ArgumentParser(prog="formopt", description="The running form that wastes "
                                  "the least energy at foot strike.")
    top.add_argument("--version", action="version", version=f"formopt {__version__}")
    commands = top.add_subparsers(dest="command", required=True)
    for name, module in COMMANDS.items():
        module.add_parser(commands)
    return top


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        return COMMANDS[args.command].run(args)
    except (InputError, OutputError) as err:
        where = getattr(args, "scene", None)
        prefix = f"{where}: " if where and isinstance(err, InputError) and \
            not str(err).startswith(str(where)) else ""
        print(f"formopt: error: {one_line(f'{prefix}{err}', 600)}", file=sys.stderr)
        return 2
    except Diverged as err:  # not a result: the run did not reach its goal
        print(f"formopt: {one_line(err, 600)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as err:
        print("formopt: interrupted" + (f": {err}" if str(err) else ""), file=sys.stderr)
        return 130


