"""Maps of stride optima: the half stride of a `[stride]` scene across a parameter grid.

`formopt sweep stride --param speed_mps=2.5:4.5:41 --param cadence_spm=140:210:21` solves the
scene's half stride (optim.stride) at every grid point. Parameters (PARAMETERS): the speed, the
cadence (imposed: the half-period fixed to 60 / cadence), the step length (imposed: at speed v
the step length L fixes the cadence, 60 v / L steps/min, since a step is a half stride,
L = v T with T the half-period and the cadence 60 / T), the slope and the friction. Speed,
slope, friction and cadence are parameters of the built NLP, so one build serves the grid.

The grid is walked as a serpentine and cut into chains (studies.sweep runs them, as it runs
optimum maps): in a chain each point starts from the solved point before it; the chain's first
point, and any point whose warm start fails, is the better of a solve from the free optimum at
its speed, slope and friction (itself solved from the generic guess with the scene's `starts`)
and one from the generic guess. A point that
fails says so (`status`, `success`) and seeds nothing: the next starts as a chain's first.

`cadence_curve(scene, speed, cadences)` is the one home of "the stride at these cadences": at
each, the least costly optimum reached from the free optimum and from the neighbouring
cadences (the literature scripts and compare's what-if call it). Warm starts from a solution of
the same NLP carry its multipliers (StrideNLP.resolve).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import asdict, dataclass, field, fields, replace

import numpy as np

from ..io.stride_scene import StrideScene
from ..mechanics.errors import InputError
from ..optim.stride import Stride, StrideNLP, costs, ranges, rank, summarise
from ..optim.stride.guess import ballistic, fitted
from ..optim.stride.layout import Solved
from ..optim.stride.local import optimum
from .pool import Background

PARAMETERS = {"speed_mps": "running speed, m/s", "cadence_spm": "imposed cadence, steps/min",
              "step_length_m": "imposed step length (a half stride), m",
              "slope_deg": "ground slope, deg uphill", "friction": "coefficient"}
# the ranges of the stride's own keys (optim.stride.ranges, the scene's)
RANGES = {k: ranges.RANGES[k] for k in PARAMETERS}
# speed, cadence and step length are one relation (cadence = 60 v / L): a grid gives two at most
CADENCE_GROUP = ("speed_mps", "cadence_spm", "step_length_m")
# the objectives a map row reports (StrideRow's *_value) from the effort and the budget's work
MAPPED = ("effort", "work", "metabolic")
# Points per warm-started chain. A chain's first stride costs about 15-20 warm ones (the free
# optimum's starts from the generic guess, then the imposed solve: 40 nodes, 2026-11-23, about
# 10 CPU s against 0.6), so chains are long: on a pool the fair share (studies.sweep) cuts them
# shorter (861 strides on 2 workers: 8 chains of 108).
CHUNK = 120


@dataclass(frozen=True)
class StrideRow:
    """One point of a stride map (SI; names as in the stride's JSON). None: not computed
    (`error` says why). The objectives' values are per distance and scaled as the NLP's
    (`objective_values`); `objective_value` is the scene's objective as IPOPT saw it (with its
    smoothing and regularisation terms)."""

    speed_mps: float
    slope_deg: float
    friction: float
    cadence_spm: float | None = None  # imposed, or the optimum's when free
    step_length_m: float | None = None
    strike: str | None = None
    objective_value: float | None = None
    effort_value: float | None = None
    work_value: float | None = None
    metabolic_value: float | None = None
    mechanical_power_W: float | None = None  # W+ / T
    cost_of_transport: float | None = None  # W+ / (m g d)
    impact_loss_W: float | None = None  # sum of the impacts' T_c / T
    impacts_J: float | None = None
    positive_work_J: float | None = None
    negative_work_J: float | None = None
    stance_s: float | None = None
    duty_factor: float | None = None
    peak_vertical_grf_bw: float | None = None
    trunk_deg: float | None = None  # touchdown angles
    hip_deg: float | None = None
    knee_deg: float | None = None
    ankle_deg: float | None = None
    hip_from_strike_ahead_m: float | None = None  # the hip ahead of the striking point
    hip_from_strike_above_m: float | None = None
    valid: bool | None = None  # success and every impact valid under the scene's law
    success: bool | None = None
    status: str | None = None  # IPOPT's return status
    iterations: int | None = None
    solve_s: float | None = None
    start: str | None = None  # neighbour (warm), free (from the free optimum) or cold
    error: str = ""

    def to_dict(self) -> dict:
        """{column: CSV value} ("" where None)."""
        return {k: "" if v is None else v for k, v in asdict(self).items()}


COLUMNS = [f.name for f in fields(StrideRow)]


def check(scene, params) -> None:
    """Refuse a grid a stride map cannot take, before any solve, in one line naming the
    parameter: a stride scene's `best` strike (a map solves one strike), speed, cadence and
    step length all swept (one follows from the other two), or a point whose given or derived
    speed, cadence or step length is outside its range (`point`)."""
    if scene.strike == "best":
        raise InputError("stride.strike = 'best': a stride map solves one strike; set heel, "
                         "forefoot or flat in the scene")
    group = [n for n, _ in params if n in CADENCE_GROUP]
    if len(group) > 2:
        raise InputError(f"--param {group[2]}: speed, cadence and step length are one relation "
                         "(cadence = 60 speed / step length): sweep two of them at most")
    names = [n for n, _ in params]
    for values in itertools.product(*[np.asarray(v, float) for _, v in params]):
        point(scene, dict(zip(names, values)))


def point(scene: StrideScene, values: dict) -> tuple[float, float, float, float | None]:
    """(speed m/s, slope rad, friction, imposed cadence steps/min or None) of a grid point,
    each given or derived value checked (optim.stride.ranges.point; InputError)."""
    speed = values.get("speed_mps", scene.speed)
    step = values.get("step_length_m")
    cadence = values.get("cadence_spm", scene.cadence if step is None else None)
    if step is not None and "cadence_spm" in values and "speed_mps" not in values:
        speed = cadence * step / 60.0
        if speed not in RANGES["speed_mps"]:
            raise InputError(f"cadence_spm = {cadence:g} and step_length_m = {step:g}: give a speed of "
                             f"{speed:.4g} m/s, outside {RANGES['speed_mps'].text()}")
        step = None
    speed, cadence = ranges.point(speed, None if step is not None else cadence, step)
    slope = values.get("slope_deg", math.degrees(scene.slope))
    friction = values.get("friction", scene.friction)
    ranges.check("slope_deg", slope)
    ranges.check("friction", friction)
    return speed, math.radians(slope), friction, cadence


def solution(stride: Stride, nlp: StrideNLP) -> dict:
    """The decision variables (blocks by name) of a stride solved here (summarise keeps them),
    fitted to `nlp`'s nodes (a Coulomb stride that slid has one phase more)."""
    if stride.solved is None:
        raise RuntimeError("a stride without its solution (Stride.solved) cannot seed a solve")
    return fitted(nlp, stride.solved.blocks)


