"""Speed of `formopt compare` on a 30 s trial (RBDS001 T35: 4500 frames, 85 touchdowns) with an
optimum for every step, without the stride section (`--stride` below), as a whole process
(start-up, reading, checks, kinematics, the mean step's multi-start optimum, 85 per-step
optima, figure, CSV, JSON, OpenSim files).

    python benchmarks/compare_speed.py [--repeats 5]

Prints the median wall time of the whole process (target <= 3 s), and the time of its parts in
one process; side by side, the per-step optima done the way the NLP was built before the
reference became one of its parameters: one PostureProblem (symbolic build and solver) per
step. No peer tool computes this (OpenSim and Visual3D give the angles, not an optimum).

    python benchmarks/compare_speed.py --stride T25 [--workers 1] [--json FILE] [--compiled true] [--solves]
                                       [--nodes 24 --transcription hermite-simpson] [--model quick]
    python benchmarks/compare_speed.py --diff BEFORE.json AFTER.json

`--stride`: compare's stride section (studies.compare_stride.answer) for one runner of
problems/compare/runners.toml (a part of its trial's name: T35, T25, 20160226): its wall and
CPU time (this process and its pool's, resource.getrusage), and per stage of this process (the
caller of each IPOPT run: the free optimum, the cadence curve's attempts, the family, the band's
variants, the other strikes) and per NLP (strike, objective, a sliding touchdown, the body: 0
the runner's, others the band's) the solves, iterations, CPU and ms an iteration, interpreted or
compiled, and the CPU of the NLPs' and solvers' builds and of the forward checks; per process
(this one and its pool's workers: `Timeline`), its busy wall and CPU s while the nominal curve,
its family and the band are told, its CPU in IPOPT, builds and checks, and the section's wall
alone on 2 idle cores estimated from each process's CPU between this process's waits for its
pool (`two_cores`: on the shared machine the wall measures the other runs as much as this one);
`--workers 1` puts every stage in this process; `--compiled true` compiles every NLP's node
models (collocation.COMPILED; once, then from the disk cache: the section with every NLP
compiled); `--nodes`, `--transcription`: the strides' mesh (compare_stride.answer's; default
the model's); `--model`: the section's stride model (studies.stride_form.STRIDE_MODELS, compare's
`stride_model`: scenes, formopt stride's and the default since 2026-11-28, or quick); `--solves`: every IPOPT
run of every process (stage, NLP, solver: `stride_warm` the
warm start with multipliers, cadence, iterations, status, objective, CPU s, pid, its wall from
the section's start to its end). `--diff`: the
stride sections of two comparison.json files (or --json files), number by number: each
relative difference over 1e-9 and the largest, and any other value that differs (the
section's `seconds` left out).
"""

from __future__ import annotations

import argparse
import collections
import inspect
import itertools
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data" / "rbds"
ARGS = ["compare", "--trial", str(DATA / "RBDS001runT35.c3d"), "--static", str(DATA / "RBDS001static.c3d"),
        "--mass", "62", "--height", "1.81", "--no-stride"]  # the stride section: --stride


def parse() -> argparse.Namespace:
    from formopt.studies.stride_form import STRIDE_MODEL, STRIDE_MODELS

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--stride", help="compare's stride section of this runner (runners.toml)")
    parser.add_argument("--workers", type=int, default=None, help="--stride's processes (default: answer's)")
    parser.add_argument("--json", help="--stride: write the section's JSON here")
    parser.add_argument("--compiled", choices=("auto", "true", "false"), default="auto",
                        help="--stride: the stride NLPs' node models in C (collocation.COMPILED)")
    parser.add_argument("--solves", action="store_true", help="--stride: print every IPOPT run of this process")
    parser.add_argument("--nodes", type=int, default=None, help="--stride: the strides' intervals")
    parser.add_argument("--transcription", default=None, choices=("trapezoid", "hermite-simpson"),
                        help="--stride: the strides' transcription")
    parser.add_argument("--model", choices=tuple(STRIDE_MODELS), default=STRIDE_MODEL,
                        help="--stride: the section's stride model (stride_form.STRIDE_MODELS)")
    parser.add_argument("--diff", nargs=2, metavar=("BEFORE", "AFTER"))
    return parser.parse_args()


