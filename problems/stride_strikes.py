"""The paper's central claim in a stride: heel against forefoot strike (issue 23 item 7).

    python problems/stride_strikes.py [impact_weight]      (default 1.0)

The paper's body at 2.5 and 3.5 m/s, each strike's own optimum (objective `effort`, with the
impacts' T_c weighted by `impact_weight`), under each law of the impacts: no-slip (the
friction cone on the impulse a constraint) and Coulomb (the impact solved sticking, then
checked with formopt's Coulomb map: valid when its mode is stick). Printed: cadence, step,
each impact's T_c (J) and validity, the impacts' share of the positive work, the total cost
(objective per distance), CoT.
"""

import sys

from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum


def main(weight: float):
    js = JointSpace(paper_body())
    print(f"{'law':8s} {'strike':8s} {'v':>4s} {'ok':>3s} {'cadence':>8s} {'step m':>7s} "
          f"{'impacts T_c J (valid)':>30s} {'share':>6s} {'cost':>7s} {'CoT':>6s}")
    for law in ("no-slip", "coulomb"):
        for strike in ("heel", "forefoot"):
            nlp = StrideNLP(js, StrideSettings(strike=strike, law=law, impact_weight=weight))
            guess = None
            for speed in (3.5, 2.5):  # 2.5 m/s warm-started from 3.5 m/s
                s = optimum(nlp, speed, guess=guess, simulate=False)
                guess = s.solved.blocks if s.success else None
                impacts = " ".join(f"{i['point']}{i['leg']} {i['T_c']:.2f}"
                                   f"({'ok' if i['valid'] else i['coulomb_mode']})" for i in s.impacts)
                share = s.budget["impacts_J"] / s.budget["positive_work_J"]
                print(f"{law:8s} {strike:8s} {speed:4.1f} {'yes' if s.success else 'no':>3s} "
                      f"{s.cadence_spm:8.1f} {s.step_length_m:7.3f} {impacts:>30s} {share:6.2f} "
                      f"{s.objective_value:7.3f} {s.cost_of_transport:6.3f}", flush=True)


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 1.0)
