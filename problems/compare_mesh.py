"""What twice and four times the nodes do to compare's what-ifs (issue 34 item 2 on compare's
stride section, which solves the trapezoid at studies.stride_form.NODES = 30 nodes).

For each comparison.json given (written by `formopt compare`: the runner's speed, cadence, strike,
body and friction), the section's nominal scene (studies.stride_form.stride_scene, effort,
Coulomb impacts) and its cadence curve at the runner's cadence and WHAT_IF_PCT's
(studies.stride_map.cadence_curve: the least costly optimum found, as the section's before its
family), then each stride solved on each finer mesh as the section solves its band's strides,
warm from the coarse stride's values fitted to the finer nodes at its cadence, sticking
(compare_band.stride_at; `--refined`: optim.stride.refine.refined, which decides the touchdown's
mode again under Coulomb: at 60 nodes it slides), and per mesh the mechanical power P = W+/T at
the runner's cadence and each what-if's change dP(c) = P(c) - P(c_runner) (W), beside the
section's own figures and band from the JSON:

    python problems/compare_mesh.py out/runners/*/comparison.json [--nodes 30 60 120] [--refined]

A what-if whose change moves with the mesh by more than its band's distance to zero may change
its words on a finer mesh (docs/howto/compare.md, "The mesh under the what-ifs").
"""

from __future__ import annotations

import argparse
import json
import time

from formopt.mechanics.body import scaled_body
from formopt.optim.stride.refine import refined
from formopt.studies.compare_band import stride_at
from formopt.studies.compare_stride import WHAT_IF_PCT
from formopt.studies.stride_form import stride_scene
from formopt.studies.stride_map import cadence_curve, for_nodes


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("comparisons", nargs="+", help="comparison.json files written by formopt compare")
    parser.add_argument("--nodes", nargs="+", type=int, default=[30, 60, 120],
                        help="the meshes (trapezoid nodes), the section's first")
    parser.add_argument("--refined", action="store_true",
                        help="each finer stride solved by refine.refined (its touchdown's mode decided again "
                             "under Coulomb) instead of as the section solves its strides (sticking)")
    return parser.parse_args(argv)


def runner(path: str) -> dict:
    """What the section solved for the runner of one comparison.json."""
    d = json.load(open(path))
    s = d["stride"]
    return {"name": path, "body": d["body"] if "mass_kg" in d["body"] else d["settings"]["body"],
            "friction": d["settings"]["friction"], "speed": s["speed_mps"], "law": s["law"],
            "cadence": s["measured_cadence_spm"], "strike": s["measured_strike"], "nodes": s["nodes"],
            "what_if": s["what_if"]}


def main(argv=None) -> None:
    args = parse(argv)
    for path in args.comparisons:
        r = runner(path)
        body = scaled_body(r["body"]["mass_kg"], r["body"]["height_m"], r["body"]["sex"])
        scene = stride_scene(body, r["speed"], r["strike"], "effort", r["friction"], r["law"], args.nodes[0])
        cadences = [r["cadence"]] + [r["cadence"] * (1 + p / 100) for p in WHAT_IF_PCT]
        clock = time.process_time()
        curve = cadence_curve(scene, r["speed"], cadences)
        print(f"  the curve at {args.nodes[0]} nodes: {time.process_time() - clock:.0f} s", flush=True)
        meshes = {args.nodes[0]: curve.strides}
        for n in args.nodes[1:]:
            fine = for_nodes(scene, n)
            meshes[n] = []
            for s in curve.strides:
                clock_n = time.process_time()
                got = refined(fine.nlp(), s, scene.nlp(), simulate=False) if args.refined else \
                    stride_at((fine, (s,), s.cadence_spm))
                meshes[n].append(got)
                print(f"    {n} nodes, {s.cadence_spm:.1f} steps/min: {got.status}, {got.iterations} iterations, "
                      f"{time.process_time() - clock_n:.1f} s; objective {s.objective_value:.5f} -> "
                      f"{got.objective_value:.5f}, touchdown {s.impacts[-1]['mode']} -> {got.impacts[-1]['mode']}",
                      flush=True)
        print(f"{r['name']}: {r['speed']:.2f} m/s, {r['strike']}, runner {r['cadence']:.1f} steps/min, "
              f"the section at {r['nodes']} nodes; {time.process_time() - clock:.0f} s of CPU", flush=True)
        for n, strides in meshes.items():
            ok = all(s.success for s in strides)
            power = [s.mechanical_power_W for s in strides]
            print(f"  {n:4d} nodes: P at the runner's cadence {power[0]:6.1f} W; dP " + "  ".join(
                f"{p:+.0f} %: {q - power[0]:+6.1f}" for p, q in zip(WHAT_IF_PCT, power[1:]))
                + ("" if ok else f"  (not converged: {[f'{s.cadence_spm:.0f}' for s in strides if not s.success]})"),
                flush=True)
        print("  the section: dP " + "  ".join(
            f"{w['cadence_change_pct']:+.0f} %: {w['mechanical_power_change_W']:+6.1f} [{w['low_W']:+.1f}, "
            f"{w['high_W']:+.1f}] {w['words']}" for w in r["what_if"]), flush=True)


if __name__ == "__main__":
    main()