def main():
    args = parse()
    if args.diff:
        return diff(*args.diff)
    if args.stride:
        from formopt.optim.stride import collocation
        collocation.COMPILED = {"auto": "auto", "true": True, "false": False}[args.compiled]
        section = {k: v for k, v in (("nodes", args.nodes), ("transcription", args.transcription)) if v is not None}
        return stride_stages(args.stride, args.workers, args.json, args.solves, {**section, "model": args.model})
    exe = str(Path(sys.executable).with_name("formopt"))
    walls = []
    for _ in range(args.repeats):
        with tempfile.TemporaryDirectory() as out:
            t = time.perf_counter()
            subprocess.run([exe, *ARGS, "--out", out], check=True, capture_output=True)
            walls.append(time.perf_counter() - t)
    print(f"formopt compare, whole process, 30 s trial with per-step optima: median "
          f"{statistics.median(walls):.2f} s over {args.repeats} runs (target <= 3 s)")

    from formopt.io import mocap
    from formopt.measure import measure
    from formopt.mechanics.model import build_model
    from formopt.optim.posture import PostureProblem, Problem
    from formopt.studies.compare import compare, modelled_state

    t = time.perf_counter()
    trial, static = mocap.read(DATA / "RBDS001runT35.c3d"), mocap.read(DATA / "RBDS001static.c3d")
    measure(trial, static, 1.81)
    measured = time.perf_counter() - t
    t = time.perf_counter()
    c = compare(trial, static, 62.0, 1.81, friction=0.8, per_step=False)
    mean_only = time.perf_counter() - t
    t = time.perf_counter()
    c = compare(trial, static, 62.0, 1.81, friction=0.8)
    with_steps = time.perf_counter() - t
    sides = [o for o in c.sides.values() if o.per_step]  # each side's optima, its own NLP (compare.side_optimum)
    n = sum(len(o.per_step) for o in sides)
    print(f"  reading and measuring (checks, axes, kinematics, touchdowns): {measured:.2f} s")
    print(f"  compare, each side's mean step's optimum only: {mean_only:.2f} s; with {n} per-step optima: "
          f"{with_steps:.2f} s ({(with_steps - mean_only) / n * 1e3:.1f} ms per step, one NLP a side, "
          f"the step in its parameters)")
    model = build_model(c.body, "leg")
    t = time.perf_counter()
    for o in sides:
        p = o.problem
        for k in o.per_step:
            one = Problem(p.variables, p.lower, p.upper, p.objective, starts=1, gait=p.gait)
            PostureProblem(model, o.point, modelled_state(c.steps.touchdowns[k], o.point), one, 0.0, 0.8).solve()
    rebuilt = time.perf_counter() - t
    print(f"  side by side: one PostureProblem per step (build + solve): {rebuilt:.2f} s "
          f"({rebuilt / n * 1e3:.1f} ms per step)")


SCENE = Path(__file__).resolve().parents[1] / "problems" / "compare" / "runners.toml"
# a solve's stage: the first of these among its callers (studies.compare_stride, compare_band,
# stride_map, optim.stride.local)
STAGES = ("_free_or_none", "sticking_free", "family", "stride_at", "_better_free", "optimum", "solved_from", "attempt")


def comparison(runner: str):
    """compare (no per-step optima) of the runners.toml trial whose file name holds `runner`,
    with the scene's settings as `formopt compare --scene` reads them."""
    from formopt.cli.compare import SETTINGS, read_scene
    from formopt.io import mocap
    from formopt.measure import Options
    from formopt.studies.compare import compare

    shared, trials = read_scene(SCENE)
    s = {**{k: d for k, (d, _) in SETTINGS.items()}, **shared,
         **next(t for t in trials if runner in Path(t["trial"]).name)}
    options = Options(s["markers"], s["cutoff"], s["force_threshold"], s["foot_speed_fraction"])
    return compare(mocap.read(s["trial"], s["forces"]), mocap.read(s["static"]), s["mass"], s["height"],
                   s["sex"], friction=s["friction"], starts=s["starts"], seed=s["seed"], law=s["contact"],
                   bounds_deg=s["bounds"], support=s["support"], options=options, per_step=False)


