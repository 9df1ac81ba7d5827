"""What polishing the band's metabolic variant like the nominal would cost and change, formopt unchanged.

    python benchmarks/variant_polish.py T35 [--workers 1]

compare's stride section (studies.compare_stride.answer, a runner of problems/compare/runners.toml
as benchmarks/compare_speed.py --stride reads it) with its `band_curves` wrapped: after the band,
the metabolic variant's strides polished (`polish`): each cadence re-solved warm (stride_map.warm:
with multipliers, the same NLP) from each neighbouring cadence's metabolic stride and from the
metabolic free optimum, the least costly kept (stride_map.better), then the free optimum re-solved
from the least costly imposed stride (stride_map._better_free), in rounds until one changes nothing
(at most ROUNDS). Twice, from two first starts: `nominal`, the band's strides (each warm from the
nominal's at its cadence), and `chain`, the strides chained outward along the cadences from the
band's metabolic free optimum (each warm from its polished neighbour): the same per-cadence optima
within STABLE say the polished answer does not hang on the start. Prints per cadence the metabolic
objective (band / polished / chain-polished), its envelope gap (Curve.envelope_gap) before/after,
the what-ifs (W: nominal change, band, the objective part's width, words) before/after, and the
polish's solves, IPOPT iterations and CPU s (this process: `--workers 1` puts the whole section here).
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import compare_speed  # benchmarks/compare_speed.py: the runner's comparison, CPU s

from formopt.optim.stride import collocation, summarise
from formopt.studies import compare_stride, stride_map

ROUNDS = 3  # polish rounds at most (--rounds)
STABLE = 1e-3  # relative: two starts' polished objectives this close are one optimum
COUNT = {"on": False, "solves": 0, "iterations": 0}  # the polish's IPOPT runs


def solve(scene, source, cadence):
    """The scene's stride at `cadence` (None: free) warm from `source` (stride_map.warm)."""
    nlp = scene.nlp()
    return summarise(nlp, stride_map.warm(nlp, source, scene.speed, scene.slope, scene.friction, cadence), False)


def polish(scene, curve, first: list):
    """The curve with its strides polished from `first` (strides in curve.cadences' order), its
    free optimum re-solved (module doc) and, where that slides and the strides stick, their own
    sticking free optimum (compare_stride.sticking_free, as the nominal's: the polish's source in
    the free optimum's place, its primal values being another NLP's); (curve, rounds run)."""
    nlp, cad, speed = scene.nlp(), curve.cadences, scene.speed
    order = sorted(range(len(cad)), key=lambda k: cad[k])
    kept, free = list(first), curve.free
    own, rounds = compare_stride.sticking_free(scene, speed, replace(curve, strides=kept)), 0
    while rounds < ROUNDS:
        rounds, changed = rounds + 1, False
        envelope = own if own is not None and own.success else free
        for i, k in enumerate(order):
            sources = [kept[order[j]] for j in (i - 1, i + 1) if 0 <= j < len(order)] + [envelope]
            for source in (s for s in sources if s.success):
                got = solve(scene, source, cad[k])
                if stride_map.better(got, kept[k]):
                    kept[k], changed = got, True
        again = stride_map._better_free(stride_map.CadenceCurve(free, kept), nlp, speed, scene.slope,
                                        scene.friction).free
        changed, free = changed or again is not free, again
        own = compare_stride.sticking_free(scene, speed, replace(curve, free=free, strides=kept))
        if not changed:
            break
    return replace(curve, free=free, strides=kept, own_free=own), rounds


def chained(scene, curve, start) -> list:
    """First starts chained outward from `start`'s cadence (a free optimum), each cadence warm
    from the one before it (`start` first), in curve.cadences' order."""
    cad, c0 = curve.cadences, start.cadence_spm
    out = {}
    for side in ([k for k in range(len(cad)) if cad[k] >= c0], [k for k in range(len(cad)) if cad[k] < c0]):
        source = start
        for k in sorted(side, key=lambda k: abs(cad[k] - c0)):
            out[k] = solve(scene, source, cad[k])
            source = out[k] if out[k].success else source
    return [out[k] for k in range(len(cad))]


