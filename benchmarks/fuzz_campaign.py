"""The bad-input attack at full size: the fuzz tests' mutants, many more of them, counted by
outcome. Classes: scenes through every command, compare scenes (`formopt compare --scene`),
marker maps (io.markerset.load), sweep parameters (sweep.parse_param and check_grid, the
checks a sweep makes before any work) and the numeric API (solve's settings, simulate_state,
Impact on any ground); and (issue 37) the command line's own options (a typed option's bad
value, an unknown or dangling option, --scheduler without an address), every scene command on
every shipped scene kind, a sweep's --out and `scenes copy`'s DIR holding a binary file, a
folder or a dangling link (a data file replaced or a write through a link counted apart), and
RBDS001's text trial files damaged (read and measured); every [stride] key of a torque+springs
and a muscle stride scene (parsed, no solve).

    python benchmarks/fuzz_campaign.py [--scale 1.0] [--only scenes,strides,compare,maps,params,api,options,kinds,outputs,mocap]
    python benchmarks/fuzz_campaign.py --only scenes:solve   # one command's scene mutants

Counts per class: "exit 2 one line" (a command) or "refused one line" (a function's
InputError), "success" (exit 0 or a result; exit 1 counted apart; a landing's Diverged, its
stated failure, counted apart), and what must stay zero:
a traceback (any other exception), a refusal whose message spans several lines or comes after
a (numpy) warning, or no answer within --timeout seconds (a hang).
"""

import argparse
import collections
import contextlib
import io
import signal
import sys
import tempfile
import time
import traceback
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

import test_bad_input as attack
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from formopt.cli import main
from formopt.io import markerset
from formopt.mechanics.errors import InputError
from formopt.mechanics.landing import Diverged
from formopt.studies import sweep

TIMEOUT = 60.0  # s per example: a call that has not answered by then is counted as a hang


class Hang(BaseException):
    """Raised by the alarm in an example that has not answered within TIMEOUT."""


def _alarm(signum, frame):
    raise Hang()


def counted(label, count, strategy, run):
    """Draw `count` examples of `strategy`; run(example) -> outcome text; print the counts."""
    outcomes = collections.Counter()

    @settings(max_examples=count, deadline=None, database=None, derandomize=True,
              suppress_health_check=list(HealthCheck))
    @given(example=strategy)
    def one(example):
        err, w = io.StringIO(), []
        signal.setitimer(signal.ITIMER_REAL, TIMEOUT)
        try:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()), \
                    warnings.catch_warnings(record=True) as w:
                warnings.simplefilter("always")
                outcome = run(example)
        except Hang:
            outcome = f"no answer in {TIMEOUT:g} s"
        except Diverged as failure:  # a landing's stated failure: the CLI's exit 1 with its reason
            outcome = "diverged, one line" if "\n" not in str(failure) else "diverged, several lines"
        except InputError as refusal:
            outcome = "refused one line" if "\n" not in str(refusal) else "refused, several lines"
            if w:  # a warning printed before the refusal: not alone on its line
                outcome = "refused after a warning"
        except BaseException as crash:  # counted: a traceback is what the attack looks for
            outcome = f"traceback {type(crash).__name__}"
            where = traceback.extract_tb(crash.__traceback__)[-1]
            print(f"  {label}: {type(crash).__name__}: {str(crash)[:200]!r} at {where.filename}:"
                  f"{where.lineno}; example {str(example)[:300]!r}", file=sys.__stderr__, flush=True)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        if outcome == "exit 2":
            outcome = "exit 2 one line" if len(err.getvalue().strip().splitlines()) == 1 else "exit 2, several lines"
        if outcome.startswith(("exit 2", "refused")) and w:  # a warning printed before the refusal
            outcome = "refused after a warning"
        outcomes[outcome] += 1

    one()
    print(f"{label:22s} {count:5d}: " + ", ".join(f"{k} {v}" for k, v in sorted(outcomes.items())),
          flush=True)


def command(argv) -> str:
    return f"exit {main(argv)}"


def scenes(n, folder, commands=("impact", "simulate", "solve", "sweep")):
    for cmd, needs, count, extra in (
            ("impact", None, n(1500), ["--json"]),
            ("simulate", "joints", n(400), ["--json", "--out", str(folder / "o")]),
            ("solve", "optimize", n(400), ["--json", "--starts", "1", "--out", str(folder / "o")]),
            ("sweep", "joints", n(100), ["--param", "knee_deg=10:12:2", "--out", str(folder / "s.csv"),
                                         "--no-progress", "--workers", "1"])):
        if cmd not in commands:
            continue
        counted(f"scene {cmd}", count, attack.scene_mutants(needs=needs),
                lambda d, cmd=cmd, extra=extra: command([cmd, str(attack.write(folder, d)), *extra]))


def compare_scenes(n, folder):
    mutants = st.builds(attack.mutant, st.just(attack.COMPARE_SCENE),
                        st.sampled_from([*attack.paths(attack.COMPARE_SCENE), ("trial", 0, "trial"),
                                         ("trial", 0, "sex")]),
                        st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]),
                        attack.REPLACEMENTS)
    counted("compare scene", n(1000), mutants, lambda d: command(
        ["compare", "--scene", str(attack.write(folder, d, "compare.toml")), "--out", str(folder / "c")]))


def marker_maps(n, folder):
    mutants = st.builds(attack.mutant, st.just(attack.MAP), st.sampled_from(list(attack.paths(attack.MAP))),
                        st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]),
                        attack.REPLACEMENTS)
    counted("marker map", n(2000), mutants,
            lambda d: markerset.load(attack.write(folder, d, "map.toml")) and "success")