def objective_values(nlp: StrideNLP, stride: Stride) -> dict[str, float]:
    """The three work and effort objectives (`MAPPED`) of a solved stride, each per distance and
    scaled as the NLP scales it (optim.stride.costs.own_terms), without the smoothing and
    regularisation terms. The integrals by the transcription's trapezoidal rule on the
    stride's own nodes (a phase boundary's repeated time adds nothing), so a stride that slid
    is counted with its slide."""
    b = stride.budget
    integrals = {"effort": float(np.trapezoid(np.sum(np.square(stride.tau), axis=1), stride.t)),
                 "positive": b["positive_work_J"], "negative": b["negative_work_J"]}
    return {f"{o}_value": costs.objective(costs.own_terms(o, nlp.mass), integrals, stride.step_length_m)
            for o in MAPPED}


def row_of(nlp: StrideNLP, stride: Stride, start: str) -> StrideRow:
    """The map's row of a solved stride (`start`: how its solve was started)."""
    td, b = stride.touchdown, stride.budget
    angles, hip = td["angles_deg"], td["hip_from_strike_m"]
    T, objective = stride.half_period_s, objective_values(nlp, stride)
    return StrideRow(
        speed_mps=stride.speed_mps, slope_deg=math.degrees(stride.slope), friction=stride.friction,
        cadence_spm=stride.cadence_spm, step_length_m=stride.step_length_m, strike=stride.strike,
        objective_value=stride.objective_value, effort_value=objective["effort_value"],
        work_value=objective["work_value"], metabolic_value=objective["metabolic_value"],
        mechanical_power_W=stride.mechanical_power_W, cost_of_transport=stride.cost_of_transport,
        impact_loss_W=b["impacts_J"] / T, impacts_J=b["impacts_J"],
        positive_work_J=b["positive_work_J"], negative_work_J=b["negative_work_J"],
        stance_s=stride.stance_s, duty_factor=stride.duty_factor,
        peak_vertical_grf_bw=stride.peak_vertical_grf_bw,
        trunk_deg=angles["trunk"], hip_deg=angles["hip"], knee_deg=angles["knee"],
        ankle_deg=angles["ankle"], hip_from_strike_ahead_m=hip["ahead"],
        hip_from_strike_above_m=hip["above"],
        valid=stride.valid, success=stride.success,
        status=stride.status, iterations=stride.iterations, solve_s=stride.solve_s, start=start)


