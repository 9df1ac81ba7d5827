"""Where the stride's objective moves with the mesh (issue 34's N against 2N): RBDS001's body (62 kg,
1.81 m), heel strike, torque+springs (problem.RUNNER_TENDONS), effort, at an imposed cadence (or free), each
mesh solved from the one before (optim.stride.refine.refined: its node histories at both meshes' times,
guess.fitted), so every mesh solves the same stride.

    python problems/stride_mesh.py [--speed 3.5] [--cadence 130 (0: free)]
                                   [--meshes hermite-simpson:20 hermite-simpson:40 hermite-simpson:80]
                                   [--moment-time 0.012 (s; moment dynamics)] [--approach-speed 0.05 (m/s)]
                                   [--torque-velocity (the torque limit falls with the joint's rate)]
                                   [--smoothing 1e-5 (problem.SMOOTHING's weight, for this run)]
                                   [--smoothing-order 2 (that weight times (N / N_first)^2 at N)]
                                   [--no-release-row (no f_n = 0 row at a release)]
                                   [--consistency-rows exact|trapezoid|off (StrideSettings.consistency_rows;
                                    --no-consistency-rows: off)]
                                   [--cross-rows exact (each mesh solved again with that form from its optimum)]
                                   [--acceleration 3000 (rad/s^2: collocation.ACCELERATION, for this run)]
                                   [--ankle-max 40 (deg: the ankle's dorsiflexion range, for this run)]
                                   [--range-margin 60 (deg: every joint's range widened both ways, for this run)]
                                   [--state-rate 15 (m/s and rad/s: collocation.STATE_RATE, for this run)]
                                   [--no-release-height (no height row at a phase's first column for the
                                    points the phase before held)]
                                   [--no-stance-heights (no height row for the stance foot's free points)]
                                   [--mu 0.8 (the friction coefficient)]
                                   [--no-energy-rows (no rows on the held contacts' work and the energy budget)]
                                   [--fix-durations (the finer meshes' phase durations the first's)]
                                   [--grading 0.9 (StrideSettings.grading: each phase's mesh graded to its ends;
                                    a mesh's own as trapezoid:80:0.9)]
                                   [--durations heel=0.0532 flat=0.0801 ... (s: every mesh's, held)]
                                   [--hold-rate 100 (1/s: the held rows J a + dJ v + 2 r v_c + r^2 y_c = 0)]
                                   [--smooth-ends (each phase's end columns' controls on the line through
                                    their two neighbours: no one-column layer)]
                                   [--ipopt print_level=5 mu_strategy=monotone]
                                   [--strike heel|forefoot|flat] [--body 79 1.77 (kg, m: scaled_body's)]
                                   [--stance-knee-max 55 (deg: the stance knee's flexion bound in the
                                    phases with a contact, for this run)]
                                   [--tendons knee=0 (N m/rad per kg: a stance joint's spring over
                                    problem.RUNNER_TENDONS; 0 drops it)] [--impact-weight 1 (1/m)]
                                   [--figure mesh.png]

Prints a line of the run's model options, then per mesh (transcription:intervals): the objective,
the stance knee's deepest flexion and the impacts' T_c, the smoothing term (problem.SMOOTHING, or
--smoothing's weight: it replaces costs.SMOOTHING for the run; with --smoothing-order q, times
(N / N_first)^q at N intervals: q = 2 keeps the trapezoid's term, w h sum |A_k+1 - A_k|^2 ~ w h^2 int |A'|^2 dt,
one continuous penalty on every mesh),
with moment dynamics the moment-rate term (costs.py), the effort term per phase and per joint (and its end columns' layer: what their moments cost beyond their neighbours', and how far they lie off the line of their two neighbours: `layers`), the phase durations, the dropped points' normal force
(body weights) at the last column of their phase (heel-off, toe-off), each impact's approach speed
and impulse, the decision variables on
a finite bound by row, each column with its multiplier (A at collocation.ACCELERATION, F at
contact.FORCE_LIMIT, X at the joint ranges or STATE_RATE, U at the torque limit, T at a duration
bound), per phase its held rows' multipliers summed (a smooth optimum's fall as h: a sum that
grows with the mesh is a row the transcription fights), its node rows on a bound (heights and
clearance, friction cones) with their columns and multipliers and the three with the largest
multipliers, and the other rows' inequalities on a bound (transitions, impacts), each joint's fastest
rate (rad/s) over the half stride; IPOPT's iterations and CPU seconds; at the end, per
quantity, the change from each mesh to the next and (three meshes, each twice the one before)
the observed order and Richardson's limit (`convergence`). `--fix-durations`: each phase's duration
on the finer meshes held at the first mesh's optimum's (within PIN), and so the cadence: whether the
objective's drift is the optimum's timing moving with the mesh or inside the phases. `--figure`:
the torques, accelerations and contact forces per phase on normalised phase time, the meshes
overlaid (PNG).
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import math
import sys
import time

import casadi as ca
import matplotlib
import numpy as np

from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import GRAVITY, JOINTS, RANGES, THETA, JointSpace
from formopt.optim.stride import collocation, contact, costs, ocp, ranges
from formopt.optim.stride.collocation import StrideNLP, build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.ocp import INTEGRANDS
from formopt.optim.stride.problem import (
    CONSISTENCY_ROWS,
    OBJECTIVES,
    RUNNER_TENDONS,
    SMOOTHING,
    TENDON_JOINTS,
    TRANSCRIPTIONS,
    StrideSettings,
)
from formopt.optim.stride.refine import refined

matplotlib.use("Agg")
TIGHT = 1e-6  # a value this close to its bound (relative to max(1, |bound|)) is on it
PIN = 1e-7  # s: --fix-durations' half band about each duration (a band: StrideSettings wants low < high)


def phase_terms(nlp, b, speed: float) -> tuple[dict, dict, float]:
    """({phase: effort term per joint (6,)}, {phase: its end columns' layer, the effort their
    moments cost beyond their neighbours', w_0 (u_0^2 - u_1^2) + w_n (u_n^2 - u_n-1^2) summed over
    the joints}, smoothing term): the objective's parts (per distance)."""
    d = speed * sum(b[f"T_{p.name}"].item() for p in nlp.phases)
    effort, ends, smooth = {}, {}, 0.0
    for i, (phase, n, s) in enumerate(zip(nlp.phases, nlp.split, nlp.steps)):
        T, A = b[f"T_{phase.name}"].item(), b[f"A_{phase.name}"]
        w = np.asarray(nlp.transcription.weights(T / n, s), float).ravel()
        squares = nlp.moments(b, i)[0] ** 2 * 100 / (nlp.mass * GRAVITY) ** 2 / d
        effort[phase.name] = squares @ w
        ends[phase.name] = float((squares[:, [0, -1]] - squares[:, [1, -2]]).sum(axis=0) @ w[[0, -1]])
        smooth += costs.SMOOTHING * float(nlp.transcription.smoothing(ca.DM(A), T / n, s)) / d
    return effort, ends, smooth


