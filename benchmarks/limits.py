"""Measured numerical limits: condition numbers at the extremes (README, "Numerical limits").

    python benchmarks/limits.py

Prints the condition number of Phi_q M^-1 Phi_q^T and the invariant error |T_c + T_a - T| / T
for each extreme of issue 7, and the condition number of IPOPT's KKT matrix at the demo's
optimum (Hessian of the Lagrangian and the active constraints, in the scaled variables).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import casadi as ca
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests" / "mechanics"))  # test_extremes
from helpers import touchdown
from test_extremes import body_with

from formopt import Impact, load
from formopt.mechanics.model import build_model
from formopt.optim.posture import PostureProblem

ROOT = Path(__file__).resolve().parent.parent


def row(label, body_kw=None, strike="forefoot", slope=0.0, **state):
    model = build_model(body_with(**(body_kw or {})))
    r = Impact(model, strike, math.radians(slope), 0.8)(touchdown(**state))  # the shipped friction
    err = abs(r.T_c + r.T_a - r.T) / r.T if r.T > 0 else 0.0
    mu = f"{r.mu_c:.3g}" if r.mu_c is not None else "undefined"
    print(f"{label:44s} {r.condition:12.3g} {err:14.2e} {r.T_c:12.4g}  {mu}")


def main():
    print(f"{'extreme':44s} {'cond(G)':>12s} {'|T_c+T_a-T|/T':>14s} {'T_c (J)':>12s}  mu_c")
    row("paper body, reference forefoot strike")
    row("straight knee (0 deg)", knee=0.0, ankle=-20.0)
    row("foot perpendicular to the ground", ankle=-94.0)
    row("touchdown at 1e-6 m/s", v=(1e-6, -1e-7), w=(0, 0, 0, 0))
    row("touchdown at 15 m/s", v=(15.0, -1.5))
    for ratio in (1e-4, 1e4):
        row(f"trunk mass x {ratio:g}", {"ratio_trunk": ratio})
        row(f"foot mass x {ratio:g}", {"ratio_foot": ratio})
    for length in (0.01, 3.0):
        row(f"thigh and shank {length:g} m", {"thigh_length": length, "shank_length": length}, ankle=-40.0)
    row("thigh 1 mm", {"thigh_length": 0.001})
    for slope in (-30.0, 30.0):
        row(f"heel strike on {slope:+g} deg", strike="heel", slope=slope, ankle=10.0)

    scene = load(ROOT / "formopt" / "scenes" / "demo.toml")
    problem = PostureProblem(scene.model(), scene.strike, scene.state,
                             scene.problem, scene.slope, scene.friction)
    opt = problem.solve()
    w = problem.to_unit(opt.state)
    sol, _, _ = problem.solve_from(w)
    x, p = problem.nlp["x"], problem.nlp["p"]
    lam = ca.SX.sym("lam", problem.nlp["g"].shape[0])
    lag = problem.nlp["f"] + ca.dot(lam, problem.nlp["g"])
    H = np.asarray(ca.Function("H", [x, p, lam], [ca.hessian(lag, x)[0]])(
        sol["x"], problem.p0, sol["lam_g"]), float)
    J = np.asarray(ca.Function("J", [x, p], [ca.jacobian(problem.nlp["g"], x)])(sol["x"], problem.p0), float)
    g = np.asarray(problem.constraint_function(sol["x"], problem.p0), float).ravel()
    active = [k for k in range(len(g)) if min(abs(g[k] - problem.lbg[k]), abs(g[k] - problem.ubg[k])) < 1e-6]
    u = np.asarray(sol["x"], float).ravel()
    bounds = np.eye(len(u))[[k for k in range(len(u)) if u[k] < 1e-6 or u[k] > 1 - 1e-6]]
    A = np.vstack([J[active], bounds])
    kkt = np.block([[H, A.T], [A, np.zeros((len(A), len(A)))]])
    print(f"\nIPOPT at the demo's optimum: {len(active)} active constraints, {len(bounds)} active bounds; "
          f"cond(Hessian of the Lagrangian) {np.linalg.cond(H):.3g}, cond(KKT) {np.linalg.cond(kkt):.3g}")


if __name__ == "__main__":
    main()