def measured(fn, *args):
    """fn(*args) with COUNT on: (its result, solves, iterations, CPU s)."""
    COUNT.update(on=True, solves=0, iterations=0)
    cpu = time.process_time()
    got = fn(*args)
    COUNT["on"] = False
    return got, COUNT["solves"], COUNT["iterations"], time.process_time() - cpu


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runner", help="a part of a runners.toml trial's name: T35, T25, 20160226")
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--rounds", type=int, default=ROUNDS, help="polish rounds at most")
    args = parser.parse_args()
    globals()["ROUNDS"] = args.rounds
    run = collocation.StrideNLP._run

    def counted(nlp, solver, *rest):
        got = run(nlp, solver, *rest)
        if COUNT["on"]:
            COUNT["solves"], COUNT["iterations"] = COUNT["solves"] + 1, COUNT["iterations"] + got.iterations
        return got
    collocation.StrideNLP._run = counted
    band, seen = compare_stride.band_curves, {}

    def polished(nominal, variants, beside, say, frees=None):
        curves = band(nominal, variants, beside, say, frees)
        k, v = next((k, v) for k, v in enumerate(variants) if v.name == "metabolic")
        seen["before"], seen["scene"] = curves[k], v.scene
        if not curves[k].ok:
            return curves
        (seen["chain"], seen["chain_rounds"]), *seen["chain_cost"] = measured(
            lambda: polish(v.scene, curves[k], chained(v.scene, curves[k], curves[k].free)))
        (curves[k], seen["rounds"]), *seen["cost"] = measured(polish, v.scene, curves[k], curves[k].strides)
        (seen["family"], seen["family_rounds"]), *seen["family_cost"] = measured(
            lambda: polish(v.scene, curves[k], chained(v.scene, curves[k], curves[k].envelope_free)))
        return curves
    compare_stride.band_curves = polished
    c = compare_speed.comparison(args.runner)
    cpu = compare_speed.cpu_s()
    section = compare_stride.answer(c, workers=args.workers) if args.workers else compare_stride.answer(c)
    report(args.runner, section, seen, compare_speed.cpu_s() - cpu)


def report(runner: str, section, seen: dict, cpu: float) -> None:
    """The tables of the module doc."""
    after = next(cv for cv in section.curves if cv.name == "metabolic")
    curves = {"band": seen["before"], "polished": after, "chain": seen["chain"], "family": seen["family"]}
    print(f"{runner}: section {cpu:.1f} s CPU (this process and its pool's); " + "; ".join(
        f"{name} {seen[key + 'rounds']} rounds, {n} solves, {its} iterations, {s:.1f} s CPU"
        for name, key in (("polish", ""), ("chain + polish", "chain_"), ("family + polish", "family_"))
        for n, its, s in [seen[key + "cost"]]))
    print("cadence steps/min | metabolic objective (flag): " + " | ".join(curves)
          + " | chain, family / polished - 1")
    for k in range(len(after.cadences) + 1):
        got = [cv.free if k == 0 else cv.strides[k - 1] for cv in curves.values()]
        moved = [s.objective_value / got[1].objective_value - 1 for s in got[2:]]
        print(f"{'free ' + format(got[1].cadence_spm, '.1f') if k == 0 else format(after.cadences[k - 1], '.1f')} | "
              + " | ".join(f"{s.objective_value:.5g}{mark(s)}" for s in got) + " | "
              + ", ".join(f"{m:+.2%}" for m in moved) + ("" if max(map(abs, moved)) <= STABLE else " (not one)"))
    print("envelope gap (the free's touchdown; the sticking strides' own free): " + " | ".join(
        f"{name} {'-' if (g := cv.envelope_gap) is None else format(g, '+.2%')} "
        f"({compare_stride.touchdown_mode(cv.free)}; "
        f"{'-' if cv.own_free is None else format(cv.own_free.objective_value, '.5g') + mark(cv.own_free)})"
        for name, cv in curves.items()))
    nominal = section.curves[0]
    others = [cv for cv in section.curves[1:] if cv.name != "metabolic"]
    rows = [compare_stride.what_ifs([nominal, *others, cv], nominal.cadences) for cv in curves.values()]
    print("what-if % | W nominal | band low..high W, objective part W, words: " + " | ".join(curves))
    for k, w in enumerate(section.what_if):
        print(f"{w.cadence_change_pct:+.0f} | {w.mechanical_power_change_W:+.1f} | " + " | ".join(
            f"{x.low_W:+.1f}..{x.high_W:+.1f}, {dict(x.parts).get('objective', 0):.1f}, {x.words()}"
            for x in (r[k] for r in rows)))


def mark(stride) -> str:
    """A stride's flag in the tables: failed (did not converge), invalid (a check failed), else none."""
    return " failed" if not stride.success else "" if stride.valid else " invalid"


if __name__ == "__main__":
    main()
