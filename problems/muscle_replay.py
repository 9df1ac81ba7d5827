"""Where a muscle stride leaves its forward replay, and why (issue 33: the |F'| term's 2.5 m/s
stride failing its forward check): a stride pickled by problems/muscle_energy.py (`--save`),
RBDS001's body (62 kg, 1.81 m), heel strike, the muscles' "metabolic" objective.

    python problems/muscle_replay.py FILE [--speed 2.5] [--nodes 80] [--grading 1] [--power 1]
                                     [--weight 12] [--rate-smoothing 0.5] [--intervals forefoot]

Per phase, replayed from the NLP's state at its start (optim.stride.checks.replayed, the
excitations through the activation dynamics and the Hill equilibrium: checks.forward's figure):
the largest angle error (rad) and its coordinate and node; the largest activation and tendon-force
errors (a, F_max) and their muscle; the phase's duration and nodes. Then the stance leg's
tendon-force rates F' (1/s, the NLP's controls) where the force is loaded (F > 0.1 F_max):
their median, quartile and 90th percentile of |F'|, against the |F'| smoothing eps; and how the
controls chatter, per phase: the share of nodes where the excitation e zig-zags (its steps change
direction at two neighbouring nodes running, the step between them over 0.02), the largest
|e_k+1 - e_k|, and the share where F' changes direction with a step over 1 /s. `--intervals
PHASE ...`: each interval of those phases replayed alone from the NLP's state at its first node
(the one-interval error: angles, angle rates, activations, tendon forces) beside the error grown
from the phase's start at its second. The NLP (its mesh and objective) must be the stride's own:
the replay reads its node times.
"""

from __future__ import annotations

import argparse
import pickle
import sys

import casadi as ca
import numpy as np

from formopt.io.muscle_table import body_muscles
from formopt.mechanics import muscles as hill
from formopt.mechanics.body import scaled_body
from formopt.optim.stride import ranges
from formopt.optim.stride.checks import forward, grid, muscle_dynamics, replayed
from formopt.optim.stride.collocation import NX, build
from formopt.optim.stride.problem import StrideSettings

COORDINATES = ("x", "y", "trunk", "hip_R", "knee_R", "ankle_R", "hip_L", "knee_L", "ankle_L")


def phase_errors(nlp, blocks: dict, parameters: dict) -> None:
    """Per phase the replay's largest angle, activation and force errors (module docstring)."""
    act = nlp.ocp.models[0].actuation
    n, names = act.n, act.muscles.names
    for i, phase in enumerate(nlp.phases):
        X, Z = blocks[f"X_{phase.name}"], blocks[f"Z_{phase.name}"]
        columns = grid(nlp, i)[1]
        path = replayed(nlp, i, blocks, parameters, True, np.r_[X[:, 0], Z[:, 0]])
        if path is None:
            print(f"  {phase.name:9s} replay failed")
            continue
        angle = np.abs(path[:NX, columns] - X[:NX])
        angle[:2] = 0.0
        j, k = np.unravel_index(angle.argmax(), angle.shape)
        z = np.abs(path[2 * NX:, columns] - Z)
        a_rows = np.r_[0:n, 2 * n:3 * n]
        f_rows = np.r_[n:2 * n, 3 * n:4 * n]
        ia, ka = np.unravel_index(z[a_rows].argmax(), z[a_rows].shape)
        jf, kf = np.unravel_index(z[f_rows].argmax(), z[f_rows].shape)
        leg = ("R", "L")
        print(f"  {phase.name:9s} T {blocks[f'T_{phase.name}'].item() * 1e3:6.1f} ms, {X.shape[1] - 1:3d} intervals:"
              f" angle {angle.max():.4f} rad ({COORDINATES[j]}, node {k}); a {z[a_rows].max():.3f}"
              f" ({names[ia % n]}_{leg[ia // n]}, node {ka}); F {z[f_rows].max():.3f}"
              f" ({names[jf % n]}_{leg[jf // n]}, node {kf})")