def cpu_s() -> float:
    """CPU s of this process and its ended children (user + system)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def stride_stages(runner: str, workers: int | None, out: str | None, each: bool = False,
                  section: dict | None = None) -> None:
    """The stride section's time for one runner, and per stage of this process (module doc);
    `section`: compare_stride.answer's nodes, transcription and model where given."""
    from formopt.optim.stride import collocation
    from formopt.studies import compare_band, compare_stride

    c = comparison(runner)
    runs: dict = collections.defaultdict(lambda: [0, 0, 0.0])  # (stage, compiled): solves, iterations, CPU
    nlps: dict = collections.defaultdict(lambda: [0, 0, 0.0])  # (NLP, compiled): the same
    other: dict = collections.defaultdict(float)  # CPU s outside IPOPT: builds, forward checks
    bodies: list = []  # the bodies met, in order (the NLP's label's body number)
    solve = collocation.StrideNLP._run

    def timed(nlp, solver, *args):
        stage = next((f.function for f in inspect.stack()[1:16] if f.function in STAGES), "other")
        start, begun = time.process_time(), time.perf_counter()
        got = solve(nlp, solver, *args)
        spent = time.process_time() - start
        timeline.add(begun, start, "solve", stage)
        ended = time.perf_counter() - timeline.start
        for row in (runs[(stage, nlp._solver_compiled)], nlps[(label(nlp), nlp._solver_compiled)]):
            row[0], row[1], row[2] = row[0] + 1, row[1] + got.iterations, row[2] + spent
        if each:
            print(solve_line(stage, label(nlp), solver.name(), got, spent)
                  + f" | {os.getpid()} | {begun - timeline.start:.2f}-{ended:.2f}", flush=True)
        return got

    def label(nlp) -> str:
        s = nlp.settings
        if nlp.js.body not in bodies:
            bodies.append(nlp.js.body)
        return f"{s.strike} {s.objective}{' slide' if s.touchdown == 'slide' else ''} body {bodies.index(nlp.js.body)}"

    def cpu_of(name: str, fn):
        def counted(*args, **kwargs):
            start, begun = time.process_time(), time.perf_counter()
            try:
                return fn(*args, **kwargs)
            finally:
                other[name] += time.process_time() - start
                timeline.add(begun, start, "other", name)
        return counted

    collocation.StrideNLP._run = timed
    collocation.StrideNLP.__init__ = cpu_of("NLP builds (graphs)", collocation.StrideNLP.__init__)
    collocation.StrideNLP.solver = property(cpu_of("solver builds (derivatives, compiles)",
                                                   collocation.StrideNLP.solver.fget))
    compare_band.forward_checked = cpu_of("forward checks", compare_band.forward_checked)
    timeline = Timeline()
    wall, cpu, told = time.perf_counter(), cpu_s(), []
    stages = {"progress": lambda text: told.append((time.perf_counter() - wall, text)), **(section or {})}
    answer = compare_stride.answer
    section = answer(c, workers=workers, **stages) if workers else answer(c, **stages)
    wall, cpu = time.perf_counter() - wall, cpu_s() - cpu
    print_stages(runner, told, wall, cpu, runs, nlps, other)
    timeline.report(wall, [(t, text) for t, text in told])
    if out:
        Path(out).write_text(json.dumps(section.to_dict(), default=str))


