"""What twice and four times the nodes do to compare's what-ifs (issue 34 item 2 on compare's
stride section: its quick model solves the trapezoid at studies.stride_form.NODES = 30 nodes; the
scenes' model, the default since 2026-11-28, Hermite-Simpson at 40).

For each comparison.json given (written by `formopt compare`: the runner's speed, cadence, strike,
body and friction), the section's nominal scene (studies.stride_form.stride_scene, effort,
Coulomb impacts) and its cadence curve at the runner's cadence and WHAT_IF_PCT's
(studies.stride_map.cadence_curve: the least costly optimum found, as the section's before its
family), then each stride solved on each finer mesh as the section solves its band's strides,
warm from the coarse stride's values fitted to the finer nodes at its cadence, sticking
(compare_band.stride_at; `--refined`: optim.stride.refine.refined, which decides the touchdown's
mode again under Coulomb: on RBDS001 at 2.54 m/s every 60-node stride slid), and per mesh the
model's mechanical power P = W+/T at the runner's cadence and each what-if's change
dP(c) = P(c) - P(c_runner) (W), beside the section's own figures and band from the JSON:

    python problems/compare_mesh.py out/runners/*/comparison.json [--nodes 30 60 120] [--refined]
                                    [--transcription hermite-simpson (every mesh's, the section's
                                     curve solved again on it)] [--model quick (a null model's)]

The meshes default to the section's and twice it, on its transcription, the strides built as its
model (the JSON's `model`) builds them. The figures below are the quick model's (sections run
with `--stride-model quick`).
From 30 to 60 nodes the changes moved by up to 19.2 W on the three shipped runners: the section
names its what-ifs within compare_notes.MESH_MOVE_W (20 W) of zero, whose verdict a finer mesh
may turn (docs/howto/compare.md, "The mesh under the what-ifs"). The section's "nodes" are the
transcription's intervals (StrideSettings.nodes). On Hermite-Simpson (`--transcription
hermite-simpson --nodes 24 48`) they moved by 0.1-5.6 W and the objective by 0.1-1.5 %
(docs/howto/compare.md, "Hermite-Simpson under the what-ifs").
"""

from __future__ import annotations

import argparse
import json
import time

from formopt.mechanics.body import scaled_body
from formopt.optim.stride.problem import TRANSCRIPTIONS
from formopt.optim.stride.refine import refined
from formopt.studies.compare_band import stride_at
from formopt.studies.compare_stride import WHAT_IF_PCT
from formopt.studies.stride_form import STRIDE_MODELS, stride_scene
from formopt.studies.stride_map import cadence_curve, for_nodes


