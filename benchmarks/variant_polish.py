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
    """The curve with its strides polished from `first` (strides in curve.cadences' order) and its
    free optimum re-solved (module doc); (curve, rounds run)."""
    nlp, cad = scene.nlp(), curve.cadences
    order = sorted(range(len(cad)), key=lambda k: cad[k])
    kept, free = list(first), curve.free
    rounds = 0
    while rounds < ROUNDS:
        rounds, changed = rounds + 1, False
        for i, k in enumerate(order):
            sources = [kept[order[j]] for j in (i - 1, i + 1) if 0 <= j < len(order)] + [free]
            for source in (s for s in sources if s.success):
                got = solve(scene, source, cad[k])
                if stride_map.better(got, kept[k]):
                    kept[k], changed = got, True
        again = stride_map._better_free(stride_map.CadenceCurve(free, kept), nlp, scene.speed, scene.slope,
                                        scene.friction).free
        changed, free = changed or again is not free, again
        if not changed:
            break
    return replace(curve, free=free, strides=kept), rounds


def chained(scene, curve) -> list:
    """`chain`'s first starts: outward from the free optimum's cadence, each cadence warm from
    the one before it (the free optimum first), in curve.cadences' order."""
    cad, c0 = curve.cadences, curve.free.cadence_spm
    out = {}
    for side in (sorted(k for k in range(len(cad)) if cad[k] >= c0),
                 sorted((k for k in range(len(cad)) if cad[k] < c0), key=lambda k: -cad[k])):
        side = sorted(side, key=lambda k: abs(cad[k] - c0))
        source = curve.free
        for k in side:
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
            lambda: polish(v.scene, curves[k], chained(v.scene, curves[k])))
        (curves[k], seen["rounds"]), *seen["cost"] = measured(polish, v.scene, curves[k], curves[k].strides)
        return curves
    compare_stride.band_curves = polished
    c = compare_speed.comparison(args.runner)
    cpu = compare_speed.cpu_s()
    section = compare_stride.answer(c, workers=args.workers) if args.workers else compare_stride.answer(c)
    report(args.runner, section, seen, compare_speed.cpu_s() - cpu)


def report(runner: str, section, seen: dict, cpu: float) -> None:
    """The tables of the module doc."""
    before, after, chain = seen["before"], next(cv for cv in section.curves if cv.name == "metabolic"), seen["chain"]
    print(f"{runner}: section {cpu:.1f} s CPU (this process and its pool's); polish {seen['rounds']} rounds, "
          f"{seen['cost'][0]} solves, {seen['cost'][1]} iterations, {seen['cost'][2]:.1f} s CPU; "
          f"chain start + polish ({seen['chain_rounds']} rounds) {seen['chain_cost'][0]} solves, "
          f"{seen['chain_cost'][1]} iterations, {seen['chain_cost'][2]:.1f} s CPU")
    print("cadence steps/min | metabolic objective (flag): band | polished | chain-polished | chain/polished - 1")
    for cad, b, a, ch in [(None, before.free, after.free, chain.free),
                          *zip(before.cadences, before.strides, after.strides, chain.strides)]:
        moved = ch.objective_value / a.objective_value - 1
        print(f"{'free ' + format(a.cadence_spm, '.1f') if cad is None else format(cad, '.1f')} | "
              + " | ".join(f"{s.objective_value:.5g}{mark(s)}" for s in (b, a, ch))
              + f" | {moved:+.2%}" + ("" if abs(moved) <= STABLE else " (not one optimum)"))
    print("envelope gap: band {} | polished {} | chain-polished {}".format(
        *(f"{g:+.2%}" if (g := cv.envelope_gap) is not None else "-" for cv in (before, after, chain))))
    nominal = section.curves[0]
    others = [cv for cv in section.curves[1:] if cv.name != "metabolic"]
    rows = {"band": compare_stride.what_ifs([nominal, *others, before], nominal.cadences),
            "polished": section.what_if,
            "chain": compare_stride.what_ifs([nominal, *others, chain], nominal.cadences)}
    print("what-if % | W nominal | band low..high W, objective part W, words: band | polished | chain-polished")
    for k, w in enumerate(section.what_if):
        print(f"{w.cadence_change_pct:+.0f} | {w.mechanical_power_change_W:+.1f} | " + " | ".join(
            f"{x.low_W:+.1f}..{x.high_W:+.1f}, {dict(x.parts).get('objective', 0):.1f}, {x.words()}"
            for x in (r[k] for r in rows.values())))


def mark(stride) -> str:
    """A stride's flag in the tables: failed (did not converge), invalid (a check failed), else none."""
    return " failed" if not stride.success else "" if stride.valid else " invalid"


if __name__ == "__main__":
    main()
