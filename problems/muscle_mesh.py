"""The muscles' stride on N against 2N nodes (issue 34 item 2 on issue 33's body): RBDS001's body
(62 kg, 1.81 m; `--mass`: another mass at the same height), `actuation = "muscles"`
(io.muscle_table.body_muscles, "metabolic" objective, the default force-rate and reserve
weights), free cadence, at one speed and strike. The first
mesh's stride is the global search's answer there (optim.stride.search.global_optimum at
`--spend`: the stride the tables of docs/concepts/muscles.md report), or with `--start path`
the default path's (local.optimum's one start: problems/stride_ladder.py's); each finer mesh
is solved from the one before (optim.stride.refine.refined: its node histories interpolated onto the
finer mesh, guess.fitted), so every mesh solves the same stride.

    python problems/muscle_mesh.py [--speed 3.5] [--strike heel|forefoot] [--nodes 40 80 160]
                                   [--start search|path] [--spend 1] [--mu-init 3e-4 1e-2]
                                   [--no-consistency-rows [--rows-first]]
                                   [--grading 0.9 [--first-grading 0]] (a mesh's own: --nodes 160:1;
                                   a phase's duration held, ms: --nodes 160:0@flat=59.5-60.1)
                                   [--replay-cost] [--power 1] [--goals] [--angles] [--mass 75]
                                   [--activation-smoothing 0 10 [--chained]] [--direct] [--ipopt max_cpu_time=600 ...]
                                   [--transcription hermite-simpson (a mesh's own: --nodes 160/trapezoid)]
                                   [--weight 14] [--stance-knee-max 50 (deg; with --direct: refine's
                                    continuation solves variants without it)]

Prints per mesh: cadence (steps/min), objective (per distance), stance (s), the stance knee's
deepest flexion (deg), the phases' durations (ms; one on its duration bound marked low or high), validity and the failed checks,
the forward check's worst deviation per phase (rad: the excitations replayed, each phase
from the NLP's state at its start), the held points' contact drift (mm), the energy budget's
balance (% of W+), the reserves' largest mean over 10 ms and largest node value (N m/kg), IPOPT's iterations (the kept
solve's; the search's total in brackets) and its return status and the CPU seconds (time.process_time, the search
or solve with its checks; under the search's answer its record: spend, solves, the grid's
objective per cadence, the optima met and their spread), and the objective's parts per phase and cost term (costs.terms:
the muscles' energy, the force rate, the muscle rates, the reserves, the smoothing; `phase_costs`)
with the force-rate term's part at each phase's first and last column (a layer at its ends);
after each finer mesh the change of cost and cadence from the one before (%) and each part's
change with its share of the objective's (where the cost's drift sits), and at the end, with three meshes each twice the one before, their observed
order and Richardson's limit (problems/stride_mesh.py's `convergence`). `--mu-init`: each finer
mesh solved from the interpolated stride with IPOPT's barrier starting at each value, each
reported; the first value's stride is the one the next mesh starts from. The default is the
muscles' warm start's (ipopt_options.MUSCLE_WARM_START, 3e-4), which keeps the iterate near the
stride it starts from; their cold solves' 1e-2 (MUSCLE_IPOPT) can leave it: at 2.5 m/s (heel)
the search's 152.9 steps/min at 40 nodes went to 148.0 at 80 from 3e-4, to 170.2 (another
optimum, 6 % costlier) from 1e-2. `--no-consistency-rows`: every mesh, the first one's too, with
StrideSettings.consistency_rows "off" (the rows the continuous stride meets by itself dropped);
with `--rows-first` the first mesh's stride is solved with them, then without them from it (as a
finer mesh is from the one before), so that every mesh solves the rows-kept stride's neighbour.
`--grading g`: every mesh graded toward each phase's ends (StrideSettings.grading); with
`--first-grading`, the first mesh's grading (e.g. 0: the uniform stride continued on graded
meshes). Each finer mesh starts from the one before at both meshes' node times (guess.fitted).
`--replay-cost`: at the end, each mesh's force-rate integral per phase by the NLP's quadrature
and along its excitations replayed forward (`replayed_force_rate`): the cost of each stride's
controls by a method no mesh's quadrature shares. `--goals`: at the end, each mesh's stride in
problems/stride_ladder.py's columns (its `row`: cadence, stance, peak vertical force, the joint
angles' RMS, peak ankle power, the tendons' energy, the swing foot's height...) against
RBDS001's processed mean cycle: issue 33's goals on the searched, refined stride. `--angles`:
the finest mesh's joint angles taken apart (problems/stride_angles.py's `table`: per joint the
offset, the time shift, the shape, the range and when the extremes fall; at 2.5 and 3.5 m/s the
thigh from the vertical against the runner's markers) and its ankle push-off against the
runner's (`push_off`). `--activation-smoothing S...`: the last mesh solved from the one before with
the activations' rates' scale in the transcription's smoothing (StrideSettings.activation_rate_smoothing)
at each value in turn, each reported (the meshes before at the default); with `--chained` each
value's solve from the one before's stride, not from the mesh before (a continuation; the scales' solves
are each one, to its end). Each finer mesh is solved as refine.refined solves it: directly, IPOPT stopped at
its first restoration phase, and where that fails without the activations' rates' smoothing first, then with
it from there (refine.continued; the iterations printed "D direct + U unsmoothed + N"); `--direct`: each finer
mesh solved directly to its end (the chain before 2026-11-27 evening, for the measurement:
docs/concepts/muscles.md, "The refinement's continuation"). `--ipopt KEY=VALUE...`:
IPOPT options over the finer meshes' solves (e.g. max_cpu_time=600, output_file=ipopt.log
file_print_level=5: a slow solve's iterations), each of a continuation's three solves getting them
(max_cpu_time=S: up to 3 S a mesh). `--transcription hermite-simpson`: every mesh on Hermite-Simpson
(--nodes its intervals), or one mesh's own with "/": `--nodes 20 40 80/trapezoid` continues the
40-interval stride on the 80-node trapezoid (guess.fitted reads it at its own columns' times);
`--weight W`: StrideSettings.force_rate_weight on every mesh (default the power's calibrated one;
docs/concepts/muscles.md, "On Hermite-Simpson").
"""

