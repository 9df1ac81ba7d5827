"""Command line of formopt: one module per command, one error path for all.

    formopt impact SCENE      the indicators of the foot strike a scene describes
    formopt solve SCENE       the touchdown posture that absorbs the least energy
    formopt simulate SCENE    the landing from touchdown
    formopt sweep SCENE       landings across a grid of parameters (resumable)
    formopt compare ...       measured touchdowns of a motion-capture trial against the optimum
    formopt bench             time and accuracy of each model level and numerical option
    formopt stride SCENE      the periodic running half stride: cadence, placement, budget
    formopt scenes            the shipped scenes; `formopt scenes copy NAME DIR` copies one
    formopt data              the shipped trial (RBDS001); `formopt data copy DIR` copies it

SCENE is a scene file (TOML) or the name of a shipped scene (`formopt solve demo`).

Exit status: 0 success; 1 a run that did not reach its goal (no start converged, a diverged
landing), with the reason; 2 bad input (scene, data, option or output path) or an output that
cannot be written (a full disk, a closed standard output), in one line naming the file, key or
path; 130 interrupted; 141 (quietly) a closed pipe. Any other error is a bug in formopt and shows
its traceback.
"""

from __future__ import annotations

import argparse
import functools
import os
import signal
import sys
import threading
from importlib import import_module

from .. import __version__
from ..mechanics.errors import one_line

__all__ = ["COMMANDS", "main", "parser"]  # the command modules are the CLI's own

INTERRUPTED = threading.Event()  # set by the first Ctrl-C from a shell (`_interrupted`)
GRACE_S = 2.0  # s: how long an interrupted run has to end by itself

# One module per command, imported when the command line is parsed (inside main's handlers).
COMMANDS = ("impact", "solve", "simulate", "sweep", "compare", "bench", "stride", "scenes", "data")
SCENE_COMMANDS = ("impact", "solve", "simulate", "sweep", "stride")  # SCENE: a file or a shipped name


class _Parser(argparse.ArgumentParser):
    """argparse's own errors (an unknown option, `--speed abc`) in one line naming the option
    and exit 2, as every bad input; the usage is what `--help` shows."""

    def error(self, message: str):
        from ..mechanics.errors import InputError

        raise InputError(f"{message} (`{self.prog} --help` lists the options)")


@functools.cache
def parser() -> argparse.ArgumentParser:
    """The command line's parser, built once per process (every command module imported): a
    script or test calling `main` many times does not pay the build each time (test_bad_input's
    ~550 calls: 3-4 s). Parsing does not change it."""
    top = _Parser(prog="formopt", description="The running form that wastes the least energy at "
                                              "foot strike.")
    top.add_argument("--version", action="version", version=f"formopt {__version__}")
    commands = top.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        import_module(f".{name}", __name__).add_parser(commands)
    return top


def main(argv=None) -> int:
    """Run one command; Ctrl-C at any moment is one line and exit 130, a closed pipe a quiet
    exit (141, as a shell reports SIGPIPE). From a shell (argv None, on the main thread) Ctrl-C
    goes through `_interrupted`; called with argv (a test, a script) it is Python's
    KeyboardInterrupt."""
    if sys.stdout is None:  # started with it closed (formopt ... >&-): nowhere to print the answer
        print("formopt: error: standard output is closed; redirect it (> FILE, or > /dev/null)",
              file=sys.stderr)
        return 2
    INTERRUPTED.clear()
    ended = threading.Event()
    shell = argv is None and threading.current_thread() is threading.main_thread()
    if shell:
        signal.signal(signal.SIGINT, _interrupted)
        threading.Thread(target=_watchdog, args=(ended,), daemon=True).start()
    stdout, sys.stdout = sys.stdout, _Stdout(sys.stdout)
    try:
        return _run(argv)
    except KeyboardInterrupt as err:
        print("formopt: interrupted" + (f": {err}" if str(err) else ""), file=sys.stderr)
        return _end_interrupted(shell)
    except BrokenPipeError:  # the reader went away (formopt ... | head): stop quietly
        _drop_stdout(stdout)
        return 141
    except Exception:
        if not INTERRUPTED.is_set():
            raise
        print("formopt: interrupted", file=sys.stderr)  # a KeyboardInterrupt CasADi turned into another error
        return _end_interrupted(shell)
    finally:
        sys.stdout = stdout
        ended.set()


