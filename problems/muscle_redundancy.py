"""The muscle layer in a collocation problem: RBDS001's measured cycle driven by its muscles.

    python problems/muscle_redundancy.py [--speed 3.5] [--every 1]

The muscle-redundancy problem of De Groote et al. 2016 on a runner: the right leg's measured
joint angles and moments over RBDS001's mean gait cycle (RBDS001processed.txt, 101 rows, the
hip moment negated to extensor positive: problems/muscle_capacity.py says why), periodic, the
cycle lasting two steps at the runner's measured cadence (every `--every`-th of its 100 rows a
node). Unknowns per node: activations a and
normalised tendon forces F (states), excitations e and force rates F' (controls), and a reserve
moment per joint; trapezoidal collocation of da/dt and dF/dt; per node the Hill equilibrium
(`LegFunctions.residual`, one row per muscle) and the moment balance muscles + reserve =
measured. Cost per time: the volume-weighted mean a^3 plus (reserve / 1 N m)^2 and a small
1e-4 (F' / 10/s)^2. The guess is poor on purpose: a = e = 0.1, F = 0.1, F' = 0. It prints
IPOPT's status, the time, the largest reserve, each muscle's peak activation and the leg's
mean metabolic rate (`LegFunctions.metabolic_rate`) in W/kg of body mass.
"""

import argparse
import time
from pathlib import Path

import casadi as ca
import numpy as np

from formopt.io.muscle_table import gait2d_muscles
from formopt.mechanics import muscles as mu

DATA = Path(__file__).resolve().parent.parent / "data" / "rbds" / "RBDS001processed.txt"
MASS, HEIGHT = 62.0, 1.81  # data/rbds/RBDSinfo.txt
CADENCE = {2.5: 156.5, 3.5: 171.4}  # steps/min measured (docs/howto/compare.md; issue 33)
HIP_FLIP = np.array([-1.0, 1.0, 1.0])  # the data set's moments -> extensor / plantarflexor +
JOINTS = ("hip", "knee", "ankle")


def measured(speed: float, every: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Angles (rad), rates (rad/s), moments (N m), each (100 / every, 3) over one periodic
    cycle, and the node spacing (s)."""
    suffix = f"{speed:.1f}".replace(".", "")
    data = np.genfromtxt(DATA, names=True, delimiter="\t")
    angles = np.radians(np.column_stack([data[f"R{j}AngZ{suffix}"] for j in JOINTS]))[:-1:every]
    moments = (np.column_stack([data[f"R{j}MomZ{suffix}"] for j in JOINTS]) * MASS * HIP_FLIP)[:-1:every]
    step = 120.0 / CADENCE[speed] / len(angles)
    rates = (np.roll(angles, -1, axis=0) - np.roll(angles, 1, axis=0)) / (2 * step)
    return angles, rates, moments, step


def nxt(x):
    """Each node's next node, the last one's the first (a periodic cycle)."""
    return ca.horzcat(x[:, 1:], x[:, :1])


def solve(speed: float, every: int) -> None:
    angles, rates, moments, h = measured(speed, every)
    leg = gait2d_muscles(MASS, HEIGHT)
    f = mu.leg_functions(leg)
    nodes, n = len(angles), len(leg.names)
    a, F, e, dF10, reserve = (ca.MX.sym(name, n if name != "reserve" else 3, nodes)
                              for name in ("a", "F", "e", "dF10", "reserve"))
    dF = 10.0 * dF10  # De Groote et al. 2016: the force rate's control scaled by 10
    adot = f.activation_rate.map(nodes)(e, a)
    rows = [nxt(a) - a - h / 2 * (adot + nxt(adot)), nxt(F) - F - h / 2 * (dF + nxt(dF)),
            f.residual.map(nodes)(angles.T, rates.T, a, F, dF),
            f.moments.map(nodes)(F) + reserve - moments.T]
    cost = h * (ca.sum2(f.activation_cost.map(nodes)(a)) + ca.sumsqr(reserve)
                + 1e-4 * ca.sumsqr(dF10))
    x = ca.veccat(a, F, e, dF10, reserve)
    g = ca.veccat(*rows)
    lower = np.r_[np.full(n * nodes, 0.01), np.zeros(n * nodes), np.zeros(n * nodes),
                  np.full(n * nodes, -10.0), np.full(3 * nodes, -50.0)]
    upper = np.r_[np.ones(n * nodes), np.full(n * nodes, 5.0), np.ones(n * nodes),
                  np.full(n * nodes, 10.0), np.full(3 * nodes, 50.0)]
    guess = np.r_[np.full(3 * n * nodes, 0.1), np.zeros((n + 3) * nodes)]
    solver = ca.nlpsol("redundancy", "ipopt", {"x": x, "f": cost, "g": g},
                       {"ipopt.print_level": 0, "print_time": False, "ipopt.tol": 1e-8})
    start = time.perf_counter()
    out = solver(x0=guess, lbx=lower, ubx=upper, lbg=0, ubg=0)
    seconds = time.perf_counter() - start
    report(solver, out, f, leg, angles, rates, nodes, seconds)


def report(solver, out, f, leg, angles, rates, nodes, seconds) -> None:
    n = len(leg.names)
    x = np.asarray(out["x"], float).ravel()
    a, F, _, dF10 = (x[k * n * nodes:(k + 1) * n * nodes].reshape(nodes, n).T for k in range(4))
    reserve = x[4 * n * nodes:].reshape(nodes, 3).T
    stats = solver.stats()
    print(f"IPOPT: {stats['return_status']}, {stats['iter_count']} iterations, {seconds:.1f} s")
    print(f"largest reserve moment: {np.abs(reserve).max():.2f} N m")
    for name, peak in zip(leg.names, a.max(axis=1)):
        print(f"  {name:18s} peak activation {peak:.2f}")
    rate = [float(f.metabolic_rate(angles[k], rates[k], a[:, k], F[:, k], 10 * dF10[:, k]))
            for k in range(nodes)]
    print(f"one leg's mean metabolic rate: {np.mean(rate) / MASS:.2f} W/kg")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5, choices=sorted(CADENCE))
    parser.add_argument("--every", type=int, default=1, choices=(1, 2, 4, 5),
                        help="a node at every n-th row of the measured cycle (100 rows)")
    args = parser.parse_args()
    solve(args.speed, args.every)