from __future__ import annotations

import argparse
import itertools
import math
import sys
import time

import casadi as ca
import numpy as np
from stride_angles import TRIALS, measured_segments, table  # problems/, this script's directory
from stride_ladder import RBDS, header, row
from stride_mesh import bound_stance_knee, convergence, ipopt_option

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import scaled_body
from formopt.mechanics.joint_space import JOINTS
from formopt.optim.stride import checks, problem, ranges
from formopt.optim.stride.actuation import ACTIVATION_RATE_SMOOTHING
from formopt.optim.stride.collocation import NX, build
from formopt.optim.stride.ipopt_options import MUSCLE_WARM_START
from formopt.optim.stride.local import optimum
from formopt.optim.stride.ocp import INTEGRANDS, step_length
from formopt.optim.stride.problem import StrideSettings
from formopt.optim.stride.refine import refined
from formopt.optim.stride.search import global_optimum
from formopt.studies.stride import measured_cycle, predicted_cycle


def label(settings) -> str:
    """A mesh's name: "80 nodes", "40 intervals Hermite-Simpson", with its grading where not 0."""
    mesh = "intervals Hermite-Simpson" if settings.transcription == "hermite-simpson" else "nodes"
    return f"{settings.nodes} {mesh}" + (f" graded {settings.grading:g}" if settings.grading else "")


def report(settings, stride, seconds: float) -> str:
    """One mesh's stride as the module docstring lists (`settings`: its mesh's StrideSettings)."""
    bound = {b["phase"]: b["side"] for b in stride.on_bound}
    phases = " ".join(f"{name} {d * 1e3:.1f}" + (f" ({bound[name]})" if name in bound else "")
                      for name, d in stride.phases)
    forward = " ".join(f"{e:.3f}" for e in stride.checks.get("forward_per_phase", []))
    total = f" [{stride.search['iterations']}]" if stride.search else ""
    tried = stride.checks.get("continuation")  # refine.continued's tries
    tries = (f"{tried['direct_iterations']} direct ({tried['direct_status']}) + {tried['unsmoothed_iterations']} "
             f"unsmoothed ({tried['unsmoothed_status']}) + ") if tried else ""
    return (f"  {label(settings)}: {stride.cadence_spm:.1f} steps/min, objective {stride.objective_value:.5f}, "
            f"stance {stride.stance_s:.3f} s, knee {stride.stance_knee_deg:.1f} deg at most; phases ms: {phases}; valid "
            f"{'yes' if stride.valid else 'NO: ' + ('; '.join(stride.failed_checks) or stride.status)}; forward rad per phase [{forward}]; drift "
            f"{stride.checks['drift_m'] * 1e3:.3f} mm, balance {stride.checks['balance_relative'] * 100:.2e} %, "
            f"reserves {stride.checks['reserve_nm_per_kg']:.3f} N m/kg over 10 ms ({stride.checks['reserve_peak_nm_per_kg']:.3f} at a node); {tries}{stride.iterations}{total} iterations ({stride.status}), "
            f"{seconds:.1f} s CPU")