def print_stages(runner: str, told: list, wall: float, cpu: float, runs: dict, nlps: dict, other: dict) -> None:
    """stride_stages' tables: the stages told, the section's wall and CPU (s), this process's
    solves, iterations and CPU per stage and per NLP, and its CPU outside IPOPT."""
    print("timeline (s, the stage told): " + "; ".join(f"{t:.1f} {text}" for t, text in told))
    print(f"compare's stride section, {runner}: {wall:.1f} s wall, {cpu:.1f} s CPU (this process and its "
          f"pool's), load {os.getloadavg()[0]:.1f} at the end")
    for what, rows in (("stage", runs), ("NLP", nlps)):
        print(f"{what} (this process) | compiled | solves | iterations | CPU s | ms/iteration")
        for (key, compiled), (n, its, s) in sorted(rows.items(), key=lambda kv: -kv[1][2]):
            print(f"{key} | {compiled} | {n} | {its} | {s:.2f} | {s / max(its, 1) * 1e3:.1f}")
    print("outside IPOPT (this process): " + "; ".join(f"{k} {v:.2f} s CPU" for k, v in other.items()))


class Timeline:
    """When each process of the section is busy: this process and its pools' workers (forked:
    they inherit the patches and the file) append one line an interval: pid, start and end
    (s, time.perf_counter's clock: system-wide on Linux), the process's CPU s at both
    (time.process_time), kind and what. Kinds: a pool task (`task`), this process waiting for
    its pool's results (`wait`), an IPOPT run (`solve`), a build or a forward check (`other`)."""

    def __init__(self):
        global TIMELINE
        fd, self.path = tempfile.mkstemp(prefix="timeline")
        os.close(fd)
        self.fd, self.pid = os.open(self.path, os.O_WRONLY | os.O_APPEND), os.getpid()
        self.start, self.cpu = time.perf_counter(), time.process_time()
        TIMELINE = self
        from formopt.studies import pool
        started, results = pool.Background.start, pool.Background.results

        def start(bg, tasks, **later):
            return started(bg, [(_task, (fn, args), name) for fn, args, name in tasks], **later)

        def waited(bg, handles, say):
            begun, cpu = time.perf_counter(), time.process_time()
            try:
                return results(bg, handles, say)
            finally:
                self.add(begun, cpu, "wait", "results")
        pool.Background.start, pool.Background.results = start, waited

    def add(self, begun: float, cpu: float, kind: str, what: str) -> None:
        """An interval of this process from `begun` (perf_counter) and `cpu` (process_time) to now."""
        os.write(self.fd, f"{os.getpid()}|{begun - self.start:.3f}|{time.perf_counter() - self.start:.3f}|"
                          f"{cpu:.3f}|{time.process_time():.3f}|{kind}|{what}\n".encode())

    def report(self, end: float, told: list) -> None:
        """Per process, its busy wall s and CPU s in each window of the section (the nominal curve,
        its family, the band: from the stages told), this process busy but where it waits for
        its pool, a worker in its tasks; and the wall the section would take alone on 2 cores
        (`two_cores`)."""
        os.close(self.fd)
        rows = [line.split("|") for line in Path(self.path).read_text().splitlines()]
        os.unlink(self.path)
        marks = [0.0] + [next((t for t, text in told if key in text), end) for key in ("family", "variants")] + [end]
        spans = self._spans(rows, end)
        print(f"busy wall s, CPU s per process (nominal {marks[0]:.1f}-{marks[1]:.1f} | family -{marks[2]:.1f} | "
              f"band -{marks[3]:.1f} | all; this process first)")
        for pid, own in spans.items():
            cut = [_within(own, lo, hi) for lo, hi in itertools.pairwise(marks)]
            parts: dict = collections.defaultdict(float)  # CPU s in its solves, builds and checks
            for p, _, _, c0, c1, kind, what in rows:
                if p == pid and kind in ("solve", "other"):
                    parts["IPOPT" if kind == "solve" else what] += float(c1) - float(c0)
            print(f"  {pid}: " + " | ".join(f"{w:.1f}, {c:.1f}" for w, c in cut)
                  + f" | {sum(w for w, _ in cut):.1f}, {sum(c for _, c in cut):.1f}; CPU s: "
                  + "; ".join(f"{k} {v:.1f}" for k, v in parts.items()))
        waits = sorted({float(x) for r in rows if r[0] == str(self.pid) and r[5] == "wait" for x in r[1:3]})
        print(f"alone on 2 cores (each process's CPU in each interval between this process's waits, "
              f"the interval max(its largest, its sum / 2)): {two_cores(spans, [0.0, *waits, end]):.1f} s")

    def _spans(self, rows: list, end: float) -> dict:
        """{pid: [(start, end, CPU s)]}: this process's busy intervals (between its waits, and
        its tasks: with one worker a pool's tasks run here), each worker's tasks."""
        out: dict = {str(self.pid): []}
        for p, a, b, c0, c1, kind, _ in rows:
            if kind == "task":
                out.setdefault(p, []).append((float(a), float(b), float(c1) - float(c0)))
        mine = sorted((float(a), float(b), float(c0), float(c1)) for p, a, b, c0, c1, kind, _ in rows
                      if p == str(self.pid) and kind == "wait")
        t, c = 0.0, self.cpu
        for a, b, c0, c1 in [*mine, (end, end, time.process_time(), 0.0)]:
            if a > t:
                out[str(self.pid)].append((t, a, c0 - c))
            t, c = max(t, b), c1
        return out