def free(scene: StrideScene, speed: float, slope: float, mu: float) -> Stride:
    """The free optimum (cadence not imposed) at these parameters: the generic guess and
    scene.starts - 1 perturbations of it, the best kept (optim.stride.optimum)."""
    return optimum(scene.nlp(), speed, slope, mu, None, simulate=False, starts=scene.starts)


def warm(nlp: StrideNLP, previous: Stride, speed, slope, mu, cadence) -> Solved:
    """A solve warm-started from a solved neighbour: with its multipliers when it is a
    solution of this NLP or of another body's with the same settings (StrideNLP.layout,
    .resolve), else from its variables fitted to the nodes."""
    if previous.solved is not None and previous.solved.layout == nlp.layout:
        return nlp.resolve(previous.solved, speed, slope, mu, cadence)
    return nlp.solve(solution(previous, nlp), speed, slope, mu, cadence)


def solve_point(scene: StrideScene, values: dict, previous: Stride | None) -> tuple[Stride, str]:
    """One grid point: warm from `previous` (a solved neighbour) when given; else, or when that
    fails, the better of two solves, from the free optimum at the point's speed, slope and
    friction and from the generic guess (the free optimum itself when no cadence is imposed):
    from the free optimum alone, a chain's first stride at 4 m/s and 203 steps/min fell into a
    local optimum 19 % costlier than the generic guess's (0.971 against 0.815, 40 nodes,
    2026-11-23), and its chain followed it. (the stride, how it was started)."""
    nlp = scene.nlp()
    speed, slope, mu, cadence = point(scene, values)
    tries = []
    if previous is not None:
        stride = summarise(nlp, warm(nlp, previous, speed, slope, mu, cadence), False)
        if stride.valid:
            return stride, "neighbour"
        tries.append((stride, "neighbour"))
    seed = free(scene, speed, slope, mu)
    if cadence is None:
        return min([*tries, (seed, "free" if seed.success else "cold")], key=lambda t: rank(t[0]))
    tries.append((summarise(nlp, nlp.solve(ballistic(nlp, speed), speed, slope, mu, cadence), False), "cold"))
    if seed.success:
        tries.insert(0, (summarise(nlp, nlp.solve(solution(seed, nlp), speed, slope, mu, cadence), False), "free"))
    return min(tries, key=lambda t: rank(t[0]))


def rows(scene: StrideScene, chunk, tick=None) -> list[dict]:
    """The rows ({column: CSV value}, StrideRow) of a chain of neighbouring points; a point
    that fails seeds nothing. `tick()`, when given, after each point (a progress bar's step:
    studies.sweep.Kind.ticks)."""
    out, previous = [], None
    for values in chunk:
        try:
            stride, start = solve_point(scene, values, previous)
            row, previous = row_of(scene.nlp(), stride, start), stride if stride.success else None
        except (InputError, RuntimeError) as err:
            speed, slope, mu, cadence = point(scene, values)
            row, previous = StrideRow(speed, math.degrees(slope), mu, cadence,
                                      error=str(err).replace("\n", " ")), None
        out.append(row.to_dict())
        if tick:
            tick()
    return out