def search_record(search: dict) -> str:
    """The search's record (optim.stride.search): its spend, solves, the grid's least objective
    per cadence, the distinct optima met (cadence: objective, validity) and their spread (%)."""
    grid = " ".join(f"{c:.0f}: " + ("-" if o is None else f"{o:.4f}")
                    for c, o in zip(search["grid_spm"], search["grid_objective"]))
    optima = ", ".join(f"{o['cadence_spm']:.1f}: {o['objective']:.4f}"
                       + ("" if o["valid"] else " invalid (" + "; ".join(o["failed"]) + ")")
                       + (" (answer)" if o["answer"] else "") for o in search["optima"])
    spread = "none converged" if search["spread_pct"] is None else f"{search['spread_pct']:.2f} %"
    return (f"  search: spend {search['spend']}, {search['solves']} solves, grid steps/min: objective "
            f"[{grid}]; optima met [{optima}], spread {spread}")


def phase_costs(nlp, solved, speed: float, column: int | None = None) -> dict[str, dict[str, float]]:
    """{phase: {cost term: its part of the objective}}: each of the NLP's terms (costs.terms)
    with its integral over that phase alone, w s I_phase / d (d = v T the whole step's), so that
    the parts sum to the objective; the impacts (at transitions) left out: the muscles' weight is 0.
    With `column` (0 or -1), only that column's share of each integral (the smoothing 0): a
    layer at the phase's ends shows there."""
    b = solved.blocks
    d = step_length(speed, sum(b[f"T_{p.name}"].item() for p in nlp.phases))
    out = {}
    for phase, n, s, (L, w) in zip(nlp.phases, nlp.split, nlp.steps, nlp.integrands(b, solved.parameters)):
        if column is not None:
            w = w * (np.arange(w.size) == np.arange(w.size)[column])
        integrals = dict(zip(INTEGRANDS, L @ w))
        integrals["smoothing"] = 0.0 if column is not None else float(nlp.transcription.smoothing(
            ca.DM(b[f"A_{phase.name}"]), b[f"T_{phase.name}"].item() / n, s))
        out[phase.name] = {t.integral: float(t(integrals, d)) for t in nlp.ocp.cost_terms if t.integral != "impacts"}
    return out


def costs_table(parts: dict) -> str:
    """The objective's parts per phase and term (`phase_costs`), each phase's sum and each term's."""
    terms = list(next(iter(parts.values())))
    lines = [f"  {phase:9s} " + " ".join(f"{t} {v:.5f}" for t, v in row.items()) + f" | {sum(row.values()):.5f}"
             for phase, row in parts.items()]
    totals = {t: sum(row[t] for row in parts.values()) for t in terms}
    return "\n".join(lines + ["  all       " + " ".join(f"{t} {v:.5f}" for t, v in totals.items())
                              + f" | {sum(totals.values()):.5f}"])


def end_columns(nlp, solved, speed: float) -> str:
    """The force-rate term's part at each phase's first and last column (`phase_costs`' column)."""
    first, last = (phase_costs(nlp, solved, speed, column) for column in (0, -1))
    key = "force_rate_abs" if nlp.settings.force_rate_power == 1 else "force_rate"
    return "  force rate at the first / last column: " + " ".join(
        f"{p} {first[p][key]:.5f} / {last[p][key]:.5f}" for p in first)