def sweep_params(n, folder):
    def run(texts):
        sweep.check_grid([sweep.parse_param(t) for t in texts])
        return "success"
    counted("sweep parameters", n(5000), st.lists(attack.PARAM_TEXT, min_size=1, max_size=3), run)


def numeric_api(n, folder):
    context = attack.api_setup()
    counted("numeric API", n(2000), attack.api_calls(),
            lambda call: attack.call_api(*call, context) is not None and "success")


def stride_scenes(n, folder):
    """Every key of a torque+springs and a muscle [stride] scene deleted, misspelt or replaced,
    parsed (io.scene.parse: the checks before any solve)."""
    from formopt.io.scene import SceneError, parse

    def run(case):
        (base, path), action, replacement = case
        try:
            parse(attack.mutant(base, path, action, replacement))
        except SceneError as refusal:  # io's refusal: one line naming its key
            raise InputError(str(refusal)) from None
        return "success"
    counted("stride scene keys", n(3000), st.tuples(
        st.sampled_from(attack.STRIDE_PATHS), st.sampled_from(["delete", "misspell", "unicode key", "replace",
                                                               "replace"]), attack.REPLACEMENTS), run)


def options(n, folder):
    """A typed option with a bad value, an unknown or dangling option, --scheduler without an
    address, on a command line that would otherwise run (compare on RBDS001 T35)."""
    counted("options", n(600), attack.bad_options(), lambda case: command(
        [*attack.base_argv(case[0], folder, str(attack.RUN35)), *case[1]]))


def scene_kinds(n, folder):
    """Every scene command on every shipped scene (a stride's own solve left out: minutes)."""
    pairs = [(cmd, name) for cmd in ("impact", "simulate", "solve", "sweep --landings", "stride")
             for name in sorted(attack.SCENES) if not (cmd == "stride" and "stride" in attack.SCENES[name])]

    def run(pair):
        cmd, name = pair
        extra = (["--param", "friction=0.7:0.8:2", "--no-progress", "--workers", "1", "--out",
                  str(folder / f"k{time.monotonic_ns()}.csv")] if cmd.startswith("sweep") else
                 ["--json"] if cmd == "impact" else ["--json", "--out", str(folder / "k")])
        return command([*cmd.split(), str(attack.SHIPPED / name), *extra,
                        *(["--starts", "1"] if cmd == "solve" else [])])
    counted("scene kinds", min(n(len(pairs)), len(pairs)), st.sampled_from(pairs), run)


def outputs(n, folder):
    """What a sweep's --out and `scenes copy`'s DIR may hold: the data file is never replaced
    by a figure, nothing is written through a link (counted as "destroyed" or "escaped")."""
    def sweep_out(case):
        name, holds = case
        out = folder / f"o{time.monotonic_ns()}" / name
        out.parent.mkdir()
        outside = folder / f"outside{time.monotonic_ns()}"
        if holds == "binary":
            out.write_bytes(bytes(range(256)) * 4)
        elif holds == "dangling link":
            out.symlink_to(outside)
        outcome = command(["sweep", str(attack.SPRING), "--param", "ankle_deg=-12:-8:2", "--no-progress",
                           "--workers", "1", "--out", str(out)])
        if outside.exists():
            return "success, wrote through a link"
        if outcome == "exit 0" and not out.read_bytes().startswith(b"ankle_deg,"):
            return "success, the data replaced"
        return outcome

    def copy(case):
        name, holds = case
        folder_ = folder / f"d{time.monotonic_ns()}"
        folder_.mkdir()
        outside = folder / f"outside{time.monotonic_ns()}"
        target = folder_ / f"{name}.toml"
        if holds == "dangling link":
            target.symlink_to(outside)
        elif holds == "folder":
            target.mkdir()
        elif holds == "file":
            target.write_text("mine")
        outcome = command(["scenes", "copy", name, str(folder_)])
        return "success, wrote through a link" if outside.exists() else outcome

    names = st.sampled_from(["s.csv", "s.png", "s.PNG", "s.svg", "s", "s.csv.png", "s.CSV", "s.pdf"])
    counted("sweep --out", n(60), st.tuples(names, st.sampled_from(["nothing", "binary", "dangling link"])),
            sweep_out)
    counted("scenes copy", n(40), st.tuples(st.sampled_from(sorted(p.removesuffix(".toml") for p in attack.SCENES)),
                                            st.sampled_from(["nothing", "dangling link", "folder", "file"])), copy)


def mocap_files(n, folder):
    """RBDS001 T25's text files damaged (tests' damaged_text_trial) through read and measure."""
    static = attack.standing()
    counted("damaged trial files", n(300), attack.damaged_text_trial(),
            lambda case: attack.measured_or_refused(folder, case, static))


CLASSES = {"scenes": scenes, "strides": stride_scenes, "compare": compare_scenes, "maps": marker_maps,
           "params": sweep_params,
           "api": numeric_api, "options": options, "kinds": scene_kinds, "outputs": outputs,
           "mocap": mocap_files}


def main_():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--only", default=",".join(CLASSES), help="classes, comma-separated")
    parser.add_argument("--timeout", type=float, default=TIMEOUT, help="s per example (a hang)")
    args = parser.parse_args()
    globals()["TIMEOUT"] = args.timeout
    signal.signal(signal.SIGALRM, _alarm)
    folder = Path(tempfile.mkdtemp())
    def n(k):
        return max(1, int(k * args.scale))
    for name in args.only.split(","):  # "scenes:solve" runs one command's scene mutants
        kind, _, one = name.partition(":")
        CLASSES[kind](n, folder, *([(one,)] if one else []))


if __name__ == "__main__":
    main_()
