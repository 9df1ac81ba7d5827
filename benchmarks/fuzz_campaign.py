"""The bad-input attack at full size: the fuzz tests' mutants, many more of them, counted by
outcome. Classes: scenes through every command, compare scenes (`formopt compare --scene`),
marker maps (io.markerset.load), sweep parameters (sweep.parse_param and check_grid, the
checks a sweep makes before any work) and the numeric API (solve's settings, simulate_state,
Impact on any ground).

    python benchmarks/fuzz_campaign.py [--scale 1.0] [--only scenes,compare,maps,params,api]
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


CLASSES = {"scenes": scenes, "compare": compare_scenes, "maps": marker_maps, "params": sweep_params,
           "api": numeric_api}


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