def reserve_peaks(nlp, solved, top: int = 2) -> str:
    """Where the reserves' largest node values sit: the `top` joints' (each joint's largest), with
    its phase and column (N m/kg, signed)."""
    n = nlp.ocp.models[0].actuation.n
    peaks = []
    for p in nlp.phases:
        R = solved.blocks[f"U_{p.name}"][6 * n:]
        for j, joint in enumerate(JOINTS):
            k = int(np.abs(R[j]).argmax())
            peaks.append((abs(R[j, k]), f"{joint} {R[j, k]:+.3f} ({p.name}, column {k} of {R.shape[1] - 1})"))
    best = {}
    for _value, text in sorted(peaks, reverse=True):
        best.setdefault(text.split()[0], text)
    return "largest reserves at a node: " + ", ".join(list(best.values())[:top])


def costs_change(before: dict, after: dict) -> str:
    """The parts' change from one mesh to the next (`phase_costs`), each with its share of the
    objective's change (%), per phase and term, each phase's and each term's."""
    delta = {p: {t: after[p][t] - v for t, v in row.items()} for p, row in before.items()}
    total = sum(sum(row.values()) for row in delta.values())

    def share(v: float) -> str:
        return f"{v:+.5f} ({v / total * 100:+.0f} %)"

    lines = [f"  {p:9s} " + " ".join(f"{t} {share(v)}" for t, v in row.items()) + f" | {share(sum(row.values()))}"
             for p, row in delta.items()]
    terms = {t: sum(row[t] for row in delta.values()) for t in next(iter(delta.values()))}
    return "\n".join(["  the parts' change (share of the objective's):", *lines,
                      "  all       " + " ".join(f"{t} {share(v)}" for t, v in terms.items()) + f" | {total:+.5f}"])


def change(before, after) -> str:
    """The cost's and cadence's change from one mesh's stride to the next (%)."""
    return (f"  change: cost {(after.objective_value / before.objective_value - 1) * 100:+.2f} %, "
            f"cadence {(after.cadence_spm / before.cadence_spm - 1) * 100:+.2f} %")


def finer(nlp, speed: float, before, mu_inits: list[float], ipopt: dict, continuation: bool = True):
    """The stride on `nlp`'s (finer) mesh from `before` (a stride, its `phase_costs` and its NLP)
    interpolated onto it (guess.fitted, at both meshes' times), solved with IPOPT's barrier
    starting at each of `mu_inits` in turn (`ipopt`: options over them; refine.refined, directly
    to the end without `continuation`), each reported with its change from `before`;
    returns the first (with its parts and NLP)."""
    out = []
    for mu in mu_inits:
        clock = time.process_time()
        solver = nlp.variant({"mu_init": mu, **ipopt})
        solver.blocks.upper = [u.copy() for u in nlp.blocks.upper]  # the study's bounds (--stance-knee-max)
        stride = refined(solver, before[0], before[2], continuation=continuation)
        print(report(nlp.settings, stride, time.process_time() - clock)
              + f" (mu_init {mu:g})", flush=True)
        parts = phase_costs(nlp, stride.solved, speed)
        print(costs_table(parts) + "\n" + end_columns(nlp, stride.solved, speed) + "\n  "
              + reserve_peaks(nlp, stride.solved), flush=True)
        print(change(before[0], stride), flush=True)
        print(costs_change(before[1], parts), flush=True)
        out.append((stride, parts, nlp))
    return out[0]


def mesh(body, args, nodes: int, consistency_rows: str, grading: float, held: dict | None = None,
         smoothing: float = ACTIVATION_RATE_SMOOTHING, scheme: str | None = None):
    """The muscles' stride NLP on `nodes` nodes at the command line's strike and `grading`;
    `held`: phase -> (low, high) duration bounds (s) over StrideSettings' defaults; `smoothing`:
    StrideSettings.activation_rate_smoothing; `scheme`: the transcription (default --transcription's)."""
    duration = {**StrideSettings().duration, **(held or {})}
    settings = StrideSettings(strike=args.strike, nodes=nodes, muscles=body_muscles(body), objective="metabolic",
                              consistency_rows=consistency_rows, grading=grading, duration=duration,
                              force_rate_power=args.power, activation_rate_smoothing=smoothing,
                              transcription=scheme or args.transcription, force_rate_weight=args.weight)
    nlp = build(body, settings)
    if args.stance_knee_max:
        bound_stance_knee(nlp, math.radians(args.stance_knee_max))
    return nlp


