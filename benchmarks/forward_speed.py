"""The stride's forward check (optim.stride.checks.forward): its CPU and its figures on a few
solved strides, so two versions of the check can be timed and compared on the same solutions.

    python benchmarks/forward_speed.py solve [--cache DIR]     solve the CASES once (pickled)
    python benchmarks/forward_speed.py time [--cache DIR] [--repeats N] [--cases ...]
    python benchmarks/forward_speed.py pin [--cache DIR]       write tests' pinned solutions
    python benchmarks/forward_speed.py cli [--repeats N]       `formopt stride stride_rbds001
                                                                 --strike heel --json`'s CPU

`time` prints, per case, the forward check's CPU (time.process_time, median of N repeats, the
NLP built beforehand, its first check untimed apart) and its figures (reset_theta, theta,
periodicity); `cli` runs the command in a subprocess N times and prints the median of its CPU
(its children's rusage). Run it with PYTHONPATH at the formopt tree to be measured (the cache
of solutions is shared). `pin` writes tests/optim/stride/forward_pins.npz: each case's blocks,
parameters and settings, and the check's figures as this tree computes them (the pinned
figures of tests/optim/stride/test_forward.py: written at 1675f05, scipy's DOP853 and LSODA,
before CVODES replaced them; pinning again pins this tree's own figures). Measured 2026-11-27:
docs/reference/performance.md, "The forward check in C".

The paper's body at 3.5 m/s, one start each: a 24-node heel, flat and forefoot strike, a 40-node
heel strike, a 24-node sliding forefoot strike (Coulomb, mu 0.3: tests/optim/test_stride_slide.py's),
a 24-node Hermite-Simpson heel strike and a 14-node muscle-driven flat strike
(tests/optim/stride/test_muscle_stride.py's).
"""

from __future__ import annotations

import argparse
import json
import pickle
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.checks import forward

SPEED = 3.5
CASES = {  # name: (StrideSettings' fields, with muscles = True for the body's; mu)
    "heel24": ({"strike": "heel", "nodes": 24}, 0.8),
    "heel40": ({"strike": "heel", "nodes": 40}, 0.8),
    "flat24": ({"strike": "flat", "nodes": 24}, 0.8),
    "forefoot24": ({"strike": "forefoot", "nodes": 24}, 0.8),
    "slide24": ({"strike": "forefoot", "nodes": 24, "law": "coulomb"}, 0.3),
    "hermite24": ({"strike": "heel", "nodes": 24, "transcription": "hermite-simpson"}, 0.8),
    "muscles14": ({"strike": "flat", "nodes": 14, "objective": "metabolic", "muscles": True}, 0.8),
}
CACHE = Path("/tmp/formopt_forward_cases")
PINS = Path(__file__).resolve().parents[1] / "tests" / "optim" / "stride" / "forward_pins.npz"
FIGURES = ("reset_theta", "theta", "thetad", "periodicity")


def settings(fields: dict) -> StrideSettings:
    """StrideSettings of a case's fields (muscles = True: the paper body's muscles)."""
    fields = dict(fields)
    if fields.pop("muscles", False):
        fields["muscles"] = body_muscles(paper_body())
    return StrideSettings(**fields)


def nlp_of(fields: dict) -> StrideNLP:
    return StrideNLP(JointSpace(paper_body()), settings(fields))


def solve(cache: Path) -> None:
    """Solve each case (optimum, one start, no forward check) and pickle its settings' fields
    (the touchdown's mode and slip of the NLP variant that solved it), blocks and parameters."""
    cache.mkdir(parents=True, exist_ok=True)
    for name, (fields, mu) in CASES.items():
        nlp = nlp_of(fields)
        stride = optimum(nlp, SPEED, 0.0, mu, simulate=False)
        touchdown = stride.impacts[-1]
        fields = {**fields, "touchdown": touchdown["mode"], "slip": int(touchdown.get("slip", 1))}
        with open(cache / f"{name}.pkl", "wb") as out:
            pickle.dump({"fields": fields, "blocks": stride.solved.blocks,
                         "parameters": stride.solved.parameters}, out)
        print(name, stride.status, f"{stride.cadence_spm:.1f} steps/min", touchdown["mode"], flush=True)


def load(cache: Path, name: str) -> dict:
    with open(cache / f"{name}.pkl", "rb") as f:
        return pickle.load(f)


def timed(nlp: StrideNLP, case: dict, repeats: int) -> tuple[dict, float, float]:
    """(figures, the first check's CPU s, the median CPU s of `repeats` more)."""
    start = time.process_time()
    out = forward(nlp, case["blocks"], case["parameters"])
    first = time.process_time() - start
    cpu = []
    for _ in range(repeats):
        start = time.process_time()
        forward(nlp, case["blocks"], case["parameters"])
        cpu.append(time.process_time() - start)
    return out, first, statistics.median(cpu)


def time_cases(cache: Path, names: list[str], repeats: int) -> None:
    print(f"{'case':<11} {'first s':>8} {'median s':>9} " + " ".join(f"{k:>13}" for k in FIGURES))
    for name in names:
        case = load(cache, name)
        nlp = nlp_of(case["fields"])
        out, first, median = timed(nlp, case, repeats)
        print(f"{name:<11} {first:8.3f} {median:9.3f} " + " ".join(f"{out[k]:13.6e}" for k in FIGURES), flush=True)


def pin(cache: Path) -> None:
    """tests' pinned solutions and this tree's figures of them (module docstring)."""
    arrays: dict = {}
    for name in CASES:
        case = load(cache, name)
        out = forward(nlp_of(case["fields"]), case["blocks"], case["parameters"])
        arrays.update({f"{name}/{k}": v for k, v in case["blocks"].items() if k[:2] in ("X_", "Z_", "U_", "T_")})
        arrays[f"{name}/meta"] = np.array(json.dumps({
            "fields": case["fields"], "parameters": {k: None if v is None else float(v) for k, v in case["parameters"].items()},
            "figures": {k: v for k, v in out.items() if np.isscalar(v) or isinstance(v, list)}}))
        print(name, {k: out[k] for k in FIGURES}, flush=True)
    np.savez_compressed(PINS, **arrays)


def cli(repeats: int) -> None:
    """The CPU (s, its process and children) of `formopt stride stride_rbds001 --strike heel --json`."""
    cpu = []
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, "-m", "formopt.cli", "stride", "stride_rbds001", "--strike", "heel", "--json"],
                       check=True, capture_output=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    print("formopt stride stride_rbds001 --strike heel --json: CPU s", " ".join(f"{c:.2f}" for c in cpu),
          f"median {statistics.median(cpu):.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=("solve", "time", "pin", "cli"))
    parser.add_argument("--cache", type=Path, default=CACHE)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    args = parser.parse_args()
    if args.command == "solve":
        solve(args.cache)
    elif args.command == "time":
        time_cases(args.cache, args.cases, args.repeats)
    elif args.command == "pin":
        pin(args.cache)
    else:
        cli(args.repeats)


if __name__ == "__main__":
    main()