def rate_term(nlp, solved, speed: float) -> float:
    """The moment-rate term of the objective (costs.py; 0 without moment dynamics)."""
    b, k = solved.blocks, INTEGRANDS.index("moment_rates")
    d = speed * sum(b[f"T_{p.name}"].item() for p in nlp.phases)
    integral = sum(float(L[k] @ w) for L, w in nlp.integrands(b, solved.parameters))
    return nlp.settings.moment_time ** 2 * 100 / (nlp.mass * GRAVITY) ** 2 * integral / d


def layers(U) -> tuple[float, float]:
    """How far a phase's first and last columns' controls lie off the line through their two
    neighbours (largest over the rows, N m/kg for torques): |u_0 - 2 u_1 + u_2|, |u_n - 2 u_n-1 + u_n-2|;
    O(h^2) on a smooth optimum, O(1) in a one-column layer."""
    U = np.asarray(U, float)
    return float(np.abs(U[:, 0] - 2 * U[:, 1] + U[:, 2]).max()), float(np.abs(U[:, -1] - 2 * U[:, -2] + U[:, -3]).max())


def near(values, bounds):
    """Which values are on their (finite) bounds (within TIGHT relative to max(1, |bound|))."""
    return np.isfinite(bounds) & (np.abs(values - bounds) <= TIGHT * np.maximum(1.0, np.abs(bounds)))


def row_name(block: str, row: int) -> str:
    """A block's row by name: THETA (and its rates, "d" before) for X and A, JOINTS for U."""
    names = {"X": (*THETA, *(f"d{t}" for t in THETA)), "A": THETA, "U": JOINTS}.get(block[0])
    return names[row] if names else str(row)


def at_columns(on, lam) -> str:
    """The columns where `on` holds with their |multiplier|: "3 (0.742), 4 (0.362)"."""
    return ", ".join(f"{c} ({lam[c]:.3g})" for c in np.flatnonzero(on))