def start(nlp, args):
    """The first mesh's stride: the search's answer at `--spend`, or the default path's; reported,
    with its `phase_costs` and NLP."""
    clock = time.process_time()
    stride = global_optimum(nlp, args.speed, spend=args.spend) if args.start == "search" else optimum(nlp, args.speed)
    print(report(nlp.settings, stride, time.process_time() - clock), flush=True)
    if stride.search:
        print(search_record(stride.search), flush=True)
    parts = phase_costs(nlp, stride.solved, args.speed)
    print(costs_table(parts) + "\n" + end_columns(nlp, stride.solved, args.speed) + "\n  "
          + reserve_peaks(nlp, stride.solved), flush=True)
    return stride, parts, nlp


def smoothings(body, args, nodes: int, grading: float, held: dict, before, scheme: str | None = None):
    """The last mesh solved at each of `--activation-smoothing`'s scales (StrideSettings.
    activation_rate_smoothing) from `before` (`finer`'s), or with `--chained` from the scale
    before's stride; returns the last scale's."""
    last = before
    for scale in args.activation_smoothing:
        print(f"the activations' rates' smoothing scale {scale:g}:", flush=True)
        last = finer(mesh(body, args, nodes, args.consistency_rows, grading, held, scale, scheme),
                     args.speed, last if args.chained else before, args.mu_init, args.ipopt, continuation=False)
    return last


def replayed_force_rate(nlp, stride) -> str:
    """The force-rate integral int sum_legs sum_i V_i F'_i^2 / sum_i V_i dt (1/s, costs'
    "force_rate" before its weight and distance) per phase, by the NLP's quadrature and along
    the stride's excitations replayed (checks.replayed: each phase from the NLP's state at its
    start, CVODES at 1e-10, F' from the Hill equilibrium; trapezoid on 40 points an interval): an
    evaluation of the stride's cost that no mesh's quadrature makes."""
    blocks, par = stride.solved.blocks, stride.solved.parameters
    act = nlp.ocp.models[0].actuation
    n, volume = act.n, act.muscles.volume / act.muscles.volume.sum()
    k = INTEGRANDS.index("force_rate")
    quadrature = [float(L[k] @ w) for L, w in nlp.integrands(blocks, par)]
    replayed = []
    td = blocks[f"X_{nlp.phases[0].name}"][:NX, 0]
    for i, phase in enumerate(nlp.phases):
        columns, U, T = nlp.times(i, 1.0), blocks[f"U_{phase.name}"], blocks[f"T_{phase.name}"].item()
        start = np.r_[blocks[f"X_{phase.name}"][:, 0], blocks[f"Z_{phase.name}"][:, 0]]
        fine = np.unique(np.concatenate([np.linspace(a, b, 41) for a, b in itertools.pairwise(columns)]))
        path = checks.replayed(nlp, i, blocks, par, True, start, fine)
        if path is None:  # the replay failed
            replayed.append(np.inf)
            continue
        u = np.array([np.interp(fine, columns, row) for row in U])  # the controls linear between the columns
        rates = np.asarray(checks.muscle_dynamics(nlp, i).map(fine.size)(
            path[:2 * NX], path[2 * NX:], u, np.repeat(td[:, None], fine.size, 1), par["slope"], par["mu"]))[2 * NX:]
        values = volume @ rates[n:2 * n] ** 2 + volume @ rates[3 * n:] ** 2  # z' = [a'_R, F'_R, a'_L, F'_L]
        replayed.append(float(np.trapezoid(values, T * fine)))
    parts = "; ".join(f"{p.name} {q:.4f} / {r:.4f}" for p, q, r in zip(nlp.phases, quadrature, replayed))
    return (f"  {label(nlp.settings)}: force-rate integral, quadrature / replayed: {parts}; "
            f"all {sum(quadrature):.4f} / {sum(replayed):.4f}")


def goals(strides, speed: float) -> str:
    """Each mesh's stride in problems/stride_ladder.py's columns (its `row`: issue 33's goals)
    against RBDS001's processed mean cycle and measured cadence at `speed`."""
    measured = measured_cycle(RBDS, speed)
    rows = [row(label(nlp.settings), speed, stride, measured) for stride, _, nlp in strides]
    return "\n".join(["issue 33's goals (problems/stride_ladder.py's columns):", header("mesh objective"), *rows])