def parse(argv=None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("comparisons", nargs="+", help="comparison.json files written by formopt compare")
    parser.add_argument("--nodes", nargs="+", type=int,
                        help="the meshes (the transcription's intervals, StrideSettings.nodes; default the "
                             "section's and twice it)")
    parser.add_argument("--transcription", choices=TRANSCRIPTIONS, help="every mesh's (default the section's)")
    parser.add_argument("--model", choices=tuple(STRIDE_MODELS),
                        help="the section's stride model where its JSON says none (a mesh set by hand)")
    parser.add_argument("--refined", action="store_true",
                        help="each finer stride solved by refine.refined (its touchdown's mode decided again "
                             "under Coulomb) instead of as the section solves its strides (sticking)")
    return parser.parse_args(argv)


def runner(path: str) -> dict:
    """What the section solved for the runner of one comparison.json."""
    with open(path) as f:
        d = json.load(f)
    s = d["stride"]
    return {"name": path, "body": d["body"] if "mass_kg" in d["body"] else d["settings"]["body"],
            "friction": d["settings"]["friction"], "speed": s["speed_mps"], "law": s["law"],
            "cadence": s["measured_cadence_spm"], "strike": s["measured_strike"], "nodes": s["nodes"],
            "what_if": s["what_if"], "transcription": s.get("transcription", "trapezoid"),
            "model": s.get("model", "quick")}  # a JSON from before the key (2026-11-28): quick's


def finer(scene, strides: list, nodes: int, refine: bool) -> list:
    """Each stride solved again on `nodes` nodes (module docstring), one line each as it ends."""
    fine, out = for_nodes(scene, nodes), []
    for s in strides:
        clock = time.process_time()
        got = refined(fine.nlp(), s, scene.nlp(), simulate=False) if refine else stride_at((fine, (s,), s.cadence_spm))
        out.append(got)
        print(f"    {nodes} nodes, {s.cadence_spm:.1f} steps/min: {got.status}, {got.iterations} iterations, "
              f"{time.process_time() - clock:.1f} s of CPU; objective {s.objective_value:.5f} -> "
              f"{got.objective_value:.5f}, touchdown {s.impacts[-1]['mode']} -> {got.impacts[-1]['mode']}", flush=True)
    return out


def changes(strides: list) -> tuple[float, list[float]]:
    """The model's power at the runner's cadence (W, the first stride) and each what-if's change."""
    power = [s.mechanical_power_W for s in strides]
    return power[0], [q - power[0] for q in power[1:]]


def main(argv=None) -> None:
    args = parse(argv)
    how = "refined, the touchdown's mode decided again" if args.refined else "as the section's band, sticking"
    for path in args.comparisons:
        r = runner(path)
        r["model"] = r["model"] or args.model
        if r["model"] is None:
            raise SystemExit(f"{path}: its stride section's model is null (a mesh set by hand): give --model")
        nodes, transcription = args.nodes or [r["nodes"], 2 * r["nodes"]], args.transcription or r["transcription"]
        print(f"{r['name']}: {r['speed']:.2f} m/s, {r['strike']}, runner {r['cadence']:.1f} steps/min, the section "
              f"on the {r['transcription']} at {r['nodes']} intervals; the finer meshes solved {how}", flush=True)
        if (nodes[0], transcription) != (r["nodes"], r["transcription"]):
            print(f"  NOTE: the first mesh ({transcription} at {nodes[0]} intervals) is not the "
                  f"section's ({r['transcription']} at {r['nodes']})", flush=True)
        body = scaled_body(r["body"]["mass_kg"], r["body"]["height_m"], r["body"]["sex"])
        scene = stride_scene(body, r["speed"], r["strike"], "effort", r["friction"], r["law"], nodes[0],
                             transcription=transcription, model=r["model"])
        clock = time.process_time()
        curve = cadence_curve(scene, r["speed"], [r["cadence"]] + [r["cadence"] * (1 + p / 100) for p in WHAT_IF_PCT])
        print(f"  the curve at {nodes[0]} nodes: {time.process_time() - clock:.0f} s of CPU", flush=True)
        meshes = {nodes[0]: curve.strides}
        meshes.update({n: finer(scene, curve.strides, n, args.refined) for n in nodes[1:]})
        for n, strides in meshes.items():
            p0, dp = changes(strides)
            failed = ", ".join(f"{s.cadence_spm:.0f}" for s in strides if not s.success)
            print(f"  {n:4d} nodes: the model's P at the runner's cadence {p0:6.1f} W; dP " + "  ".join(
                f"{p:+.0f} %: {d:+6.1f}" for p, d in zip(WHAT_IF_PCT, dp))
                + (f"  (not converged at {failed} steps/min)" if failed else ""), flush=True)
        section = [w["mechanical_power_change_W"] for w in r["what_if"]]
        off = max(abs(a - b) for a, b in zip(changes(curve.strides)[1], section))
        print("  the section: dP " + "  ".join(
            f"{w['cadence_change_pct']:+.0f} %: {w['mechanical_power_change_W']:+6.1f} [{w['low_W']:+.1f}, "
            f"{w['high_W']:+.1f}] {w['words']}" for w in r["what_if"])
            + (f"  (NOTE: the curve here differs from the section's by up to {off:.1f} W)" if off > 0.05 else ""),
            flush=True)


if __name__ == "__main__":
    main()
