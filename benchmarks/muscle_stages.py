"""Where the muscle-driven stride's time goes, stage by stage (issue 33 item 6).

    python benchmarks/muscle_stages.py [--speed 3.5] [--nodes 40] [--ipopt JSON] [--continuation JSON] [--warm JSON]

RBDS001's body, heel, interpreted: the stages of benchmarks/stride_muscles.py's muscle row apart,
as local.muscle_start runs them: the torque+springs optimum from the generic guess, the muscles'
solve at each weight of problem.RESERVE_CONTINUATION from its split (guess.from_torques), the
solve at the setting's reserve weight from that (cold) and 0.1 m/s faster from it
(StrideNLP.resolve, warm). Per stage: user and system CPU s (the process's threads), minor page
faults, IPOPT's iterations, the objective and the cadence, so that an option's effect on the
speed is seen apart from its effect on the optimum. `--ipopt` IPOPT options over collocation's
for every muscle solve, `--continuation` over ipopt_options.CONTINUATION_IPOPT for the
continuation's, `--warm` over ipopt_options.MUSCLE_WARM_START for the warm start (a what-if:
the module's dict updated). Measure only.
"""

from __future__ import annotations

import argparse
import json
import resource

from stride_muscles import rung_settings

from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, ipopt_options
from formopt.optim.stride.checks import half_period
from formopt.optim.stride.guess import ballistic, from_torques
from formopt.optim.stride.local import torque_start
from formopt.optim.stride.problem import RESERVE_CONTINUATION


def stage(label: str, nlp: StrideNLP, run):
    """run()'s Solved, with its CPU, page faults and result printed on one line."""
    before = resource.getrusage(resource.RUSAGE_SELF)
    solved = run()
    after = resource.getrusage(resource.RUSAGE_SELF)
    print(f"{label:16s} user {after.ru_utime - before.ru_utime:6.2f} sys {after.ru_stime - before.ru_stime:5.2f} "
          f"faults {after.ru_minflt - before.ru_minflt:8d} it {solved.iterations:4d} "
          f"objective {solved.objective:.6f} {60.0 / half_period(nlp, solved.blocks):6.2f} steps/min  {solved.status}",
          flush=True)
    return solved


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--nodes", type=int, default=40)
    parser.add_argument("--ipopt", type=json.loads, default=None, help="IPOPT options of the muscle solves (JSON)")
    parser.add_argument("--continuation", type=json.loads, default={}, help="over CONTINUATION_IPOPT (JSON)")
    parser.add_argument("--warm", type=json.loads, default={}, help="over MUSCLE_WARM_START (JSON)")
    args = parser.parse_args()
    ipopt_options.MUSCLE_WARM_START.update(args.warm)
    body, v = scaled_body(62.0, 1.81), args.speed
    nlp = StrideNLP(JointSpace(body), rung_settings("muscles", body, args.nodes), args.ipopt, False)
    print(f"RBDS001's body, heel, {args.nodes} nodes, {v:g} m/s, interpreted; CPU s")
    base = torque_start(nlp)
    torques = stage("torque+springs", base, lambda: base.solve(ballistic(base, v), v))
    start = from_torques(nlp, base, torques)
    for weight in (w for w in RESERVE_CONTINUATION if w < nlp.settings.reserve_weight):
        step = nlp.variant({**ipopt_options.CONTINUATION_IPOPT, **args.continuation}, reserve_weight=weight)
        start = stage(f"reserves {weight:g}", step, lambda: step.solve(start, v)).blocks  # noqa: B023
    cold = stage(f"reserves {nlp.settings.reserve_weight:g}", nlp, lambda: nlp.solve(start, v))
    stage(f"warm {v + 0.1:g} m/s", nlp, lambda: nlp.resolve(cold, v + 0.1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
