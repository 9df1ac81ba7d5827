"""Heel versus forefoot strike of the paper's body at 3.5 m/s, everything else equal.

    python problems/heel_vs_forefoot.py [--out out/heel_vs_forefoot.csv]

Touchdown states span what treadmill runners show at 3.5 m/s (RBDS, Fukuchi et al. 2017:
hip flexion about 20-30 deg, knee flexion 8-25 deg at touchdown): for each knee angle the
foot is put toe-up (heel strike) or toe-down (forefoot strike) by the same angle, the rest of
the state is the same. Two sets of velocities:
- "example": issue 2's reference touchdown (hip 3.5, -0.6 m/s; thigh -150, shank 120,
  foot 40 deg/s): the foot still moves forward at about 3.5 m/s when it lands;
- "rbds": rates of RBDS subject 001's touchdowns (2.5 m/s trial, medians of both sides,
  rotation rates of the thigh, shank and foot marker clusters; a rough estimate until
  `formopt compare` measures them): hip (3.5, -0.7) m/s, thigh +40, shank -220,
  foot -140 deg/s: the foot is swept back and lands at about 1 m/s forward.
Prints T_c, the impulses, mu_c and dv of the trunk, and writes a CSV.
"""

import argparse
import csv
import math
from pathlib import Path

import numpy as np

from formopt import Impact
from formopt.mechanics.model import build_model
from formopt.mechanics.body import paper_body

DEG = math.pi / 180


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/heel_vs_forefoot.csv")
    args = parser.parse_args()
    model = build_model(paper_body(), "leg")
    impacts = {s: Impact(model, s, friction=0.8) for s in ("heel", "forefoot")}
    rows = []
    for name, velocity in VELOCITIES.items():
        rows += compare(impacts, name, velocity)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(".tmp")
    with tmp.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    tmp.replace(out)
    print(f"wrote {out}")


# hip velocity (m/s), then thigh, shank and foot angular velocities (deg/s)
VELOCITIES = {"example": (3.5, -0.6, -150.0, 120.0, 40.0),
              "rbds": (3.5, -0.7, 40.0, -220.0, -140.0)}


def compare(impacts, name, velocity):
    vx, vz, w_thigh, w_shank, w_foot = velocity
    hip, trunk = 25.0, 5.0
    rows = []
    print(f"\nvelocities {name!r}: hip ({vx}, {vz}) m/s, thigh {w_thigh:g}, shank {w_shank:g}, "
          f"foot {w_foot:g} deg/s; trunk {trunk:g}, hip {hip:g} deg")
    print(f"{'knee':>5s} {'foot':>5s} {'strike':>9s} {'v_x':>6s} {'T_c J':>8s} {'t N s':>8s} "
          f"{'n N s':>8s} {'mu_c':>6s} {'dv_x':>7s} {'dv_z':>7s}  valid")
    for knee in (8.0, 12.0, 18.0, 24.0):
        shank = hip - trunk - knee
        for foot in (5.0, 10.0, 15.0):
            for strike, sign in (("heel", 1.0), ("forefoot", -1.0)):
                ankle = sign * foot - shank
                x = np.array([trunk * DEG, hip * DEG, knee * DEG, ankle * DEG, vx, vz,
                              0.0, w_thigh * DEG, w_shank * DEG, w_foot * DEG])
                r = impacts[strike](x)
                (t, n), = r.impulse.values()
                v_point = r.qd_minus[impacts[strike].model.cols(strike)][0]
                rows.append({"velocities": name, "knee_deg": knee, "foot_deg": sign * foot, "ankle_deg": ankle,
                             "strike": strike, "T_c": r.T_c, "impulse_t": t, "impulse_n": n,
                             "mu_c": r.mu_c, "dv_trunk_x": r.dv_trunk[0], "dv_trunk_z": r.dv_trunk[1],
                             "valid": r.valid})
                mu = f"{r.mu_c:6.2f}" if r.mu_c is not None else "   n<0"
                print(f"{knee:5.0f} {sign * foot:5.0f} {strike:>9s} {v_point:6.2f} {r.T_c:8.2f} {t:8.3f} {n:8.3f} "
                      f"{mu} {r.dv_trunk[0]:7.3f} {r.dv_trunk[1]:7.3f}  {r.valid}")
    heel = np.array([r["T_c"] for r in rows if r["strike"] == "heel"])
    fore = np.array([r["T_c"] for r in rows if r["strike"] == "forefoot"])
    valid = {s: sum(r["valid"] for r in rows if r["strike"] == s) for s in ("heel", "forefoot")}
    print(f"T_c heel strike     {heel.min():.2f} .. {heel.max():.2f} J (median {np.median(heel):.2f}); "
          f"valid {valid['heel']}/{len(heel)}")
    print(f"T_c forefoot strike {fore.min():.2f} .. {fore.max():.2f} J (median {np.median(fore):.2f}); "
          f"valid {valid['forefoot']}/{len(fore)}")
    print(f"forefoot / heel T_c in the same state: median {np.median(fore / heel):.2f}")
    return rows


if __name__ == "__main__":
    main()
