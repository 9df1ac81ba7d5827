"""The posture NLP's objective: weighted impact indicators, the landing, the stance's support.

    F(x) = sum_k w_k term_k(x)

Terms: T_c (J, the first impact's absorbed energy), T_c_total (J, both impacts of the
landing), dv_trunk_x/z and dv_com_x/z (m/s, velocity changes at the impact), and `support`:

    support = sum_j M_j^2 / (2 k_j),   M_j = F d_j                                      (J)

the elastic energy the knee and ankle must hold to carry the stance's peak ground force F
(N, `stance_peak_bw` body weights, default 2.4: RBDS001's 23.5 N/kg at 3.5 m/s) along the
line from the strike point to the hip, d_j the joint's distance from that line (m) and k_j its
running quasi-stiffness (landing.RUNNING_JOINTS scaled to the body, N m/rad). A bent leg puts
the knee and ankle far from the force line: their effective mechanical advantage falls and the
muscles must pull harder (Biewener 1989, Science 245:45; Biewener et al. 2004, J Appl Physiol
97:2266), which is what makes crouched running costly (McMahon et al. 1987). The geometry is
the touchdown's; the force line is taken through the hip (whose moment is then zero).

The weights enter normalised (w_k / sum |w_k|), so any positive scaling of them gives the same
NLP, the same optimum and the same iterations; the value reported is sum |w_k| times it.
"""

from __future__ import annotations

import math

import casadi as ca

from ..mechanics.dynamics import GRAVITY
from ..mechanics.landing import RUNNING_JOINTS
from ..mechanics.model import Model, landmarks

OBJECTIVES = ("T_c", "T_c_total", "dv_trunk_x", "dv_trunk_z", "dv_com_x", "dv_com_z", "support")
UNITS = {"T_c": "J", "T_c_total": "J", "dv_trunk_x": "m/s", "dv_trunk_z": "m/s",
         "dv_com_x": "m/s", "dv_com_z": "m/s", "support": "J"}
STANCE_PEAK_BW = 2.4  # body weights: RBDS001's peak vertical force, 23.5 N/kg at 3.5 m/s
SUPPORT_JOINTS = ("knee", "ankle")


def normalised(weights: dict[str, float]) -> tuple[dict[str, float], float]:
    """(weights / sum |weights|, sum |weights|)."""
    total = sum(abs(w) for w in weights.values())
    return {k: w / total for k, w in weights.items()}, total


def support_moments(x, model: Model, strike_point: str, peak_bw: float = STANCE_PEAK_BW) -> dict:
    """{joint: M_j} (N m, signed; SX/MX, or DM for a numeric x) of the stance's peak force
    F along the strike-point-to-hip line, M_j = F d_j (d_j: the joint's signed distance, m)."""
    world = landmarks(x, model.body, strike_point)
    hip = world["hip"][0]
    line = hip / ca.norm_2(hip)
    force = peak_bw * model.body.mass * GRAVITY
    return {j: force * (world[j][0][0] * line[1] - world[j][0][1] * line[0]) for j in SUPPORT_JOINTS}


def support(x, model: Model, strike_point: str, peak_bw: float = STANCE_PEAK_BW):
    """The stance support term (J) of touchdown state x: sum_j M_j^2 / (2 k_j)."""
    moments = support_moments(x, model, strike_point, peak_bw)
    return sum(m ** 2 / (2.0 * RUNNING_JOINTS["stiffness"][j] * model.body.mass * 180.0 / math.pi)
               for j, m in moments.items())