@dataclass
class CadenceCurve:
    """The stride at imposed cadences around the free optimum of one speed: at each cadence the
    least costly of the optima reached from several starts (`cadence_curve`)."""

    free: Stride  # the free optimum (cadence not imposed)
    strides: list[Stride] = field(default_factory=list)  # one per cadence, in the order asked
    starts: list[str] = field(default_factory=list)  # how each was started (rows' `start`)
    # per cadence, the objective values of every converged solve (the kept one among them)
    tried: list[list[float]] = field(default_factory=list)
    free_from: str = "free"  # "free", or the imposed cadence whose stride seeded a better free optimum

    def rows(self, nlp: StrideNLP) -> list[StrideRow]:
        """The map rows of the free optimum (first) and of each cadence."""
        return [row_of(nlp, self.free, "free")] + [row_of(nlp, s, k) for s, k in zip(self.strides, self.starts)]

    def spread(self) -> list[float]:
        """Per cadence, how much costlier (fraction) the worst converged local optimum was than
        the one kept (0 when every start reached the same optimum)."""
        return [max(t) / min(t) - 1.0 if t else 0.0 for t in self.tried]


SAME = 1e-6  # relative: two objective values this close are one optimum (IPOPT's tolerance)
PASSES = 4  # sweeps of the polish, alternating direction, at most


def cadence_curve(scene: StrideScene, speed: float, cadences, slope: float | None = None,
                  friction: float | None = None, start: Stride | None = None,
                  beside: Background | None = None) -> CadenceCurve:
    """The scene's stride at `speed` (m/s) with each cadence of `cadences` (steps/min)
    imposed: the least costly optimum found from several starts, since the stride's
    landscape has several local optima at an imposed cadence.

    1. The free optimum (scene.starts starts, or `start`: a free optimum of this scene at
       these parameters found before); every cadence solved from it.
    2. Sweeps along the cadences (the free optimum's among them, neither re-solved nor a
       source: step 1 solved from it), alternately falling and rising: each cadence re-solved
       warm from its neighbour (past the free optimum's) when that neighbour changed since, the
       better kept, until a sweep changes nothing (at most PASSES): a better family of strides
       found at one cadence spreads to its neighbours.
    3. The free optimum solved again from the least costly imposed stride, kept if better.

    `slope` (rad), `friction`: the scene's when None; `beside`: a pool for step 1's solves,
    independent of each other (`first_sweep`). Strides in the order of `cadences`."""
    slope = scene.slope if slope is None else slope
    mu = scene.friction if friction is None else friction
    values = [float(c) for c in cadences]
    for c in values:
        ranges.point(speed, c)
    base = free(scene, speed, slope, mu) if start is None else start
    if not base.success:
        raise RuntimeError(f"no free stride optimum at {speed:g} m/s ({base.status})")
    nlp = scene.nlp()
    kept: dict[float, tuple[Stride, str]] = {}
    tried: dict[float, list[float]] = {c: [] for c in values}

    def attempt(c: float, source: Stride, how: str) -> bool:
        """Solve cadence c warm from `source`; keep it if it is better; True if kept."""
        return keep(c, summarise(nlp, warm(nlp, source, speed, slope, mu, c), False), how)

    def keep(c: float, stride: Stride, how: str) -> bool:
        """Keep cadence c's `stride` if it is better than the one kept; True if kept."""
        if stride.success:
            tried[c].append(stride.objective_value)
        old = kept.get(c)
        if old is None or better(stride, old[0]):
            kept[c] = (stride, how)
            return True
        return False

    for c, stride in zip(values, first_sweep(scene, base, speed, slope, mu, values, beside)):
        keep(c, stride, "free")
    _polish(sorted(set(values) | {base.cadence_spm}), base.cadence_spm, kept, attempt)
    for c in values:  # no warm start gave a valid stride: the generic guess, as a map's chain would
        if not kept[c][0].valid:
            cold = summarise(nlp, nlp.solve(ballistic(nlp, speed), speed, slope, mu, c), False)
            if cold.success:
                tried[c].append(cold.objective_value)
            if better(cold, kept[c][0]):
                kept[c] = (cold, "cold")
    curve = CadenceCurve(base, [kept[c][0] for c in values], [kept[c][1] for c in values],
                         [tried[c] for c in values])
    return _better_free(curve, nlp, speed, slope, mu)