def local_errors(nlp, blocks: dict, parameters: dict, phase_name: str) -> None:
    """Phase `phase_name`'s one-interval errors: each interval replayed from the NLP's state at its
    first column to its second (the excitations and reserves linear between them), the largest
    angle (rad), angle rate (rad/s), activation and force errors at its end, beside the path's
    error grown from the phase's start (checks.replayed) at that column."""
    i = [p.name for p in nlp.phases].index(phase_name)
    act = nlp.ocp.models[i].actuation
    dynamics = muscle_dynamics(nlp, i)
    y, u0, u1 = ca.MX.sym("y", 2 * NX + act.states), ca.MX.sym("u0", act.controls), ca.MX.sym("u1", act.controls)
    h, s, td = ca.MX.sym("h"), ca.MX.sym("s"), ca.MX.sym("td", NX)
    rates = dynamics(y[:2 * NX], y[2 * NX:], u0 + s * (u1 - u0), td, parameters["slope"], parameters["mu"])
    step = ca.integrator("interval", "cvodes", {"x": y, "p": ca.vertcat(h, u0, u1, td), "t": s, "ode": h * rates},
                         0.0, 1.0, {"abstol": 1e-10, "reltol": 1e-10, "linear_multistep_method": "adams",
                                    "nonlinear_solver_iteration": "functional"})
    X, Z, U = (blocks[f"{k}_{phase_name}"] for k in "XZU")
    Y, t = np.vstack([X, Z]), nlp.times(i, blocks[f"T_{phase_name}"].item())
    td0 = blocks[f"X_{nlp.phases[0].name}"][:NX, 0]
    path = replayed(nlp, i, blocks, parameters, True, Y[:, 0])
    n = act.n
    print(f"  {phase_name}: interval, h ms, one-interval error: angle rad, rate rad/s, a, F | from the phase's start: angle rad")
    for k in range(X.shape[1] - 1):
        end = np.asarray(step(x0=Y[:, k], p=np.r_[t[k + 1] - t[k], U[:, k], U[:, k + 1], td0])["xf"], float).ravel()
        e = np.abs(end - Y[:, k + 1])
        grown = np.abs(path[3:NX, grid(nlp, i)[1][k + 1]] - X[3:NX, k + 1]).max()
        print(f"   {k:3d} {1e3 * (t[k + 1] - t[k]):5.1f}  {e[3:NX].max():.5f}  {e[NX + 3:2 * NX].max():7.4f}"
              f"  {e[2 * NX:][np.r_[0:n, 2 * n:3 * n]].max():.4f}  {e[2 * NX:][np.r_[n:2 * n, 3 * n:4 * n]].max():.4f} | {grown:.4f}")


def rates_and_chatter(nlp, blocks: dict, eps: float) -> None:
    """The loaded stance tendons' |F'| against eps, and each phase's excitation zig-zag."""
    act = nlp.ocp.models[0].actuation
    n = act.n
    loaded = []
    for phase in nlp.phases:
        Z, U = blocks[f"Z_{phase.name}"], blocks[f"U_{phase.name}"]
        if phase.rows:  # the right leg holds the ground: its tendons' forces F and rates F'
            F, Fd = Z[n:2 * n], act.RATE_SCALE * U[2 * n:3 * n]
            loaded.append(np.abs(Fd[F > 0.1]))
        E = np.vstack([U[3 * n * leg:3 * n * leg + n] for leg in range(2)])
        d = np.diff(E, axis=1)
        flips = np.sign(d[:, 1:]) * np.sign(d[:, :-1]) < 0
        zigzag = (flips[:, 1:] & flips[:, :-1]) & (np.abs(d[:, 1:-1]) > 0.02)
        Fds = act.RATE_SCALE * np.vstack([U[3 * n * leg + 2 * n:3 * n * (leg + 1)] for leg in range(2)])
        dF = np.diff(Fds, axis=1)
        fflips = (np.sign(dF[:, 1:]) * np.sign(dF[:, :-1]) < 0) & (np.abs(dF[:, 1:]) > 1.0)
        print(f"  {phase.name:9s} e zig-zags {zigzag.mean() * 100 if zigzag.size else 0:5.1f} % of nodes,"
              f" largest |de| {np.abs(d).max() if d.size else 0:.3f}; F' sign flips of its step > 1/s"
              f" {fflips.mean() * 100 if fflips.size else 0:5.1f} %, |F'| max {np.abs(Fds).max():.1f} /s")
    rates = np.concatenate(loaded)
    print(f"  stance leg, loaded tendons (F > 0.1): |F'| median {np.median(rates):.2f}, 25th {np.percentile(rates, 25):.2f},"
          f" 90th {np.percentile(rates, 90):.2f} /s, below eps {eps:g}: {np.mean(rates < eps) * 100:.0f} %")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--speed", type=float, default=2.5)
    parser.add_argument("--nodes", type=int, default=80)
    parser.add_argument("--grading", type=float, default=1.0)
    parser.add_argument("--power", type=int, default=1)
    parser.add_argument("--weight", type=float, default=12.0)
    parser.add_argument("--intervals", nargs="*", default=[], help="phases whose one-interval errors to print")
    parser.add_argument("--rate-smoothing", type=float, help="1/s: --power 1's eps (a what-if; 0.5)")
    args = parser.parse_args(argv)
    if args.rate_smoothing is not None:
        hill.FORCE_RATE_SMOOTHING = args.rate_smoothing
    ranges.allow_nodes(args.nodes)
    body = scaled_body(62.0, 1.81)
    settings = StrideSettings(strike="heel", nodes=args.nodes, objective="metabolic", grading=args.grading,
                              muscles=body_muscles(body), force_rate_weight=args.weight,
                              force_rate_power=args.power)
    nlp = build(body, settings)
    with open(args.file, "rb") as file:
        saved = pickle.load(file)
    blocks, parameters = saved["blocks"], {"speed": args.speed, "slope": 0.0, "mu": 0.8}
    sim = forward(nlp, blocks, parameters)
    print(f"{args.file}: {saved['cadence']:.1f} steps/min; forward (reset) {sim['reset_theta']:.4f} rad, per phase "
          + " ".join(f"{p.name} {e:.4f}" for p, e in zip(nlp.phases, sim["reset_per_phase"]))
          + f"; moments replayed {sim['moments_reset_theta']:.4f}")
    phase_errors(nlp, blocks, parameters)
    rates_and_chatter(nlp, blocks, hill.FORCE_RATE_SMOOTHING)
    for name in args.intervals:
        local_errors(nlp, blocks, parameters, name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