TIMELINE: Timeline | None = None  # the section's timeline (its pool tasks write to it)


def _task(task: tuple):
    """A pool task (fn, args) run and its busy interval added to TIMELINE."""
    fn, args = task
    begun, cpu = time.perf_counter(), time.process_time()
    try:
        return fn(args)
    finally:
        TIMELINE.add(begun, cpu, "task", fn.__name__)


def _within(spans: list, lo: float, hi: float) -> tuple[float, float]:
    """(wall s, CPU s) of (start, end, CPU) intervals within [lo, hi], an interval's CPU shared
    in proportion to its wall."""
    wall = cpu = 0.0
    for a, b, c in spans:
        part = max(0.0, min(b, hi) - max(a, lo))
        wall, cpu = wall + part, cpu + (c * part / (b - a) if b > a else 0.0)
    return wall, cpu


def two_cores(spans: dict, marks: list) -> float:
    """The section's wall alone on 2 idle cores, estimated: between each two `marks` (this
    process's waits for its pool begin and end), each process's CPU there (`_within`), the
    interval's wall the larger of the most of one process and half their sum."""
    total = 0.0
    for lo, hi in itertools.pairwise(marks):
        cpus = [_within(own, lo, hi)[1] for own in spans.values()]
        total += max(max(cpus), sum(cpus) / 2)
    return total


def solve_line(stage: str, nlp: str, solver: str, got, spent: float) -> str:
    """One IPOPT run for `--solves`: stage, NLP, solver, cadence, iterations, status, objective, CPU s."""
    cadence = got.parameters["cadence"]
    return (f"solve | {stage} | {nlp} | {solver} | {'free' if cadence is None else f'{cadence:.2f}'} | "
            f"{got.iterations} | {got.status} | {got.objective:.9g} | {spent:.2f}")


def diff(before: str, after: str) -> None:
    """The two stride sections' numbers compared (module doc)."""
    def flat(x, at=""):
        if isinstance(x, dict):
            return {k: v for key, item in x.items() for k, v in flat(item, f"{at}.{key}").items()}
        if isinstance(x, list):
            return {k: v for i, item in enumerate(x) for k, v in flat(item, f"{at}[{i}]").items()}
        return {at: x}

    def numbers(file: str) -> dict:
        data = json.loads(Path(file).read_text())  # a comparison.json, or --json's section alone
        return {k: v for k, v in flat(data.get("stride", data)).items() if k not in (".seconds", ".figure")}

    a, b = numbers(before), numbers(after)
    worst = (0.0, "")
    for key in sorted(a.keys() | b.keys()):
        x, y = a.get(key), b.get(key)
        if isinstance(x, float) and isinstance(y, float):
            rel = abs(x - y) / max(abs(x), abs(y), 1e-300)
            worst = max(worst, (rel, key))
            if rel > 1e-9:
                print(f"{key}: {x!r} -> {y!r} ({rel:.1e})")
        elif x != y:
            print(f"{key}: {x!r} -> {y!r}")
    print(f"{len(a)} values; the largest relative difference {worst[0]:.1e}" + (f" ({worst[1]})" if worst[0] else ""))


if __name__ == "__main__":
    main()