def first_sweep(scene: StrideScene, base: Stride, speed, slope, mu, cadences: list[float],
                beside: Background | None) -> list[Stride]:
    """Step 1 of `cadence_curve`: each cadence solved warm from the free optimum `base`, in the
    order of `cadences`; on `beside`'s pool where given (studies.pool.Background), each the same
    solve as here, the farthest from `base`'s cadence first (often the longest: RBDS001 T25's
    +10 %, 143 IPOPT iterations of the sweep's 548; not always: RIC's longest, 219 of 534, was
    its nearest; 2026-11-27)."""
    tasks = [(solved_from, (scene, base, speed, slope, mu, c), "") for c in cadences]
    if beside is None:
        return [solved_from(args) for _, args, _ in tasks]
    order = sorted(range(len(tasks)), key=lambda k: -abs(cadences[k] - base.cadence_spm))
    got = dict(zip(order, beside.results(beside.start([tasks[k] for k in order]), lambda text: None)))
    return [got[k] for k in range(len(tasks))]


def solved_from(task: tuple) -> Stride:
    """The scene's stride at `cadence` warm from `source` (`warm`), from (scene, source, speed,
    slope, mu, cadence)."""
    scene, source, speed, slope, mu, cadence = task
    nlp = scene.nlp()
    return summarise(nlp, warm(nlp, source, speed, slope, mu, cadence), False)


def _polish(order: list[float], free_cadence: float, kept: dict, attempt) -> None:
    """Step 2 of `cadence_curve`: sweeps along `order` (cadences, the free optimum's
    `free_cadence` among them), each point re-solved from a neighbour changed since (the first
    sweep each way from every point; a point changed earlier in the same sweep counts, so a
    cheaper stride travels the whole sweep). The free optimum's cadence is not re-solved, nor
    solved from (step 1 solved every cadence from it: the same solve again, 231 of RBDS001 T25's
    2,688 iterations, 2026-11-27); a point next to it is tried from the point beyond it, so a
    cheaper family crosses it."""
    changed = set(order)
    for k in range(PASSES):
        sweep = order[::-1] if k % 2 == 0 else order
        now: set[float] = set()
        for i in range(1, len(sweep)):
            target = sweep[i]
            if target == free_cadence:
                continue
            j = i - 2 if sweep[i - 1] == free_cadence else i - 1  # the neighbour, past the free one
            if j < 0 or (sweep[j] not in changed and sweep[j] not in now):
                continue
            stride = kept[sweep[j]][0]
            if stride.success and attempt(target, stride, "neighbour"):
                now.add(target)
        if not now and k > 0:
            return
        changed = now | (set(order) if k == 0 else set())  # both directions once from every point


def better(stride: Stride, other: Stride) -> bool:
    """`stride` ranks before `other` (optim.stride.rank), by more than SAME when the two differ
    in the objective alone."""
    a, b = rank(stride), rank(other)
    return a[:2] < b[:2] or (a[:2] == b[:2] and a[2] < b[2] - SAME * abs(b[2]))


def _better_free(curve: CadenceCurve, nlp: StrideNLP, speed, slope, mu) -> CadenceCurve:
    """Step 3 of `cadence_curve`: the free optimum solved again (optim.stride.optimum, with
    its touchdown mode under Coulomb) from the least costly imposed stride when that one is
    better than it (`better`: the free optimum was then a local one); kept if better."""
    cheapest = min(curve.strides, key=rank, default=None)
    if cheapest is None or cheapest.solved is None or not better(cheapest, curve.free):
        return curve
    again = optimum(nlp, speed, slope, mu, None, guess=cheapest.solved.blocks, simulate=False)
    if better(again, curve.free):
        return replace(curve, free=again, free_from=f"{cheapest.cadence_spm:.1f}")
    return curve


def for_nodes(scene: StrideScene, nodes: int, starts: int | None = None) -> StrideScene:
    """The scene with another node count (and number of starts): a cheaper map or test."""
    return replace(scene, settings=replace(scene.settings, nodes=nodes),
                   starts=scene.starts if starts is None else starts)
