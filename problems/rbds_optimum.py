"""RBDS001's gait-anchored optimum under each contact law and support weight.

    python problems/rbds_optimum.py [--trial T] [--static S] [--out out/rbds_optimum]

For the mean forefoot touchdown of the right foot of RBDS001 at 3.5 m/s (T35), the measured
hip placement, velocities, segment rates and cadence held: the optimum of T_c + w support
under each contact law for w = 0, 0.1, 0.3; measured against optimal per joint, what holds
each optimum, the saving in J per step and W, and how the optimum moves with friction
(KKT sensitivity, deg per 0.1 of friction). Writes rbds_optimum.csv.
"""

import argparse
from pathlib import Path

from formopt.io import mocap
from formopt.io.files import write_csv
from formopt.mechanics.contact import LAWS
from formopt.studies.compare import compare, report

DATA = Path(__file__).resolve().parents[1] / "data" / "rbds"
WEIGHTS = (0.0, 0.1, 0.3)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trial", default=str(DATA / "RBDS001runT35.c3d"))
    parser.add_argument("--static", default=str(DATA / "RBDS001static.c3d"))
    parser.add_argument("--out", default="out/rbds_optimum")
    args = parser.parse_args()
    trial, static = mocap.read(args.trial), mocap.read(args.static)
    rows = [["law", "support_weight", "verdict", "hip_deg", "knee_deg", "ankle_deg", "T_c_J",
             "support_J", "saving_J_per_step", "saving_W", "knee_per_0.1_friction_deg"]]
    print(f"{'law':13s} {'w':>4s} {'hip':>6s} {'knee':>6s} {'ankle':>6s} {'T_c J':>7s} "
          f"{'save W':>7s} {'knee/0.1 mu':>11s}  what the optimum is")
    measured = None
    for law in LAWS:
        for weight in WEIGHTS:
            c = compare(trial, static, 62.0, 1.81, friction=0.8, law=law, support=weight, per_step=False)
            rep = report(c)
            opt, a = c.optimum, rep["optimum"]["touchdown"]["angles_deg"]
            if measured is None:
                measured = rep["reference"]["angles_deg"]
                print(f"{'measured':13s} {'':>4s} {measured['hip']:6.1f} {measured['knee']:6.1f} "
                      f"{measured['ankle']:6.1f}   (mean forefoot-impact touchdown, both sides, cadence "
                      f"{c.steps.cadence_spm:.1f} steps/min)")
            knee_mu = (opt.sensitivity.get("d_posture_d_friction_deg", {}).get("knee", float("nan"))
                       * 0.1)
            power = opt.power if opt.success else float("nan")
            print(f"{law:13s} {weight:4.1f} {a['hip']:6.1f} {a['knee']:6.1f} {a['ankle']:6.1f} "
                  f"{opt.impact.T_c:7.3f} {power:7.2f} {knee_mu:+11.2f}  {opt.verdict}")
            rows.append([law, weight, opt.verdict, a["hip"], a["knee"], a["ankle"], opt.impact.T_c,
                         opt.terms.get("support", float("nan")), opt.saving, power, knee_mu])
    print(f"wrote {write_csv(Path(args.out) / 'rbds_optimum.csv', rows)}")


if __name__ == "__main__":
    main()