def on_bounds(nlp, solved) -> tuple[list[str], list[str]]:
    """(the blocks' entries on a bound, per row: its columns and their |multiplier|; per phase,
    its node rows' inequalities on a bound, the same, and the three rows with the largest
    |multiplier|; last, the other rows' inequalities on a bound: transitions, impacts)."""
    b, x = nlp.blocks, solved.x
    at = near(x, np.concatenate(b.lower)) | near(x, np.concatenate(b.upper))
    blocks = []
    for name in b.names:
        s = slice(b.offsets[name], b.offsets[name] + int(np.prod(b.shapes[name])))
        on, lam = (v[s].reshape(b.shapes[name], order="F") for v in (at, np.abs(solved.lam_x)))
        blocks += [f"{name} {row_name(name, r)} at {on[r].sum()} of {on.shape[1]} columns: {at_columns(on[r], lam[r])}"
                   for r in np.flatnonzero(on.any(axis=1))]
    p = [solved.parameters[k] for k in ("speed", "slope", "mu")]
    g = np.asarray(ca.Function("g", [b.vector(), nlp.p], [nlp.problem["g"]])(x, p), float).ravel()
    on_row = (nlp.lbg < nlp.ubg) & (near(g, nlp.lbg) | near(g, nlp.ubg))  # lbg: as relaxed for the run
    rows, k = [], 0
    for i, phase in enumerate(nlp.phases):
        c, labels = nlp.columns[i], node_row_names(nlp.ocp.models[i])
        assert len(labels) == len(nlp.node_bounds[i][0]), "node_row_names: ocp.NodeModel's rows changed"
        on, lam = (v[k:k + len(labels) * c].reshape(c, len(labels)) for v in (on_row, np.abs(solved.lam_g)))
        top = np.argsort(lam.max(axis=0))[::-1][:3]
        held = [r for r, label in enumerate(labels) if label.startswith("held")]
        rows.append(f"{phase.name}: held rows' |lam| summed {lam[:, held].sum():.3g}; on a bound " + ("; ".join(f"{labels[r]} at {on[:, r].sum()} of {c}: "
                                                            f"{at_columns(on[:, r], lam[:, r])}"
                                                            for r in np.flatnonzero(on.any(axis=0))) or "-")
                    + "; largest lam " + " ".join(f"{labels[r]} {lam[:, r].max():.3g} at column "
                                                  f"{lam[:, r].argmax()}/{c - 1}" for r in top))
        k += len(labels) * c
    rest = np.flatnonzero(on_row[k:])
    rows.append(f"other rows: {len(rest)} on a bound, |lam| " + " ".join(f"{abs(solved.lam_g[k + j]):.3g}" for j in rest))
    return blocks, rows


def node_row_names(model) -> list[str]:
    """A torque rung's node rows by name, in ocp.NodeModel's order: the torque-velocity limit's
    (StrideSettings.torque_velocity), the free points' heights, the held rows (J a + dJ v), the
    friction cones, the equations of motion, the power split."""
    contact = model.contact
    sticking = [p for p, a in contact.rows if a == "t" and p != contact.sliding]
    limit = [f"torque-velocity {j} {side}" for side in ("extensor", "flexor") for j in JOINTS] \
        if model.actuation.velocity else []
    return (limit + [f"height {p}" for p in contact.free]
            + [f"held {contact.rows[k][0]} {contact.rows[k][1]}" for k in contact.held]
            + [f"cone {p} {side}" for p in sticking for side in "+-"] + [f"motion {t}" for t in THETA]
            + ([f"split {j}" for j in JOINTS] if model.split else []))


def release_forces(nlp, b) -> list[str]:
    """The dropped points' normal force (body weights) at the last column of their phase."""
    out = []
    for before, after in zip(nlp.phases, nlp.phases[1:]):
        for k, (point, axis) in enumerate(before.rows):
            if axis == "n" and point not in after.points:
                out.append(f"{point} {b[f'F_{before.name}'][k, -1]:.3f}")
    return out


