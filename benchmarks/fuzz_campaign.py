"""The bad-input attack at full size: the fuzz tests' scene mutants, many more of them,
through every command, counted by outcome.

    python benchmarks/fuzz_campaign.py [--scale 1.0]

Counts per command: exit 2 with one line, exit 0, exit 1, and what must stay zero: a
traceback, or an exit 2 whose message spans several lines.
"""

import argparse
import collections
import contextlib
import io
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from hypothesis import HealthCheck, given, settings
from test_bad_input import scene_mutants, write

from formopt.cli import main


def campaign(command, needs, count, extra, folder):
    outcomes = collections.Counter()

    @settings(max_examples=count, deadline=None, database=None, derandomize=True,
              suppress_health_check=list(HealthCheck))
    @given(data=scene_mutants(needs=needs))
    def attack(data):
        err = io.StringIO()
        try:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                code = main([command, str(write(folder, data)), *extra])
        except BaseException as crash:  # counted: a traceback is what the attack looks for
            outcomes[f"traceback {type(crash).__name__}"] += 1
            return
        lines = err.getvalue().strip().splitlines()
        outcomes["exit 2, several lines" if code == 2 and len(lines) != 1 else f"exit {code}"] += 1

    attack()
    print(f"{command:9s} {count:5d} mutants: " + ", ".join(f"{k} {v}" for k, v in sorted(outcomes.items())))


def main_():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scale", type=float, default=1.0)
    args = parser.parse_args()
    folder = Path(tempfile.mkdtemp())
    n = lambda k: max(1, int(k * args.scale))  # noqa: E731
    campaign("impact", None, n(1500), ["--json"], folder)
    campaign("simulate", "joints", n(400), ["--json", "--out", str(folder / "o")], folder)
    campaign("solve", "optimize", n(400), ["--json", "--starts", "1", "--out", str(folder / "o")], folder)
    campaign("sweep", "joints", n(100), ["--param", "knee_deg=10:12:2", "--out", str(folder / "s.csv"),
                                         "--no-progress", "--workers", "1"], folder)


if __name__ == "__main__":
    main_()
