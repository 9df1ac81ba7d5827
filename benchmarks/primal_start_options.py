"""Experiment (issue 34 item 5): compare's stride section with other IPOPT options for the
primal warm start (stride_map.warm's branch from a neighbouring problem's variables alone, used
by the band's objective variant, compare_band.stride_at, and by stride_map's sweeps), run
through benchmarks/compare_speed.py --stride in this process, formopt itself unchanged.

    python benchmarks/primal_start_options.py --ipopt '{"mu_strategy": "monotone", "mu_init": 1e-4}' \
        [--scope band|map|all] [--chain] -- --stride T35 --workers 1 --solves --json F

`--ipopt`: options over the NLP's own for that branch (a solver named `stride_primal` in
--solves, sharing the cold solver's derivatives); a failed solve falls back to the NLP's own
solver. `--scope`: band (compare_band.stride_at only), map (stride_map's sweeps only) or all.
`--chain`: the band's objective variant solves its cadences warm, with multipliers, from its own
free optimum (solved first with --workers 1) instead of the nominal's strides' variables.
"""

from __future__ import annotations

import argparse
import json
import runpy
import sys
from pathlib import Path

import casadi as ca

from formopt.studies import compare_band, stride_map

OWN_WARM, OWN_STRIDE_AT = stride_map.warm, compare_band.stride_at


def primal_solver(nlp, ipopt: dict):
    """The NLP's IPOPT with `ipopt` over its options, sharing the cold solver's derivatives."""
    solver = nlp.solver
    if getattr(nlp, "_primal_for", None) is not solver:
        shared = {k: solver.get_function(f"nlp_{f}")
                  for k, f in (("grad_f", "grad_f"), ("jac_g", "jac_g"), ("hess_lag", "hess_l"))}
        nlp._primal_solver = ca.nlpsol("stride_primal", "ipopt", nlp._nlp, {
            "ipopt": {**nlp.options, **ipopt}, "print_time": False, **shared})
        nlp._primal_for = solver
    return nlp._primal_solver


def warm_with(ipopt: dict):
    """stride_map.warm with `ipopt` on its primal branch."""
    def warm(nlp, previous, speed, slope, mu, cadence):
        if previous.solved is not None and previous.solved.layout == nlp.layout:
            return OWN_WARM(nlp, previous, speed, slope, mu, cadence)
        guess = stride_map.solution(previous, nlp)
        got = nlp._run(primal_solver(nlp, ipopt), {"x0": nlp.blocks.join(nlp._with_power_split(guess))},
                       speed, slope, mu, cadence)
        return got if got.success else nlp.solve(guess, speed, slope, mu, cadence)
    return warm


FREES: dict = {}


def chained_stride_at(task: tuple):
    """compare_band.stride_at, a variant without a start of its own layout (the objective's)
    started at a cadence from its own free optimum (its multipliers)."""
    scene, starts, cadence = task
    layout = scene.nlp().layout
    if cadence is None:
        FREES[layout] = got = OWN_STRIDE_AT(task)
        return got
    own = FREES.get(layout)
    if own is not None and own.success and not any(s.solved is not None and s.solved.layout == layout
                                                   for s in starts):
        starts = [own, *starts]
    return OWN_STRIDE_AT((scene, starts, cadence))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ipopt", type=json.loads, default={})
    parser.add_argument("--scope", choices=("band", "map", "all"), default="band")
    parser.add_argument("--chain", action="store_true")
    args, rest = parser.parse_known_args()
    if args.ipopt:
        if args.scope in ("band", "all"):
            compare_band.warm = warm_with(args.ipopt)
        if args.scope in ("map", "all"):
            stride_map.warm = warm_with(args.ipopt)
    if args.chain:
        compare_band.stride_at = chained_stride_at
    sys.argv = ["compare_speed.py", *[a for a in rest if a != "--"]]
    runpy.run_path(str(Path(__file__).with_name("compare_speed.py")), run_name="__main__")


if __name__ == "__main__":
    main()