def consistency_values(nlp, solved) -> str:
    """What the consistency rows hold (StrideSettings.consistency_rows), at a solution: each
    released point's height (mm) at the next phase's first column (its held drift), and the held
    contacts' work and the energy budget less the climb's work (mm: J per body weight)."""
    b = solved.blocks
    p = [solved.parameters[k] for k in ("speed", "slope", "mu")]
    heights = []
    for before, after in zip(nlp.phases, nlp.phases[1:]):
        for point in before.points:
            if point not in after.points:
                y = contact.height(nlp.js, point, ca.DM(b[f"X_{after.name}"][:len(THETA), 0]), p[1])
                heights.append(f"{point} {float(y) * 1e3:+.4f}")
    x = nlp.blocks.vector()
    weight = nlp.mass * GRAVITY
    climb = weight * p[0] * sum(b[f"T_{ph.name}"].item() for ph in nlp.phases) * math.sin(p[1])
    ground, balance = (float(ca.Function("e", [x, nlp.p], [nlp.integral(k)])(solved.x, p)) for k in ("ground", "balance"))
    energy = [ground / weight * 1e3, (balance - climb) / weight * 1e3]
    return (f"  consistency rows' values: released heights at the next phase's first column (mm) "
            f"{', '.join(heights)}; held contacts' work {energy[0]:+.4f} mm, energy budget {energy[1]:+.4f} mm")


def figure(path: str, meshes: list) -> None:
    """The torques (N m/kg), accelerations and contact forces (body weights) per phase on
    normalised phase time, one line per mesh (`meshes`: (label, nlp, blocks))."""
    import matplotlib.pyplot as plt
    phases = [p.name for p in meshes[0][1].phases]
    what = [("U", j, JOINTS[j]) for j in range(len(JOINTS))] + [("A", j, THETA[j]) for j in range(3, len(THETA))] \
        + [("F", j, f"row {j}") for j in range(3)]
    fig, axes = plt.subplots(len(what), len(phases), figsize=(4 * len(phases), 1.8 * len(what)), squeeze=False)
    for label, nlp, b in meshes:
        for c, phase in enumerate(phases):
            for r, (key, j, name) in enumerate(what):
                values = b[f"{key}_{phase}"]
                if j < values.shape[0]:
                    axes[r, c].plot(nlp.times(c, 1.0), values[j], ".-", ms=3, lw=0.8, label=label)
                axes[r, c].set_title(f"{phase} {key} {name}", fontsize=8)
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=60)


def pinned(blocks: dict) -> dict:
    """StrideSettings.duration with each solved phase's duration T (s) held to (T - PIN, T + PIN);
    the other phases' (a slide the solve did not take) the default bounds."""
    held = {k[2:]: (v.item() - PIN, v.item() + PIN) for k, v in blocks.items() if k.startswith("T_")}
    return {**StrideSettings().duration, **held}


def phase_duration(text: str) -> tuple[str, float]:
    """A phase's duration "phase=seconds" as (phase, seconds); a phase StrideSettings does not
    know is an error (it would hold nothing)."""
    phase, _, value = text.partition("=")
    if phase not in StrideSettings().duration:
        raise argparse.ArgumentTypeError(f"{text}: expected phase=seconds, a phase of "
                                         f"{', '.join(StrideSettings().duration)}")
    return phase, float(value)


def tendon(text: str) -> tuple[str, float]:
    """A stance joint's spring "joint=N m/rad per kg" (problem.TENDON_JOINTS) as (joint, k);
    k = 0 drops that joint's spring."""
    joint, _, value = text.partition("=")
    if joint not in TENDON_JOINTS:
        raise argparse.ArgumentTypeError(f"{text}: expected joint=k, a joint of {', '.join(TENDON_JOINTS)}")
    return joint, float(value)


def ipopt_option(text: str) -> tuple[str, int | float | str]:
    """An IPOPT option "key=value" as (key, value): an integer, a number or a string."""
    key, equals, value = text.partition("=")
    if not equals:
        raise argparse.ArgumentTypeError(f"{text!r}: expected an IPOPT option as key=value")
    for kind in (int, float):
        try:
            return key, kind(value)
        except ValueError:
            pass
    return key, value


def smooth_ends() -> None:
    """collocation.StrideNLP with rows u_0 - 2 u_1 + u_2 = 0 and u_n - 2 u_n-1 + u_n-2 = 0 on each
    phase's controls, for this process: its end columns without the one-column layer the
    transitions leave (a smooth optimum meets both to O(h^2))."""
    phase = collocation.StrideNLP._phase

    def with_ends(self, i):
        phase(self, i)
        U = self.v[f"U_{self.phases[i].name}"]
        self.rows.add(ca.horzcat(U[:, 0] - 2 * U[:, 1] + U[:, 2], U[:, -1] - 2 * U[:, -2] + U[:, -3]))
    collocation.StrideNLP._phase = with_ends  # type: ignore[method-assign]


