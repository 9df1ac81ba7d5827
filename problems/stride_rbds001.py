"""RBDS001's running against the stride optimum, per objective (issue 23 item 6).

    python problems/stride_rbds001.py [speeds ...]      (default 3.5 2.5)

The body scaled to RBDS001 (62 kg, 1.81 m, de Leva 1996); heel and forefoot strikes (the runner
lands forefoot-first in 40 of 43 right steps at 3.5 m/s); objectives: effort, effort with the
impacts' T_c weighted (impact_weight 1), work and metabolic; each the best of 4 starts (the
generic guess and 3 perturbations of it); each without and with the stance leg's tendons
(optim.stride.problem.RUNNER_TENDONS). Measured: cadence 156.5 / 171.4 steps/min (the trials), stance share of the cycle
and peak vertical force from the processed mean cycle (RBDS001processed.txt). Goals: cadence
and stance time within 10 %, peak force within 15 %, joint angles within 10 deg RMS.
"""

import sys
from pathlib import Path

from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.problem import RUNNER_TENDONS
from formopt.studies.stride import compare_cycle, measured_cycle

DATA = Path(__file__).resolve().parent.parent / "data" / "rbds" / "RBDS001processed.txt"
CADENCE = {2.5: 156.5, 3.5: 171.4}  # steps/min, RBDS001's trials
VARIANTS = tuple((objective, weight, tendons) for tendons in (False, True)
                 for objective, weight in (("effort", 0.0), ("effort", 1.0), ("work", 0.0), ("metabolic", 0.0)))


def rows(speeds):
    js = JointSpace(scaled_body(62.0, 1.81))
    for strike in ("heel", "forefoot"):
        nlps = {v: StrideNLP(js, StrideSettings(strike=strike, objective=v[0], impact_weight=v[1],
                                                tendons=dict(RUNNER_TENDONS) if v[2] else {}))
                for v in VARIANTS}
        for speed in speeds:
            measured = measured_cycle(DATA, speed)
            for variant, nlp in nlps.items():
                stride = optimum(nlp, speed, simulate=False, starts=4)
                c = compare_cycle(stride, measured)
                cycle = 120.0 / CADENCE[speed]
                yield (speed, strike, f"{variant[0]}{'+T_c' if variant[1] else ''}{'+tendons' if variant[2] else ''}", stride, c,
                       c["stance_share_measured"] * cycle)


def main(speeds):
    print(f"{'v':>4s} {'strike':8s} {'objective':19s} {'ok':>3s} {'cadence':>12s} {'stance s':>12s} "
          f"{'peak N/kg':>12s} {'RMS hip/knee/ankle deg':>24s} {'T_c J':>7s} {'CoT':>6s}")
    for speed, strike, name, s, c, stance in rows(speeds):
        peak = c["peak_vertical_n_per_kg"]
        rms = c["angle_rms_deg"]
        print(f"{speed:4.1f} {strike:8s} {name:19s} {'yes' if s.success else 'no':>3s} "
              f"{s.cadence_spm:5.1f}/{CADENCE[speed]:5.1f} {s.stance_s:5.3f}/{stance:5.3f} "
              f"{peak['predicted']:5.1f}/{peak['measured']:5.1f} "
              f"{rms['hip']:7.1f}/{rms['knee']:5.1f}/{rms['ankle']:5.1f}      "
              f"{s.budget['impacts_J']:7.2f} {s.cost_of_transport:6.3f}", flush=True)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [3.5, 2.5])
