"""Every shipped stride scene and variant at its own nodes, one start from the generic guess,
as a regression record (JSON) and a
line each: objective, cadence, stance, impacts, iterations, the forward check, balance,
validity, and the CPU seconds of the NLP's graph and of the solve with its checks.

    python benchmarks/stride_scenes.py OUT.json

Compare two records (before and after a change) to see which numbers moved; a moved optimum
with the same NLP is another local optimum (issue 34).
"""

from __future__ import annotations

import dataclasses
import json
import resource
import sys

from formopt import load
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import optimum
from formopt.optim.stride.collocation import StrideNLP

CASES = [("stride", s, {}) for s in ("heel", "forefoot", "flat")] + [
    ("stride_rbds001", "heel", {}), ("stride", "heel", {"objective": "work"}),
    ("stride", "heel", {"objective": "metabolic"}), ("stride", "heel", {"impact_weight": 1.0}),
    ("stride", "forefoot", {"law": "coulomb"})]


def cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def main(path: str) -> int:
    out = {}
    for name, strike, change in CASES:
        scene = load(name)
        settings = dataclasses.replace(scene.settings, strike=strike, **change)
        start = cpu()
        nlp = StrideNLP(JointSpace(scene.body), settings)
        graph = cpu() - start
        s = optimum(nlp, scene.speed, scene.slope, scene.friction, scene.cadence, simulate=True)
        key = f"{name}/{strike}/{change}"
        out[key] = {"success": s.success, "objective": s.objective_value, "cadence": s.cadence_spm,
                    "stance": s.stance_s, "iterations": s.iterations, "graph_cpu": graph,
                    "solve_cpu": cpu() - start - graph, "impacts": s.budget["impacts_J"],
                    "forward": s.checks.get("forward_theta"), "balance": s.budget["balance_J"], "valid": s.valid}
        print(key, json.dumps(out[key]), flush=True)
    with open(path, "w") as fh:
        json.dump(out, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1] if len(sys.argv) > 1 else "stride_scenes.json"))