def held_feedback(rate: float) -> None:
    """contact.RigidContact's held rows J a + dJ v = 0 as J a + dJ v + 2 r v_c + r^2 y_c = 0 (r = `rate`,
    1/s; v_c the rows' velocities, y_c the normal rows' heights), for this process: the held
    points' drift decays at r instead of growing with the transcription's error (Baumgarte)."""
    kinematics = contact.RigidContact.kinematics

    def fed_back(self, theta, thetad, slope):
        J, drift, v = kinematics(self, theta, thetad, slope)
        y = ca.vertcat(*[contact.height(self.js, p, theta, slope) if a == "n" else 0 for p, a in self.rows])
        return J, drift + 2 * rate * v + rate ** 2 * y, v
    contact.RigidContact.kinematics = fed_back  # type: ignore[method-assign]


def without_release_rows() -> None:
    """ocp.Release without its force rows (the dropped points' f_n = 0 at their phase's last
    column, which the trapezoid keeps), for this process: what the row's layer costs."""
    rows = ocp.Release.rows
    ocp.Release.rows = lambda self, *args: rows(dataclasses.replace(self, dropped=()), *args)  # type: ignore[method-assign]


def relax_heights(nlp, release: bool, stance: bool) -> None:
    """The NLP's node height rows made free (lower bound -inf) for this run: `release`, at each
    phase's first column those of the points the phase before held (their held drift); `stance`,
    at every column those of the free points of a leg that holds a point (the forefoot in the heel
    phase, the heel in the forefoot phase)."""
    k = 0
    for i, (model, c) in enumerate(zip(nlp.ocp.models, nlp.columns)):
        rows = len(nlp.node_bounds[i][0])
        assert len(node_row_names(model)) == rows, "relax_heights: the node rows are not the torque rung's"
        legs = {p[-1] for p in model.contact.points}
        for r, point in enumerate(model.contact.free):  # the height rows come first (node_row_names)
            held_before = i > 0 and point in nlp.phases[i - 1].points
            if release and held_before:
                nlp.lbg[k + r] = -np.inf
            if stance and point[-1] in legs:
                nlp.lbg[k + r:k + rows * c:rows] = -np.inf
        k += rows * c


def free_energy_rows(nlp) -> None:
    """The NLP's last two rows, the held contacts' work and the energy budget (collocation.StrideNLP,
    with springs), made free for this run: both hold in the continuous problem by themselves.
    Consistency rows "off" has none (its last two rows are a touchdown row and the half-period's)."""
    assert any(nlp.settings.tendons.values()), "free_energy_rows: no energy rows without springs"
    assert nlp.settings.consistency_rows != "off", "--no-energy-rows: consistency rows off has no energy rows"
    nlp.lbg[-2:], nlp.ubg[-2:] = -np.inf, np.inf


def convergence(name: str, values: list[float], nodes: list[int]) -> str:
    """The successive changes of `values` on meshes each twice the one before, in % of the
    coarser; with three or more, the observed order p = log2(d1 / d2) of the last three, the
    Richardson limit J_2N + d2 / (2^p - 1) (d2 = J_2N - J_N) and the change predicted from the
    last mesh to twice it, d2 / 2^p, in % (an order p <= 0 predicts nothing)."""
    text = f"  {name}: " + ", ".join(f"{n} -> {m} {(b / a - 1) * 100:+.2f} %"
                                      for a, b, n, m in zip(values, values[1:], nodes, nodes[1:]))
    if len(values) < 3 or any(m != 2 * n for n, m in itertools.pairwise(nodes)):
        return text
    d1, d2 = values[-2] - values[-3], values[-1] - values[-2]
    if d1 == 0 or d2 / d1 <= 0 or abs(d2) >= abs(d1):
        return text + f"; no order (d1 {d1:+.4g}, d2 {d2:+.4g})"
    p = math.log2(d1 / d2)
    limit, step = values[-1] + d2 / (2 ** p - 1), d2 / 2 ** p
    return (text + f"; order p {p:.2f}, Richardson limit {limit:.5g} ({(limit / values[-1] - 1) * 100:+.2f} % "
            f"from {nodes[-1]}), predicted {nodes[-1]} -> {2 * nodes[-1]} {step / values[-1] * 100:+.2f} %")


def mesh_token(text: str, grading: float) -> tuple[str, int, float]:
    """A mesh "transcription:intervals[:grading]" as (transcription, intervals, grading), the
    grading `grading` (--grading's) where the token gives none."""
    parts = text.split(":")
    if len(parts) not in (2, 3) or parts[0] not in TRANSCRIPTIONS:
        raise SystemExit(f"stride_mesh.py: error: --meshes {text!r}: expected transcription:intervals[:grading], the "
                         f"transcription one of {', '.join(TRANSCRIPTIONS)}")
    return parts[0], int(parts[1]), float(parts[2]) if len(parts) > 2 else grading