def push_off(stride, measured: dict) -> str:
    """The ankle's peak positive power (W/kg, P = -tau theta'), predicted and measured (the data
    set's own joint power), with when it peaks (% of the cycle), the net moment there (N m/kg),
    the joint's speed P / |M| (rad/s) that makes it, and the largest moment (N m/kg)."""
    parts = []
    for name, cycle in (("predicted", predicted_cycle(stride)), ("measured", measured)):
        P, M = np.nan_to_num(cycle["powers"]["ankle"]), np.nan_to_num(cycle["moments"]["ankle"])
        k = int(np.argmax(P))
        parts.append(f"{name} {P[k]:.1f} W/kg at {cycle['percent'][k]:.0f} % of the cycle, moment "
                     f"{abs(M[k]):.2f} N m/kg at {P[k] / abs(M[k]):.1f} rad/s, largest moment {np.abs(M).max():.2f}")
    return "ankle push-off: " + "; ".join(parts)


def node_token(text: str) -> tuple[int, float | None, dict, str | None]:
    """A mesh "nodes[:grading][@phase=low-high][/transcription]" as (nodes, grading or None:
    --first-grading's or --grading's, {phase: (low, high) s}: a phase's duration held between low
    and high ms, transcription or None: --transcription's)."""
    text, slash, scheme = text.partition("/")
    if slash and scheme not in problem.TRANSCRIPTIONS:
        raise argparse.ArgumentTypeError(f"{scheme!r}: expected a transcription of {', '.join(problem.TRANSCRIPTIONS)}")
    mesh, _, held = text.partition("@")
    nodes, _, grading = mesh.partition(":")
    bounds = {}
    if held:
        phase, _, span = held.partition("=")
        low, _, high = span.partition("-")
        try:
            bounds[phase] = (float(low) * 1e-3, float(high) * 1e-3)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: expected nodes[:grading][@phase=low-high][/transcription], "
                                             "the phase's duration in ms") from None
    return int(nodes), float(grading) if grading else None, bounds, scheme or None


