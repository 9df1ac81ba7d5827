"""The stride's checks against the number of nodes, and its initial guesses (issue 23 item 5).

    python problems/stride_checks.py [strike]      (default heel)

The paper's body at 3.5 m/s, `effort`. Per node count (24, 40, 80): IPOPT's iterations, the
energy balance (J and share of W+), the forward simulation's largest error per phase (rad,
each phase from the NLP's state) and open loop, the contact drift (m), the impact-map
difference (J). Then, at 40 nodes: the generic guess, three random perturbations of it and a
continuation in speed (3.0 -> 3.5 m/s): objective, cadence, iterations.
"""

import sys

import numpy as np

from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.checks import half_period
from formopt.optim.stride.guess import ballistic, perturbed


def main(strike):
    js = JointSpace(paper_body())
    print(f"{'nodes':>5s} {'it':>4s} {'balance J':>10s} {'of W+':>7s} {'forward rad per phase':>34s} "
          f"{'open loop':>9s} {'drift m':>8s} {'impact J':>9s}")
    for nodes in (24, 40, 80):
        s = optimum(StrideNLP(js, StrideSettings(strike=strike, nodes=nodes)), 3.5)
        c = s.checks
        print(f"{nodes:5d} {s.iterations:4d} {s.budget['balance_J']:10.3f} {c['balance_relative']:7.4f} "
              f"{' '.join(f'{v:.4f}' for v in c['forward_per_phase']):>34s} {c['open_loop_theta']:9.3f} "
              f"{c['drift_m']:8.5f} {c['impact_map_J']:9.1e}", flush=True)
    nlp = StrideNLP(js, StrideSettings(strike=strike))
    rng = np.random.default_rng(20261123)
    base = ballistic(nlp, 3.5)
    runs = [("generic", base)] + [(f"random {k}", perturbed(base, rng)) for k in range(1, 4)]
    start = nlp.solve(ballistic(nlp, 3.0), 3.0)
    runs.append(("continuation 3.0 m/s", start.blocks))
    print(f"\n{'guess':22s} {'ok':>3s} {'objective':>10s} {'cadence':>8s} {'it':>4s}")
    for name, guess in runs:
        out = nlp.solve(guess, 3.5)
        print(f"{name:22s} {'yes' if out.success else 'no':>3s} {out.objective:10.5f} "
              f"{60 / half_period(nlp, out.blocks):8.1f} {out.iterations:4d}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "heel")