def model_options(parser: argparse.ArgumentParser) -> None:
    """The runner's and the model's options: the speed, the strike, the body, the friction, the
    stance knee's bound, the springs, the impacts' weight, the objective, moment dynamics, the
    approach floor and the torque-velocity limit."""
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--mu", type=float, default=0.8, help="the friction coefficient")
    parser.add_argument("--strike", default="heel", choices=("heel", "forefoot", "flat"))
    parser.add_argument("--body", nargs=2, type=float, default=[62.0, 1.81], metavar=("KG", "M"),
                        help="the body's mass and height (mechanics.body.scaled_body); RBDS001's by default")
    parser.add_argument("--stance-knee-max", type=float, default=0.0,
                        help="deg: the stance knee's flexion bound while its foot holds the ground")
    parser.add_argument("--tendons", nargs="*", default=[], type=tendon,
                        help="knee=0 ankle=4 (N m/rad per kg, over problem.RUNNER_TENDONS; 0 drops one)")
    parser.add_argument("--impact-weight", type=float, default=0.0,
                        help="StrideSettings.impact_weight (1/m): the impacts' T_c in the objective")
    parser.add_argument("--objective", default="effort", choices=OBJECTIVES[:-1],
                        help="StrideSettings.objective (the torque rungs')")
    parser.add_argument("--moment-time", type=float, default=0.0,
                        help="StrideSettings.moment_time (s): > 0, the moments as states (moment dynamics)")
    parser.add_argument("--approach-speed", type=float, default=0.0,
                        help="StrideSettings.approach_speed (m/s): each impact's least approach speed")
    parser.add_argument("--torque-velocity", action="store_true",
                        help="StrideSettings.torque_velocity: the torque limit falls with the joint's rate")


def parse(argv) -> argparse.Namespace:
    """The command line (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cadence", type=float, default=130.0, help="steps/min; 0: free")
    parser.add_argument("--meshes", nargs="+", default=[f"hermite-simpson:{n}" for n in (20, 40, 80)],
                        help="transcription:intervals[:grading], e.g. trapezoid:40 or trapezoid:80:0.9")
    parser.add_argument("--figure", default="")
    model_options(parser)
    parser.add_argument("--smoothing", type=float, default=SMOOTHING,
                        help="the smoothing term's weight (problem.SMOOTHING) for this run")
    parser.add_argument("--smoothing-order", type=float, default=0.0,
                        help="q: the smoothing's weight times (N / N_first)^q at N intervals")
    parser.add_argument("--acceleration", type=float, default=collocation.ACCELERATION,
                        help="the accelerations' bound (rad/s^2, collocation.ACCELERATION) for this run")
    parser.add_argument("--ankle-max", type=float, default=0.0,
                        help="deg: the ankle's dorsiflexion range's end for this run (0: joint_space.RANGES')")
    parser.add_argument("--range-margin", type=float, default=0.0,
                        help="deg: every joint's range (joint_space.RANGES) widened both ways, for this run")
    parser.add_argument("--state-rate", type=float, default=collocation.STATE_RATE,
                        help="the rates' bound (m/s and rad/s, collocation.STATE_RATE) for this run")
    parser.add_argument("--no-release-height", action="store_true",
                        help="no height row at a phase's first column for the points the phase before held")
    parser.add_argument("--no-stance-heights", action="store_true",
                        help="no height row for the free points of the leg that holds the ground")
    parser.add_argument("--no-energy-rows", action="store_true",
                        help="no rows on the held contacts' work and the energy budget (collocation, with springs)")
    parser.add_argument("--fix-durations", action="store_true",
                        help="the finer meshes' phase durations (and cadence) held at the first mesh's optimum's")
    parser.add_argument("--durations", nargs="*", default=[], type=phase_duration,
                        help="phase=seconds: each named phase's duration held on every mesh (within PIN)")
    parser.add_argument("--hold-rate", type=float, default=0.0,
                        help="1/s: the held rows with the contact's drift fed back (Baumgarte), for this run")
    parser.add_argument("--smooth-ends", action="store_true",
                        help="each phase's first and last columns' controls on the line through their two neighbours")
    parser.add_argument("--consistency-rows", default="exact", choices=CONSISTENCY_ROWS,
                        help="StrideSettings.consistency_rows")
    parser.add_argument("--no-consistency-rows", dest="consistency_rows", action="store_const", const="off",
                        help="StrideSettings.consistency_rows = \"off\"")
    parser.add_argument("--cross-rows", default="", choices=CONSISTENCY_ROWS,
                        help="each mesh solved again with this consistency_rows from its optimum")
    parser.add_argument("--no-release-row", action="store_true",
                        help="the releases without their f_n = 0 row (as Hermite-Simpson's torque sources)")
    parser.add_argument("--grading", type=float, default=0.0,
                        help="StrideSettings.grading: each phase's mesh graded toward its ends (0 uniform to 1)")
    parser.add_argument("--ipopt", nargs="*", default=[], type=ipopt_option,
                        help="IPOPT options over the stride's (key=value), e.g. print_level=5")
    args = parser.parse_args(argv)
    if args.smoothing < 0:
        parser.error(f"--smoothing {args.smoothing}: a weight >= 0")
    if args.no_energy_rows and args.consistency_rows == "off":
        parser.error("--no-energy-rows: consistency rows off has no energy rows")
    if args.no_release_height and "trapezoid" in (args.consistency_rows, args.cross_rows):
        parser.error("--no-release-height: consistency rows 'trapezoid' bound the released heights "
                     "by their own row (collocation._release_heights); use 'off'")
    args.meshes = [mesh_token(m, args.grading) for m in args.meshes]
    return args


def study_overrides(args) -> None:
    """The module constants a study changes for this process (read when each NLP is built):
    the release rows, the accelerations' and the ankle's bounds, and the nodes' range (a study
    past the scenes' 120 intervals, ranges.py: what solves cold; each mesh here is warm)."""
    if args.no_release_row:
        without_release_rows()
    if args.smooth_ends:
        smooth_ends()
    if args.hold_rate:
        held_feedback(args.hold_rate)
    collocation.ACCELERATION = args.acceleration
    collocation.STATE_RATE = args.state_rate
    widen = math.radians(args.range_margin)
    collocation.RANGES = {j: (lo - widen, hi + widen) for j, (lo, hi) in RANGES.items()}
    if args.ankle_max:
        collocation.RANGES["ankle"] = (collocation.RANGES["ankle"][0], math.radians(args.ankle_max))
    ranges.allow_nodes(max(n for _, n, _ in args.meshes))