def arguments(argv):
    """The command line's options (the module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5)
    parser.add_argument("--strike", default="heel", choices=problem.STRIKES)
    parser.add_argument("--nodes", type=node_token, nargs="+", default=[(40, None, {}, None), (80, None, {}, None)],
                        help="nodes[:grading][@phase=low-high][/transcription] per mesh, e.g. 160:1, 160:0@flat=59.5-60.1 "
                             "or 80/trapezoid "
                             "(default grading --grading's; a phase's duration held in ms)")
    parser.add_argument("--start", default="search", choices=("search", "path"))
    parser.add_argument("--spend", type=int, default=1)
    parser.add_argument("--power", type=int, default=2, choices=problem.FORCE_RATE_POWERS,
                        help="the force-rate term's power (its calibrated weight)")
    parser.add_argument("--mu-init", type=float, nargs="+", default=[MUSCLE_WARM_START["mu_init"]],
                        help="IPOPT's first barrier for each finer mesh's solve, each in turn")
    parser.add_argument("--no-consistency-rows", dest="consistency_rows", action="store_const", const="off",
                        default="exact", help="StrideSettings.consistency_rows \"off\" on every mesh")
    parser.add_argument("--grading", type=float, default=0.0,
                        help="StrideSettings.grading on every mesh: each phase's mesh graded toward its ends")
    parser.add_argument("--stance-knee-max", type=float, default=0.0,
                        help="deg: the stance knee's flexion bound (stride_mesh.py's), on every mesh")
    parser.add_argument("--weight", type=float, default=None,
                        help="StrideSettings.force_rate_weight (default the power's calibrated one)")
    parser.add_argument("--transcription", default="trapezoid", choices=problem.TRANSCRIPTIONS,
                        help="StrideSettings.transcription on every mesh (Hermite-Simpson: --nodes are intervals)")
    parser.add_argument("--first-grading", type=float, default=None,
                        help="the first mesh's grading (default --grading's), the finer meshes' --grading")
    parser.add_argument("--rows-first", action="store_true",
                        help="the first mesh's stride solved with the rows, then without them from it")
    parser.add_argument("--replay-cost", action="store_true",
                        help="at the end, each mesh's force-rate integral by its quadrature and replayed")
    parser.add_argument("--goals", action="store_true",
                        help="at the end, each mesh's stride in problems/stride_ladder.py's goal columns")
    parser.add_argument("--angles", action="store_true",
                        help="at the end, the finest mesh's joint angles taken apart and its ankle push-off")
    parser.add_argument("--mass", type=float, default=62.0,
                        help="the body's mass (kg) at RBDS001's height: a heavier runner")
    parser.add_argument("--activation-smoothing", type=float, nargs="+", default=None,
                        help="the last mesh solved at each a' scale in the smoothing (StrideSettings.activation_rate_smoothing)")
    parser.add_argument("--chained", action="store_true",
                        help="with --activation-smoothing, each scale's solve from the one before's stride (a continuation)")
    parser.add_argument("--direct", action="store_true",
                        help="each finer mesh solved directly to its end, without refine.refined's continuation")
    parser.add_argument("--ipopt", type=ipopt_option, nargs="+", default=[],
                        help="KEY=VALUE IPOPT options over the finer meshes' solves (each of a continuation's three), e.g. max_cpu_time=600")
    args = parser.parse_args(argv)
    args.ipopt = dict(args.ipopt)
    if args.replay_cost and args.power != 2:
        parser.error("--replay-cost replays the squared force rates: it needs --power 2")
    return args


def main(argv=None) -> int:
    args = arguments(argv)
    ranges.allow_nodes(max(n for n, *_ in args.nodes))
    body = scaled_body(args.mass, 1.81)
    print(f"RBDS001's {'body' if args.mass == 62.0 else 'height'} ({args.mass:g} kg, 1.81 m), {args.strike} strike, muscles, metabolic, {args.speed} m/s, "
          f"the first mesh's stride {'the search at spend ' + str(args.spend) if args.start == 'search' else 'the default path'}"
          f"{'' if args.consistency_rows == 'exact' else ', without the consistency rows'}"
          f"{f', grading {args.grading:g}' if args.grading else ''}"
          f"{f' (the first mesh {args.first_grading:g})' if args.first_grading is not None else ''}"
          f"{f', force-rate power {args.power}' if args.power != 2 else ''}"
          f"{f', force-rate weight {args.weight:g}' if args.weight is not None else ''}"
          f"{f', {args.transcription}' if args.transcription != 'trapezoid' else ''}",
          flush=True)
    strides = []
    first_grading = args.grading if args.first_grading is None else args.first_grading
    for nodes, own, held, scheme in args.nodes:
        grading = own if own is not None else first_grading if not strides else args.grading
        nlp = mesh(body, args, nodes, args.consistency_rows, grading, held, scheme=scheme)
        if strides and args.activation_smoothing and nodes == args.nodes[-1][0]:
            strides.append(smoothings(body, args, nodes, grading, held, strides[-1], scheme))
            continue
        if strides:
            strides.append(finer(nlp, args.speed, strides[-1], args.mu_init, args.ipopt, not args.direct))
            continue
        first = start(mesh(body, args, nodes, "exact", grading, held, scheme=scheme) if args.rows_first else nlp, args)
        strides.append(finer(nlp, args.speed, first, args.mu_init, args.ipopt, not args.direct)
                       if args.rows_first else first)
    if len(strides) > 2 and len({nlp.settings.transcription for *_, nlp in strides}) == 1:  # one scheme's order
        print("mesh convergence:")
        for name, values in (("objective", [s.objective_value for s, *_ in strides]),
                             ("cadence", [s.cadence_spm for s, *_ in strides])):
            print(convergence(name, values, [n for n, *_ in args.nodes]))
    for stride, _, nlp in strides if args.replay_cost else []:
        print(replayed_force_rate(nlp, stride), flush=True)
    if args.goals:
        print(goals(strides, args.speed), flush=True)
    if args.angles:
        measured = measured_cycle(RBDS, args.speed)
        segments = measured_segments(args.speed) if args.speed in TRIALS else None
        table(label(strides[-1][2].settings), strides[-1][0], measured, segments)
        print(push_off(strides[-1][0], measured), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
