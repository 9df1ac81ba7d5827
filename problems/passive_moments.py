"""The joints' passive moments against the bounds that held the stride (issue 34 item 2).

    python problems/passive_moments.py [variants ...]   (default: all three)

Each variant solved on the shipped scenes at 3.5 m/s, one cold start as `formopt stride` does:
stride_rbds001 (RBDS001's body, 62 kg, 1.81 m, tendons) with a heel and a forefoot strike, and
stride (the paper's body, heel). Variants:

- "riener-edrich": mechanics.joint_space as shipped (Riener & Edrich 1999; angles bounded at
  the running ranges +- LIMIT_MARGIN = 5 deg);
- "margin-15": the same moments, the angles' hard bounds 15 deg beyond the ranges;
- "stops-10": Riener & Edrich plus Anderson & Pandy's end-of-range stops (Anderson 1999's
  double exponentials, as Falisse et al. 2019, 3dpredictsim PassiveMomentsData.m, tabulate
  them for hip flexion, knee and ankle; their knee angle is flexion-negative), bounds 10 deg out.

Printed per stride: cadence (RBDS001 runs 171.4 steps/min), objective, peak vertical force (body
weights), the stance ankle's largest dorsiflexion and the knees' least flexion (deg), the joint
angles on their hard bound (bounds.held_by_bounds), the forward check (rad), the passive
moments' work (J) and, on RBDS001's body, the joint angles' RMS error against its mean cycle.
"""

import sys
from contextlib import contextmanager
from pathlib import Path

import casadi as ca
import numpy as np

from formopt import api
from formopt.io.scene import load
from formopt.mechanics import joint_space
from formopt.optim.stride import collocation
from formopt.studies.stride import compare_cycle, measured_cycle

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "data" / "rbds" / "RBDS001processed.txt"
STRIDES = (("stride_rbds001", "heel"), ("stride_rbds001", "forefoot"), ("stride", "heel"))
SHIPPED = joint_space.passive_moments


def with_stops(angles):
    """Riener & Edrich's moments plus Anderson's end-of-range stops (N m; hip, knee, ankle
    dorsiflexion; angles in rad, module docstring)."""
    hip, knee, ankle = SHIPPED(angles)
    h, k, a = angles[0], angles[1], angles[2]
    return (hip - 2.44 * ca.exp(5.05 * (h - 1.81)) + 1.51 * ca.exp(-21.88 * (h + 0.6981)),
            knee + 6.09 * ca.exp(-33.94 * (k + 0.13)) - 11.03 * ca.exp(11.33 * (k - 2.4)),
            ankle - 2.03 * ca.exp(38.11 * (a - 0.52)) + 0.18 * ca.exp(-12.12 * (a + 0.74)))


VARIANTS = {"riener-edrich": (SHIPPED, 5.0), "margin-15": (SHIPPED, 15.0), "stops-10": (with_stops, 10.0)}


@contextmanager
def variant(name):
    """The passive moments and angle margin (deg) of a variant, for the NLPs built inside (the
    process's kept NLPs, collocation.build's, dropped on the way in and out)."""
    moments, margin = VARIANTS[name]
    saved = joint_space.passive_moments, collocation.LIMIT_MARGIN
    joint_space.passive_moments, collocation.LIMIT_MARGIN = moments, np.radians(margin)
    collocation._BUILT.clear()
    try:
        yield
    finally:
        joint_space.passive_moments, collocation.LIMIT_MARGIN = saved
        collocation._BUILT.clear()


def row(name, scene, strike):
    with variant(name):
        s = api.stride(load(ROOT / "formopt" / "scenes" / f"{scene}.toml"), None, strike).best
    angles = [h for h in s.held if h["variable"].endswith("angle")]
    held = "; ".join(f"{h['variable']} {np.degrees(h['bound']):.0f} ({h['nodes']})" for h in angles) or "-"
    rms = compare_cycle(s, measured_cycle(DATA, 3.5))["angle_rms_deg"] if "rbds" in scene else None
    deg = np.degrees(s.theta)
    return (f"{name:13s} {scene:15s} {strike:8s} {s.cadence_spm:6.1f} {s.objective_value:7.4f} "
            f"{s.peak_vertical_grf_bw:5.2f} {deg[:, 5].max():6.1f} {deg[:, [4, 7]].min():6.1f} "
            f"{s.checks['forward_theta']:6.3f} {s.budget['passive_J']:6.2f}  "
            f"{'/'.join(f'{rms[j]:.0f}' for j in ('hip', 'knee', 'ankle')) if rms else '-':9s}  {held}")


def main(names):
    print(f"{'variant':13s} {'scene':15s} {'strike':8s} {'spm':>6s} {'cost':>7s} {'BW':>5s} "
          f"{'ank^':>6s} {'knee_':>6s} {'fwd':>6s} {'pass J':>6s}  {'RMS h/k/a':9s}  angles on a hard bound (nodes)")
    for name in names:
        for scene, strike in STRIDES:
            print(row(name, scene, strike), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or list(VARIANTS))
