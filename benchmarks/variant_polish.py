"""What polishing the band's metabolic variant like the nominal would cost and change, formopt unchanged.

    python benchmarks/variant_polish.py T35|T25|20160226 [--workers 1] [--rounds 3]

compare's stride section (studies.compare_stride.answer, a runner of problems/compare/runners.toml
as benchmarks/compare_speed.py --stride reads it) with its `band_curves` wrapped: after the band,
the metabolic variant's strides polished (`polish`): each cadence re-solved warm (stride_map.warm:
with multipliers, the same NLP) from each neighbouring cadence's metabolic stride and from the
metabolic free optimum, the least costly kept (stride_map.better), then the free optimum re-solved
from the least costly imposed stride (stride_map._better_free), in rounds until one changes nothing
(at most ROUNDS; the sticking strides' own free optimum in the free one's place where that slides).
From three first starts: `polished`, the band's strides (each warm from the nominal's at its
cadence); `chain`, strides chained outward along the cadences from the band's metabolic free
optimum (each warm from the one before); `family`, chained likewise from the polished curve's
envelope free optimum (Curve.envelope_free); each then polished. The same per-cadence optima
within STABLE (0.1 %) would say the polished answer does not hang on its start. Prints the
polishes' rounds, solves, IPOPT iterations and CPU s (this process: `--workers 1` puts the whole
section here); per cadence the metabolic objective (band and the three); the envelope gap
(Curve.envelope_gap) with the free optimum's touchdown; the what-ifs (W: the nominal's change,
the band, its objective part's width, the words) with each metabolic curve in the band (the
section's own is the polished one).

Measured 2026-11-27 (`--workers 1`, the machine otherwise idle; objective per distance, flag
`i`: invalid, a check failed; `family`: a third start, chained from the polished envelope's free
optimum, then polished; T25 with `--rounds 8`, its polish ending in 6):

    cadence | T35: band, polished, chain, family | T25: band, polished, chain, family | RIC: band, polished, chain
    free    | .1840 .1581sl .1840 .1581sl     | .1776i .0744 .1589i .0742    | .1979 .1979 .1979
    -10 %   | .1843 .1843 .2311 .1845        | .0868 .0747 .1722i .0743     | .2548i .2702 .2711
    -5 %    | .1723 .1723 .1985 .1723        | .0882i .0770 .1733i .0779    | .2549 .2404 .2404
    runner  | .1684 .1683 .1848 .1683        | .1870 .0850 .1792i .0891     | .2283 .2213 .2212
    +5 %    | .1930 .1687 .1900 .1687        | .1021 .0974 .1911 .1034      | .2079 .2061 .2061
    +10 %   | .2030 .1786 .2046 .1786        | .1160 .1130 .2014 .1163      | .2000 .1987 .1987
    envelope gap | +8.5 % -0.4 % -0.4 % -0.4 % | +51 % -0.5 % +0.1 % -0.2 %  | -1.0 % -0.4 % -0.4 %
    (T35's polished free slides, .1581; the gap is its strides' own sticking free's, .1677.
    RIC's family column equals its chain's.)

    what-if | W nominal | band low..high W (objective part W) verdict: band -> polished
    T35 -10 | -25.4 | -44.9..+9.1 (34.5) none -> -44.9..+9.8 (35.2) none   [chain 47.3, none]
    T35 -5  | -13.1 | -19.4..+3.1 (16.3) none -> -19.4..+3.8 (16.9) none
    T35 +5  | +17.1 | +16.0..+19.9 (0.6) costs -> +0.4..+19.9 (16.7) costs
    T35 +10 | +40.9 | +23.2..+45.0 (17.7) costs -> +4.5..+45.0 (36.4) costs [chain 28.1]
    T25 -10 | -18.7 | -26.8..-16.3 (8.1) saves -> -21.3..-2.2 (16.6) saves  [3 rounds: +2.8 (21.5) none]
    T25 -5  | -4.7  | -26.5..-2.9 (21.8) saves -> -6.1..-2.3 (2.4) saves
    T25 +5  | +5.4  | -23.0..+6.5 (28.4) none -> +3.1..+6.5 (2.3) costs
    T25 +10 | +15.1 | -19.4..+15.7 (34.5) none -> +8.7..+15.7 (6.4) costs
    RIC -10 | -14.9 | -35.2..-0.4 (1.1) saves -> -35.2..+25.9 (40.8) none (the band's -10 % was invalid)
    RIC -5  | -23.0 | -32.4..+3.8 (26.8) none -> -32.4..+8.1 (31.2) none
    RIC +5  | +13.6 | -15.3..+17.2 (28.9) none -> -4.2..+17.2 (17.8) none
    RIC +10 | +41.1 | -20.0..+43.6 (61.1) none -> -7.0..+43.6 (48.2) none

    cost of the polish (this process, CPU s) | T35 | T25 (3 rounds; 8) | RIC
    section without the polish and the two checks | 32.7 | 25.7 | 27.7
    polish: rounds, solves, IPOPT iterations, CPU s | 3, 44, 1982, 19.3 | 3, 43, 2891, 33.0; 6, 82, 4841, 50.9 | 2, 26, 1670, 18.6

Stability: RIC's three starts land on the same optima (within 0.02 %, but -10 %: 0.34 %); T35's
polish and the family start agree within 0.11 %, the chain from the band's free optimum stays on a
family 10-25 % costlier (its sticking free optimum, .1840, never seeds the sliding one); T25's
polish and family start differ by -14 % to +6 % after 3 rounds and -0.6 % to +6 % after 6, the
chain stays 2-fold costlier (mostly invalid). A local polish makes the metabolic variant's strides
cheaper (T25 up to 2-fold, T35 up to 12 %) and its envelope consistent (gap within 0.5 %), but the
answer still depends on the start: no per-cadence optimum within 0.1 % on T35 or T25.
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
    # the quick model: the one its tables were measured on (the default's since 2026-11-28 is scenes)
    section = compare_stride.answer(c, model="quick", **({"workers": args.workers} if args.workers else {}))
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