def report(label: str, nlp, stride, seconds: float, speed: float) -> None:
    """One mesh's optimum as the module docstring lists."""
    b = stride.solved.blocks
    effort, ends, smooth = phase_terms(nlp, b, speed)
    blocks, rows = on_bounds(nlp, stride.solved)
    print(f"{label} (split {nlp.split}): objective {stride.objective_value:.5f} at "
          f"{stride.cadence_spm:.1f} steps/min, effort "
          f"{sum(e.sum() for e in effort.values()):.5f}, smoothing {smooth:.5f}, moment rates "
          f"{rate_term(nlp, stride.solved, speed):.5f}; converged {stride.success} "
          f"in {stride.iterations} iterations, {seconds:.1f} s CPU; valid {stride.valid} "
          f"{' '.join(stride.failed_checks)}; stance knee {stride.stance_knee_deg:.1f} deg, impacts "
          f"{stride.budget['impacts_J']:.2f} J; forward rad per phase "
          f"{' '.join(f'{e:.3f}' for e in stride.checks['forward_per_phase'])}", flush=True)
    for phase, e in effort.items():
        first, last = layers(b[f"U_{phase}"])
        print(f"  {phase:9s} {b[f'T_{phase}'].item() * 1e3:6.1f} ms  effort {e.sum():.5f} (end layers "
              f"{ends[phase]:.5f}; first / last column off the line of its neighbours {first:.2f} / {last:.2f} "
              f"N m/kg): " + " ".join(f"{j} {v:.5f}" for j, v in zip(JOINTS, e)), flush=True)
    print(f"  released with (BW): {', '.join(release_forces(nlp, b))}; impacts: "
          + ", ".join(f"{i['point']} {i['leg']} approach {i['approach_mps']:.4f} m/s, impulse (t, n) "
                      f"{i['impulse_Ns'][0]:.4g} {i['impulse_Ns'][1]:.4g} N s" for i in stride.impacts))
    print(consistency_values(nlp, stride.solved))
    print("  variables on a bound: " + ("; ".join(blocks) or "-"))
    print("\n".join(f"  node rows, {r}" for r in rows), flush=True)
    rates = np.asarray(stride.thetad, float)[:, 3:]
    at = np.abs(rates).argmax(axis=0)
    print("  fastest joint rates (rad/s, flexion and dorsiflexion positive; the phase of its first node): " + " ".join(
        f"{j} {rates[k, i]:+.1f} ({stride.phase[k]})" for i, (j, k) in enumerate(zip(JOINTS, at))), flush=True)


