"""Why the muscle-driven stride fails its forward check, and where its reserves act (issue 33):
RBDS001's body, heel strike, the muscles' "metabolic" objective, the cadence free.

    python problems/muscle_forward.py [--speeds 3.5] [--nodes 24] [--mass 62] [--reserve-weight W]

Per speed, after the solve:

- **Reserves**: at every node where a reserve moment exceeds the tolerance (0.1 N m/kg), the
  phase, leg, joint and reserve, the muscles' moment there, and for each muscle turning the joint
  the reserve's way its excitation, activation, tendon force F (F_max) and rate F' (1/s), fibre
  length and velocity (l_opt, v_max), f_L, f_V and the moment it makes against the moment it
  would make fully active at the same fibre state (a = 1: its capacity there).
- **Forward check, two ways**, each phase from the NLP's state at its start (as
  optim/stride/checks.forward's `reset` runs, by its replays, checks.replayed): (1) the
  net joint moments replayed (piecewise linear; the torque rungs' check, a figure for the
  muscles), (2) the excitations replayed (piecewise linear) through the activation dynamics, the
  Hill equilibrium solved for F' at every step (mechanics.muscles.tendon_force_rate) and the
  tendon forces' moments, the reserves replayed as moments: the muscle-driven body's own forward
  simulation, whose fibres resist a departure from the path (force-length-velocity: the
  "preflexes" of Brown & Loeb 2000, van Soest & Bobbert 1993) where a replayed moment does not,
  and what checks.forward judges a muscle stride by. The largest joint-angle error (rad) per
  phase, and the joint where it is.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace

import casadi as ca
import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics import muscles as hill
from formopt.mechanics.body import scaled_body
from formopt.optim.stride.checks import grid, replayed
from formopt.optim.stride.collocation import NX, build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import StrideSettings
from formopt.optim.stride.result import TOLERANCES

JOINT_NAMES = ("hip", "knee", "ankle")
COORDINATES = ("x", "y", "trunk", "hip_R", "knee_R", "ankle_R", "hip_L", "knee_L", "ankle_L")
SHORT = {"iliopsoas": "IL", "glutei": "GL", "hamstrings": "HA", "rectus_femoris": "RF", "vasti": "VA",
         "gastrocnemius": "GA", "soleus": "SO", "tibialis_anterior": "TA"}


def fibre_function(muscles: hill.Muscles) -> ca.Function:
    """(theta, theta', a, F, F') -> (l~, v~, f_L, f_V, f_PE) of one leg's muscles."""
    th, thd = ca.SX.sym("theta", 3), ca.SX.sym("thetad", 3)
    a, F, Fd = (ca.SX.sym(k, len(muscles.names)) for k in ("a", "F", "Fd"))
    length, velocity = hill.fibre_state(muscles, th, thd, F, Fd)
    return ca.Function("fibres", [th, thd, a, F, Fd], [
        length, velocity, hill.active_force_length(length, ca.DM(muscles.width)), hill.force_velocity(velocity),
        hill.passive_force_length(length, ca.DM(muscles.passive_slack), ca.DM(muscles.passive_stiffness))])


