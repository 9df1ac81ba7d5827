"""The stride's mesh study: each strike of the shipped stride scene (the paper's body, 3.5 m/s,
tendons) at N intervals, trapezoid and Hermite-Simpson, one start: objective, cadence, stance,
the forward check, the contact drift, validity, the phases on a duration bound and the failed
checks, as a Markdown table.

    python benchmarks/stride_mesh.py [--nodes 20 40 80] [--strikes heel forefoot]

An optimum is an answer only where a finer mesh leaves it (design.md section 7): read the
cadence across N. The two transcriptions' objectives are different quadratures: compare their
cadences, not their costs.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

from formopt import load
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import optimum
from formopt.optim.stride.collocation import StrideNLP


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--nodes", type=int, nargs="+", default=[20, 40, 80])
    parser.add_argument("--strikes", nargs="+", default=["heel", "forefoot"])
    args = parser.parse_args()
    scene = load("stride")
    js = JointSpace(scene.body)
    print("| strike | transcription | N | success | objective | cadence | stance s | forward rad | drift mm | valid "
          "| on a bound; failed checks | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for strike in args.strikes:
        for transcription in ("trapezoid", "hermite-simpson"):
            for nodes in args.nodes:
                start = time.perf_counter()
                settings = dataclasses.replace(scene.settings, strike=strike, nodes=nodes, transcription=transcription)
                s = optimum(StrideNLP(js, settings), scene.speed, simulate=True, starts=1)
                print(f"| {strike} | {transcription} | {nodes} | {s.success} | {s.objective_value:.4f} | "
                      f"{s.cadence_spm:.1f} | {s.stance_s:.3f} | {s.checks['forward_theta']:.3f} | "
                      f"{s.checks['drift_m'] * 1e3:.2f} | {s.valid} | "
                      f"{'; '.join(filter(None, [s.bound_text(), *s.failed_checks])) or '-'} | "
                      f"{time.perf_counter() - start:.0f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