class _Stdout:
    """Standard output while a command runs: a write that fails (a full disk, a device that
    refuses it) is an OutputError (one line, exit 2; the files already written stay whole)
    and what is still buffered is dropped, so that the interpreter's exit does not report it
    again. A closed pipe stays a BrokenPipeError (main's quiet exit)."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return self._stream.write(text)
        except OSError as err:
            raise _lost(err, self._stream) from None

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as err:
            raise _lost(err, self._stream) from None

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _lost(err: OSError, stream) -> OSError:
    """The error that stands for a failed write to standard output (see _Stdout)."""
    from ..io.files import OutputError

    if isinstance(err, BrokenPipeError):
        return err
    _drop_stdout(stream)
    return OutputError(f"standard output: cannot write ({err.strerror})")


def _drop_stdout(stream) -> None:
    """Standard output (`stream`) to /dev/null: what is still buffered goes nowhere, quietly."""
    os.dup2(os.open(os.devnull, os.O_WRONLY), stream.fileno())


def _end_interrupted(shell: bool) -> int:
    """130, an interrupted run's status. From a shell the process ends here (streams flushed,
    os._exit): a Ctrl-C that came while CasADi's libraries were loading could otherwise still
    kill the interpreter by SIGINT as it exits (status -2 instead of 130, 1 run in 10 with the
    signal in the first 0.6 s after CasADi loads, on a loaded machine, 2026-11-25)."""
    if shell:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):  # a closed pipe or stream: nothing more to say
                pass
        os._exit(130)
    return 130


def _interrupted(signum, frame) -> None:
    """SIGINT from a shell: KeyboardInterrupt once, so that a run can say what it wrote (a
    sweep: how many rows, and that the same command resumes); a delivery again is ignored
    (the handler stays installed: CasADi can deliver the same Ctrl-C again after main
    returned, which Python's own handler would turn into a death by SIGINT). Raised inside
    CasADi's calls, the interrupt can also turn into a SystemError (main reports it as the
    interrupt) or be swallowed while the run goes on (all three seen on compare, 2026-11-24):
    `_watchdog` ends such a run."""
    if INTERRUPTED.is_set():
        return
    INTERRUPTED.set()
    raise KeyboardInterrupt


def _watchdog(ended: threading.Event) -> None:
    """Once interrupted, give the run GRACE_S to end by itself, then one line and exit 130 at
    once. Rows are written as they finish and files by atomic renames, so nothing written is
    lost; a torn last row of a sweep is repaired on resume."""
    INTERRUPTED.wait()
    if not ended.wait(GRACE_S):
        os.write(2, b"formopt: interrupted\n")
        os._exit(130)


def _run(argv) -> int:
    from ..api import load, scene_path
    from ..io.files import OutputError
    from ..mechanics.errors import InputError
    from ..mechanics.landing import Diverged
    from ..studies.pool import WorkerLost
    from .common import check_kind

    args = None
    try:
        args = parser().parse_args(argv)
        if args.command in SCENE_COMMANDS:  # a scene the command cannot take: refused here
            args.scene = str(scene_path(args.scene))
            check_kind(args.command, load(args.scene), getattr(args, "landings", False))
        status = import_module(f".{args.command}", __name__).run(args)
        sys.stdout.flush()  # a closed pipe or a full disk shows here, not at the interpreter's exit
        return status
    except (InputError, OutputError) as err:
        where = getattr(args, "scene", None)
        prefix = f"{where}: " if where and isinstance(err, InputError) and \
            not str(err).startswith(str(where)) else ""
        print(f"formopt: error: {one_line(f'{prefix}{err}', 600)}", file=sys.stderr)
        return 2
    except (Diverged, WorkerLost) as err:  # not a result: the run did not reach its goal
        print(f"formopt: {one_line(err, 600)}", file=sys.stderr)
        return 1


