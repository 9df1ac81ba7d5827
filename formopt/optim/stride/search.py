"""The global search for the stride's optimum (issue 34): a stated, deterministic procedure whose
spend is a parameter, and a record of what it spent and of the local optima it met.

At speed v (slope, friction), with spend s = 1, 2, ... (`global_optimum`):

1. The grid (`grid`): GRID_POINTS * s + 1 cadences evenly spaced over GRID_SPM (nested: spend 2's
   grid holds spend 1's), those whose step length 60 v / cadence is in its range
   (ranges.point), and the imposed cadence when there is one.
2. At each grid cadence (imposed), a solve from the generic start (local.generic_start).
3. Continuation along the family: the grid's cadences rising, then falling, each solved warm
   from its neighbour's stride (StrideNLP.resolve); the better kept (`rank`).
4. With the cadence free: the generic start's free solve (`optimum`'s one start) and the
   RELEASED * s least costly grid strides released to free cadence (each warm from its
   stride), whose cadence and posture then move to the nearest local optimum.
5. The answer: the best of step 4's solves (local.best_of: valid first, converged, the least
   objective; the touchdown's mode under Coulomb, the forward check). With a cadence imposed
   step 4 is skipped and the answer is the best stride met at that cadence.

Every start is fixed (no random draw): the same call gives the same answer. Step 4 includes
`optimum`'s one start, so the answer is never worse than it (by `rank`).

`Stride.search` (`record`, `distinct`) says what the search spent (solves, IPOPT iterations,
seconds; in the seconds only: the generic start's own solve for Hermite-Simpson or muscles, a
warm start's failed run before StrideNLP.resolve's cold one, the touchdown's sliding re-solve
under Coulomb and the optima's forward checks), the
grid's least objective per cadence (with `check_grid` its validity, the forward check included:
`grid_checks`), and the distinct local optima it met (step 4's, or at an
imposed cadence every stride met there): their cadences, objectives, validity (the forward check
included) and spread (how much costlier the costliest is than the least, %; None when none
converged). An optimum less costly than the answer is an invalid one: `rank` puts validity first.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable

import numpy as np

from ...mechanics.errors import InputError
from . import ranges
from .collocation import StrideNLP
from .layout import Solved
from .local import best_of, generic_start
from .result import Stride, rank, summarise

# `[stride] search`: "local", `optimum`'s starts from the generic guess (scene key `starts`), or
# "global", this module's procedure (scene key `spend`)
SEARCHES = ("local", "global")
# Cadences runners choose, 2-6 m/s: 150-200 steps/min (de Ruiter et al. 2020: 165 +- 8 at 3 m/s;
# Cavanagh & Kram 1989), widened on both sides so the grid brackets the model's optima too
# (one start found 118.6 steps/min at 2.5 m/s on RBDS001, 2026-11-25: the releases reach below
# the grid's lowest cadence, the grid only seeds them).
GRID_SPM = (130.0, 230.0)
GRID_POINTS = 4  # grid intervals per unit of spend: 5 cadences at spend 1 (25 steps/min apart)
RELEASED = 2  # the grid's least costly strides released to free cadence, per unit of spend
# two optima whose objectives differ by less than this (relative) and whose cadences by less
# than DISTINCT_SPM are one (IPOPT's tolerance, 1e-6 to 1e-8, leaves them closer than that)
DISTINCT = 1e-4
DISTINCT_SPM = 0.5


def grid(speed: float, spend: int = 1, cadence: float | None = None) -> list[float]:
    """The search's cadences (steps/min, rising) at `speed` (m/s): step 1 of the module doc. A
    speed or imposed cadence out of range is refused (ranges.point), not left an empty grid."""
    if spend < 1:
        raise InputError(f"spend = {spend}: the search's spend is a whole number from 1")
    ranges.point(speed, cadence)
    points = np.linspace(*GRID_SPM, GRID_POINTS * spend + 1)
    out = {round(float(c), 6) for c in points if _runnable(speed, float(c))}
    return sorted(out | ({float(cadence)} if cadence is not None else set()))


def _runnable(speed: float, cadence: float) -> bool:
    """Whether a cadence is admissible at `speed` (its step length in range: ranges.point)."""
    try:
        ranges.point(speed, cadence)
    except InputError:
        return False
    return True


def solves_planned(speed: float, spend: int = 1, cadence: float | None = None) -> int:
    """The solves `global_optimum` runs when every one converges (a progress bar's total): n
    from the generic start, 2 (n - 1) warm, then 1 + RELEASED * spend free ones (none with a
    cadence imposed). Fewer where one fails: no continuation from a failed grid stride, and no
    more releases than converged grid strides."""
    n = len(grid(speed, spend, cadence))
    return 3 * n - 2 + (0 if cadence is not None else 1 + RELEASED * spend)


class _Spend:
    """The search's solves, counted (solves, IPOPT iterations, seconds since it began)."""

    def __init__(self, nlp: StrideNLP, speed, slope, mu, progress: Callable[[str], None] | None):
        self.nlp, self.args, self.say = nlp, (speed, slope, mu), progress or (lambda text: None)
        self.solves, self.iterations, self.start = 0, 0, time.perf_counter()

    def run(self, text: str, cadence: float | None, previous: Solved | None = None) -> tuple[Solved, Stride]:
        """One solve at `cadence` (None: free), warm from `previous` or from the generic start."""
        self.say(text)
        nlp, (speed, slope, mu) = self.nlp, self.args
        solved = (nlp.resolve(previous, speed, slope, mu, cadence) if previous is not None
                  else nlp.solve(generic_start(nlp, speed, slope, mu, cadence), speed, slope, mu, cadence))
        self.solves += 1
        self.iterations += solved.iterations
        return solved, summarise(nlp, solved, simulate=False)


def global_optimum(nlp: StrideNLP, speed: float, slope: float = 0.0, mu: float = 0.8,
                   cadence: float | None = None, spend: int = 1, simulate: bool = True,
                   progress: Callable[[str], None] | None = None, check_grid: bool = False) -> Stride:
    """The stride found by the module's procedure at `spend` (cadence None: free; else imposed,
    steps/min), its `search` the record of what it spent and met; `progress(text)` is told of
    each solve (solves_planned of them); `check_grid`: the grid's strides forward-checked too
    (`grid_checks`; one forward simulation per grid cadence)."""
    cadences = grid(speed, spend, cadence)
    spent = _Spend(nlp, speed, slope, mu, progress)
    met: dict[float, list[tuple[Solved, Stride]]] = {c: [] for c in cadences}
    kept: dict[float, tuple[Solved, Stride]] = {}

    def attempt(c: float, text: str, previous: Solved | None = None) -> None:
        got = spent.run(text, c, previous)
        met[c].append(got)
        if c not in kept or rank(got[1]) < rank(kept[c][1]):
            kept[c] = got

    for c in cadences:
        attempt(c, f"{c:.0f} steps/min from the generic start")
    for order in (cadences, cadences[::-1]):  # the continuation, rising then falling
        for before, c in itertools.pairwise(order):
            if kept[before][1].success:
                attempt(c, f"{c:.0f} steps/min warm from {before:.0f}", kept[before][0])
    if cadence is not None:
        found = [got for got in met[cadence] if got[1].success] or [kept[cadence]]
    else:
        released = sorted((kept[c] for c in cadences if kept[c][1].success), key=lambda got: rank(got[1]))
        found = [spent.run("free cadence from the generic start", None)]
        found += [spent.run(f"free cadence from {got[1].cadence_spm:.0f} steps/min", None, got[0])
                  for got in released[:RELEASED * spend]]
    stride = best_of(nlp, [solved for solved, _ in found], simulate)
    stride.search = record(spend, spent, cadences, kept, cadence)
    stride.search["optima"] = distinct(nlp, [s for _, s in found if s.success], stride, simulate)
    if check_grid:
        stride.search["grid_valid"], stride.search["grid_failed"] = grid_checks(nlp, cadences, kept)
    stride.search["seconds"] = time.perf_counter() - spent.start  # the optima's forward checks too
    values = [o["objective"] for o in stride.search["optima"]]
    # None, not NaN, where no solve converged: the JSON writer refuses NaN (io.files.write_json)
    stride.search["spread_pct"] = (max(values) - min(values)) / abs(min(values)) * 100.0 if values else None
    return stride


def record(spend: int, spent: _Spend, cadences: list[float], kept: dict, cadence: float | None) -> dict:
    """`Stride.search` but its optima, spread and seconds: the spend, the solves and IPOPT
    iterations spent, the grid's least objective per cadence (None where no solve converged)."""
    return {"procedure": "imposed cadence" if cadence is not None else "free cadence", "spend": spend,
            "solves": spent.solves, "iterations": spent.iterations,
            "grid_spm": cadences, "grid_objective": [kept[c][1].objective_value if kept[c][1].success else None
                                                     for c in cadences]}


def grid_checks(nlp: StrideNLP, cadences: list[float], kept: dict) -> tuple[list, list]:
    """Whether each grid cadence's least costly stride (`record`'s grid_objective) is valid with
    the forward check (result.summarise, simulate), and its failed checks; None and [] where no
    solve converged there."""
    checked = [summarise(nlp, kept[c][0], simulate=True) if kept[c][1].success else None for c in cadences]
    return ([None if s is None else s.valid for s in checked],
            [[] if s is None else s.failed_checks for s in checked])


def distinct(nlp: StrideNLP, strides: list[Stride], answer: Stride, simulate: bool) -> list[dict]:
    """The distinct optima among converged strides (DISTINCT, DISTINCT_SPM) and the `answer`
    (its own where the touchdown's mode re-solved it), valid first, then the least objective:
    cadence (steps/min), objective, how many solves reached it, whether it is the `answer`, its
    validity and failed checks (with the forward check when `simulate`: the answer's own; the
    others summarised again)."""
    groups: list[list[Stride]] = []
    for s in sorted(strides, key=lambda s: s.objective_value):
        group = next((g for g in groups if _same(g[0], s)), None)
        if group is None:
            groups.append([s])
        else:
            group.append(s)
    if answer.success and not any(_same(g[0], answer) for g in groups):
        groups.append([answer])  # re-solved sliding under Coulomb (local.touchdown_mode): an optimum of its own
    out = []
    for first, *others in groups:
        is_answer = _same(first, answer)
        checked = answer if is_answer else \
            summarise(nlp, first.solved, simulate) if simulate and first.solved is not None else first
        out.append({"cadence_spm": first.cadence_spm, "objective": first.objective_value, "reached": 1 + len(others),
                    "answer": is_answer, "valid": checked.valid, "failed": checked.failed_checks})
    return sorted(out, key=lambda o: (not o["valid"], o["objective"]))


def _same(a: Stride, b: Stride) -> bool:
    """Two strides are one optimum (DISTINCT, DISTINCT_SPM)."""
    return (abs(a.objective_value - b.objective_value) <= DISTINCT * abs(b.objective_value)
            and abs(a.cadence_spm - b.cadence_spm) < DISTINCT_SPM)