def study_nlp(args, body, settings: StrideSettings) -> StrideNLP:
    """The NLP of `settings` with the command line's IPOPT options and study options (the
    heights relaxed, the energy rows freed, the stance knee bounded)."""
    nlp = StrideNLP(JointSpace(body), settings, dict(args.ipopt)) if args.ipopt else build(body, settings)
    relax_heights(nlp, args.no_release_height, args.no_stance_heights)
    if args.no_energy_rows and settings.consistency_rows != "off":  # "off" has none
        free_energy_rows(nlp)
    if args.stance_knee_max:
        bound_stance_knee(nlp, math.radians(args.stance_knee_max))
    return nlp


def bound_stance_knee(nlp, high: float) -> None:
    """The stance knee's flexion (knee_R) at most `high` (rad) at every column of the phases with
    a contact: its states' upper bound (never loosened), before the NLP's first solve."""
    b = nlp.blocks
    for k, name in enumerate(b.names):
        if name.startswith("X_") and any(p.rows for p in nlp.phases if name == f"X_{p.name}"):
            b.upper[k] = b.upper[k].copy()
            rows = slice(THETA.index("knee_R"), None, b.shapes[name][0])
            b.upper[k][rows] = np.minimum(b.upper[k][rows], high)


def cross(args, body, settings, stride, label: str) -> None:
    """The mesh's NLP with StrideSettings.consistency_rows `args.cross_rows` (and the run's other
    options), solved from this mesh's optimum and reported: whether the other form's optimum lies
    near this one's."""
    nlp = study_nlp(args, body, dataclasses.replace(settings, consistency_rows=args.cross_rows))
    clock = time.process_time()
    other = refined(nlp, stride)
    report(f"{label}, consistency rows {args.cross_rows} from it", nlp, other, time.process_time() - clock, args.speed)


def main(argv=None) -> int:
    args = parse(argv)
    study_overrides(args)
    body, stride, solved, objectives, cadences = scaled_body(*args.body), None, [], [], []
    print(f"body {args.body[0]:g} kg, {args.body[1]:g} m; {args.strike} strike, {args.speed:g} m/s, cadence "
          f"{args.cadence or 'free'}; springs {({**RUNNER_TENDONS, **dict(args.tendons)})}, impact weight "
          f"{args.impact_weight:g}, objective {args.objective}, torque-velocity {args.torque_velocity}, rate bound "
          f"{args.state_rate:g}, acceleration bound {args.acceleration:g}, stance knee bound "
          f"{args.stance_knee_max or '-'} deg, mu {args.mu:g}", flush=True)
    durations = {**StrideSettings().duration, **{k: (v - PIN, v + PIN) for k, v in args.durations}}
    for transcription, nodes, grading in args.meshes:
        # costs.terms reads it when each NLP is built
        costs.SMOOTHING = args.smoothing * (nodes / args.meshes[0][1]) ** args.smoothing_order
        settings = StrideSettings(strike=args.strike, nodes=nodes, impact_weight=args.impact_weight,
                                  objective=args.objective,
                                  tendons={**RUNNER_TENDONS, **dict(args.tendons)},
                                  transcription=transcription, moment_time=args.moment_time,
                                  approach_speed=args.approach_speed, duration=durations,
                                  consistency_rows=args.consistency_rows, grading=grading,
                                  torque_velocity=args.torque_velocity)
        nlp = study_nlp(args, body, settings)
        clock = time.process_time()
        stride = refined(nlp, stride, solved[-1][1]) if solved else \
            optimum(nlp, args.speed, mu=args.mu, cadence=args.cadence or None)
        label = f"{transcription} {nodes}" + (f" graded {grading:g}" if grading else "")
        report(label, nlp, stride, time.process_time() - clock, args.speed)
        if args.cross_rows:
            cross(args, body, settings, stride, label)
        guess = stride.solved.blocks
        if args.fix_durations and not solved:
            durations = pinned(guess)
        objectives.append(stride.objective_value)
        cadences.append(stride.cadence_spm)
        solved.append((label, nlp, guess))
    if len(args.meshes) > 1:
        print("mesh convergence (each mesh twice the one before; converged or not, as printed above):")
        for name, values in (("objective", objectives), ("cadence", cadences)):
            print(convergence(name, values, [n for _, n, _ in args.meshes]))
    if args.figure:
        figure(args.figure, solved)
    return 0


if __name__ == "__main__":
    sys.exit(main())