def reserves(nlp, blocks: dict) -> None:
    """Print the nodes where a reserve exceeds the tolerance and the muscles that could help (a
    node value: the tolerance judges the reserves' largest 10 ms mean, muscle_readings.reserve_mean)."""
    act = nlp.ocp.models[0].actuation
    n, mus, fibres = act.n, act.muscles, fibre_function(act.muscles)
    limit, start = TOLERANCES["reserve_nm_per_kg"], 0.0
    for phase in nlp.phases:
        X, Z, U, T = (blocks[f"{k}_{phase.name}"] for k in "XZUT")
        T = T.item()
        for k in range(X.shape[1]):
            for leg in range(2):
                r = U[6 * n + 3 * leg:6 * n + 3 * leg + 3, k]
                j = int(np.argmax(np.abs(r)))
                if abs(r[j]) <= limit:
                    continue
                th, thd = X[3 + 3 * leg:6 + 3 * leg, k], X[NX + 3 + 3 * leg:NX + 6 + 3 * leg, k]
                a, F = Z[2 * n * leg:2 * n * leg + n, k], Z[2 * n * leg + n:2 * n * (leg + 1), k]
                e, Fd = U[3 * n * leg:3 * n * leg + n, k], act.RATE_SCALE * U[3 * n * leg + 2 * n:3 * n * (leg + 1), k]
                length, velocity, fl, fv, fpe = (np.asarray(v, float).ravel() for v in fibres(th, thd, a, F, Fd))
                arm = -mus.moment_arms[:, j] * mus.max_force  # N m per unit F, extensor positive
                print(f"  {phase.name:8s} t {start + k * T / (X.shape[1] - 1):.3f} s  {'RL'[leg]} {JOINT_NAMES[j]:5s}"
                      f" reserve {r[j]:+.2f} N m/kg ({nlp.mass * r[j]:+4.0f} N m), muscles {arm @ F:+5.0f} N m,"
                      f" angle {np.degrees(th[j]):+4.0f} deg, rate {thd[j]:+5.1f} rad/s")
                for q in np.flatnonzero(arm * np.sign(r[j]) > 0):
                    full = arm[q] * (fl[q] * fv[q] + fpe[q] + hill.DAMPING * velocity[q])
                    print(f"      {SHORT[mus.names[q]]} e {e[q]:.2f} a {a[q]:.2f} F {F[q]:.2f} F' {Fd[q]:+6.1f}"
                          f" l~ {length[q]:.2f} v~ {velocity[q]:+.2f} f_L {fl[q]:.2f} f_V {fv[q]:.2f}"
                          f"  {arm[q] * F[q]:+5.0f} N m, fully active {full:+5.0f} N m")
        start += T


def forward_errors(nlp, solved) -> list[tuple[float, str, float, str]]:
    """Per phase: (moments replayed: the largest angle error, rad, and its coordinate; excitations
    replayed: the same), each phase from the NLP's state at its start (`solved`: layout.Solved;
    the replays optim.stride.checks.forward's, checks.replayed)."""
    out = []
    for i, phase in enumerate(nlp.phases):
        X, Z = solved.blocks[f"X_{phase.name}"], solved.blocks[f"Z_{phase.name}"]
        columns = grid(nlp, i)[1]
        row: list = []
        for excitations, y0 in ((False, X[:, 0]), (True, np.r_[X[:, 0], Z[:, 0]])):
            path = replayed(nlp, i, solved.blocks, solved.parameters, excitations, y0)
            error = np.full(NX, np.inf) if path is None else np.abs(path[:NX, columns] - X[:NX]).max(axis=1)
            error[:2] = 0.0  # the angles only (the hip's position is in m)
            row += [float(error.max()), COORDINATES[int(np.argmax(error))]]
        out.append(tuple(row))
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speeds", type=float, nargs="+", default=[3.5])
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--mass", type=float, default=62.0)
    parser.add_argument("--reserve-weight", type=float, default=None)
    args = parser.parse_args(argv)
    body = scaled_body(args.mass, 1.81)
    settings = StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic", muscles=body_muscles(body))
    if args.reserve_weight is not None:
        settings = replace(settings, reserve_weight=args.reserve_weight)
    nlp = build(body, settings)
    for speed in args.speeds:
        stride = optimum(nlp, speed)
        print(f"\n== {speed} m/s, {args.nodes} nodes: {stride.cadence_spm:.1f} steps/min, reserves "
              f"{stride.checks['reserve_nm_per_kg']:.2f} N m/kg, forward check {stride.checks['forward_theta']:.3f} rad"
              f" (moments replayed {stride.checks['forward_moments_reset_theta']:.3f})"
              f" ({'valid' if stride.valid else '; '.join(stride.failed_checks)})")
        print(" reserves beyond the tolerance, and the muscles turning the joint their way:")
        reserves(nlp, stride.solved.blocks)
        print(" forward, each phase from the NLP's state (largest angle error, rad):"
              " moments replayed | excitations replayed through the muscles")
        for phase, (m, mj, e, ej) in zip(nlp.phases, forward_errors(nlp, stride.solved)):
            print(f"  {phase.name:8s} {m:7.3f} ({mj:7s}) | {e:7.3f} ({ej})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
