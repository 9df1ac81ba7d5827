"""The stride optimum against what experiments found about running form (issue 27 item 2).

    python problems/literature.py [--objectives effort work metabolic] [--strike heel]
                                  [--nodes 30] [--starts 1] [--sections cadence step impacts
                                  heiderscheit share]

Each relation prints its numbers and a verdict computed from them: "reproduced", "not
reproduced" or "depends on the objective" (reproduced under some objectives, not others). The
paper's body (73 kg, 1.731 m), level ground, friction 0.8, no-slip impacts, one strike (heel:
most recreational runners'), on compare's quick model (studies.stride_form.STRIDE_MODELS: the
trapezoid with knee and ankle springs, the model these verdicts were measured on; not
mesh-converged). Strides at imposed cadences come from
studies.stride_map.cadence_curve (at each cadence the least costly optimum found from the free
optimum and both neighbours);
per-joint work from studies.stride_form.joint_work. A stride that does not converge is
printed as such and leaves its objective without a verdict ("no verdict").

Relations (../shared/design.md, section 6):
- cadence: +-20 % around the free optimum at 3.0 and 3.5 m/s, a U-shaped cost (the objective
  per distance higher at both ends); its minimum against de Ruiter et al. 2020 (optimal 171 +- 8
  steps/min at 3.04 m/s) and Lieberman et al. 2015 (84.8 +- 3.6 strides/min = 169.6 +- 7.2
  steps/min at 3.0 m/s): reproduced when the free optimum is within one sd of both.
- step: step length +-20 % of leg length around the free optimum at 3.83 m/s (Cavanagh &
  Williams 1982): a U, the long end costlier than the short (+3.4 against +2.6 ml/kg/min).
- impacts: the impacts' T_c per step rising with step length (Derrick, Hamill & Caldwell 1998)
  along the 3.0 m/s cadence curve (the least-squares slope's sign); the striking point closer
  to the hip as cadence rises, 5.9 % per 5 strides/min (Lieberman 2015): reproduced when the
  model's change per 10 steps/min has that sign and lies within a factor 2 of it.
- heiderscheit: +5 and +10 % cadence lower the stance knee's negative work, -10 % raises the
  stance hip's, knee's and ankle's (Heiderscheit et al. 2011; at 3.0 m/s, around the free
  optimum, the runner's preferred cadence in the model).
- share: the impacts' T_c over the positive joint work of the free optimum at 3.0 m/s against
  about 5 % (Schroeder & Kuo 2021, collisions and hysteresis): reproduced within a factor 2.
"""

from __future__ import annotations

import argparse

import numpy as np

from formopt.mechanics.body import paper_body
from formopt.mechanics.limits import CADENCE_SPM
from formopt.optim.stride.problem import OBJECTIVES
from formopt.studies.stride_form import NODES, joint_work, placement_m, stride_scene
from formopt.studies.stride_map import cadence_curve

DE_RUITER = (171.0, 8.0)  # optimal cadence, steps/min, at 3.04 m/s
LIEBERMAN = (169.6, 7.2)  # 84.8 +- 3.6 strides/min at 3.0 m/s, in steps/min
LIEBERMAN_PLACEMENT = -5.9  # % change of the foot's distance ahead of the hip per 10 steps/min
CAVANAGH = (2.6, 3.4)  # ml/kg/min more at -20 % and +20 % of leg length (short, long)
SCHROEDER = 0.05  # share of the mechanical energy in collisions and hysteresis at 3 m/s
CURVE_3 = (0.8, 0.9, 0.95, 1.05, 1.1, 1.2)  # cadence factors around the free optimum, 3.0 m/s
CURVE_35 = (0.8, 0.9, 1.1, 1.2)


def leg_length(body) -> float:
    """Hip to ground when standing (m): thigh + shank + the ankle's height over the heel."""
    return body["thigh"].length + body["shank"].length - body["foot"].landmarks["heel"][1]


class Curves:
    """Cadence curves per (speed, objective), solved once and shared by the sections."""

    def __init__(self, body, strike: str, nodes: int, starts: int):
        self.body, self.strike, self.nodes, self.starts = body, strike, nodes, starts
        self.cache = {}

    def get(self, speed: float, objective: str, factors=None, steps=None):
        """(free optimum, {factor: stride}) at `speed`; factors of the free cadence, or step
        lengths `steps` given as multiples of leg length added to the free step (m); a stride
        None where its cadence is beyond the stride's range. RuntimeError when the free optimum
        does not converge."""
        key = (speed, objective, factors, steps)
        if key not in self.cache:
            scene = stride_scene(self.body, speed, self.strike, objective, nodes=self.nodes,
                                 starts=self.starts, model="quick")
            free = cadence_curve(scene, speed, []).free
            for _ in range(3):  # again around a cheaper free optimum found from an imposed cadence
                centre = free
                names, cadences = self.grid(centre, speed, factors, steps)
                inside = [k for k, c in enumerate(cadences) if c in CADENCE_SPM]
                got = cadence_curve(scene, speed, [cadences[k] for k in inside], start=centre)
                if got.free_from == "free":
                    break
                free = got.free
                print(f"  ({objective}, {speed:.1f} m/s: a cheaper free optimum, "
                      f"{free.cadence_spm:.1f} steps/min and cost {free.objective_value:.4f} against "
                      f"{centre.cadence_spm:.1f} and {centre.objective_value:.4f}, found from the stride at "
                      f"{got.free_from} steps/min: the grid again around it)")
            else:
                print(f"  ({objective}, {speed:.1f} m/s: still moving after three grids; the last grid's "
                      f"centre, {centre.cadence_spm:.1f} steps/min, stands for the free optimum)")
            at = dict.fromkeys(names)  # None: a cadence beyond the stride's range (60-300)
            at.update({names[k]: s for k, s in zip(inside, got.strides)})
            self.cache[key] = (centre, at)  # the free optimum the cadences were set from
        return self.cache[key]

    def grid(self, free, speed: float, factors, steps) -> tuple[list, list[float]]:
        """(names, cadences (steps/min)) of the grid around a free optimum: factors of its
        cadence, or step lengths added to its step (multiples of leg length)."""
        if steps is not None:
            return steps, [60.0 * speed / (free.step_length_m + d * leg_length(self.body)) for d in steps]
        return factors, [free.cadence_spm * f for f in factors]


def combine(verdicts: dict) -> str:
    """One verdict over the objectives: reproduced / not reproduced when all that have one
    agree, else depends on the objective."""
    given = {v for v in verdicts.values() if v != "no verdict"}
    if not given:
        return "no verdict (no objective converged)"
    return given.pop() if len(given) == 1 else "depends on the objective"


def solved(*strides) -> bool:
    return all(s is not None and s.success for s in strides)


def per_objective(curves: Curves, objectives, speed: float, verdicts: list[dict], label: str = "",
                  **which):
    """(objective, free optimum, {factor: stride}) for each objective whose free optimum
    converged (Curves.get); one that did not is printed and gets "no verdict" in `verdicts`."""
    for objective in objectives:
        try:
            f0, at = curves.get(speed, objective, **which)
        except RuntimeError as err:
            print(f"  {objective:9s}{label}: {err}")
            for v in verdicts:
                v[objective] = "no verdict"
            continue
        yield objective, f0, at


def cadence_section(curves: Curves, objectives) -> None:
    print("\n== cadence: a U-shaped cost around the free optimum; its minimum against "
          "de Ruiter 2020 (171 +- 8) and Lieberman 2015 (169.6 +- 7.2 steps/min)")
    verdicts = {}
    for speed, factors in ((3.0, CURVE_3), (3.5, CURVE_35)):
        for objective, f0, at in per_objective(curves, objectives, speed, [verdicts],
                                               f" {speed:.1f} m/s", factors=factors):
            costs = {f: s.objective_value for f, s in at.items() if s is not None}
            line = "  ".join(f"{f:4.2f}:" + (f"{s.objective_value:.4f}{'' if s.success else '!'} ({s.cadence_spm:.0f})"
                                              if s is not None else "beyond range") for f, s in at.items())
            print(f"  {objective:9s} {speed:.1f} m/s: free {f0.cadence_spm:6.1f} steps/min, cost "
                  f"{f0.objective_value:.4f}; at factor x free: {line}")
            if speed != 3.0:
                continue
            if not solved(at[0.8], at[1.2]):
                print("    an end of the +-20 % curve is missing or did not converge")
                verdicts[objective] = "no verdict"
                continue
            u = costs[0.8] > f0.objective_value and costs[1.2] > f0.objective_value
            near = [abs(f0.cadence_spm - m) / sd for m, sd in (DE_RUITER, LIEBERMAN)]
            ok = u and max(near) <= 1.0
            verdicts[objective] = "reproduced" if ok else "not reproduced"
            print(f"    U-shaped {u}; the minimum {near[0]:.1f} sd from de Ruiter's, {near[1]:.1f} "
                  f"sd from Lieberman's -> {verdicts[objective]}")
    print(f"  VERDICT cadence: {combine(verdicts)} ({verdicts})")


def step_section(curves: Curves, objectives) -> None:
    print("\n== step length +-20 % of leg length at 3.83 m/s: a U, long costlier than short "
          f"(Cavanagh & Williams 1982: +{CAVANAGH[1]} long against +{CAVANAGH[0]} short)")
    verdicts = {}
    for objective, f0, at in per_objective(curves, objectives, 3.83, [verdicts],
                                           steps=(-0.2, -0.1, 0.1, 0.2)):
        c0 = f0.objective_value
        rise = {d: (s.objective_value - c0) / c0 * 100 for d, s in at.items() if s is not None}
        print(f"  {objective:9s}: free step {f0.step_length_m:.3f} m ({f0.cadence_spm:.1f} steps/min); "
              "cost change % at +-leg fraction: " + "  ".join(
                  f"{d:+.1f}:{rise[d]:+.2f}{'' if at[d].success else '!'}" for d in rise))
        if not solved(at[-0.2], at[0.2]):
            print("    an end of the +-20 % curve is missing or did not converge")
            verdicts[objective] = "no verdict"
            continue
        u = rise[-0.2] > 0 and rise[0.2] > 0
        ok = u and rise[0.2] > rise[-0.2]
        verdicts[objective] = "reproduced" if ok else "not reproduced"
        print(f"    U-shaped {u}; long ({rise[0.2]:+.2f} %) costlier than short ({rise[-0.2]:+.2f} %) "
              f"{rise[0.2] > rise[-0.2]} -> {verdicts[objective]}")
    print(f"  VERDICT step length: {combine(verdicts)} ({verdicts})")


def impacts_section(curves: Curves, objectives) -> None:
    print("\n== impacts (3.0 m/s): T_c per step rising with step length (Derrick 1998); the strike "
          f"closer to the hip with cadence ({LIEBERMAN_PLACEMENT} % per 10 steps/min, Lieberman 2015)")
    derrick, lieberman = {}, {}
    for objective, f0, at in per_objective(curves, objectives, 3.0, [derrick, lieberman],
                                           factors=CURVE_3):
        strides = [s for s in [f0, *at.values()] if s is not None and s.success]
        step = np.array([s.step_length_m for s in strides])
        T_c = np.array([s.budget["impacts_J"] for s in strides])
        cadence = np.array([s.cadence_spm for s in strides])
        ahead = np.array([placement_m(s) for s in strides])
        slope_tc = np.polyfit(step, T_c, 1)[0]
        slope_pl = np.polyfit(cadence, ahead, 1)[0] * 10 / placement_m(f0) * 100
        derrick[objective] = "reproduced" if slope_tc > 0 else "not reproduced"
        ratio = slope_pl / LIEBERMAN_PLACEMENT
        lieberman[objective] = "reproduced" if 0.5 <= ratio <= 2 else "not reproduced"
        order = np.argsort(step)
        print(f"  {objective:9s}: step m / T_c J: " + "  ".join(
            f"{step[k]:.3f}/{T_c[k]:.2f}" for k in order) + f"; slope {slope_tc:+.2f} J/m -> {derrick[objective]}")
        print(f"  {'':9s}  strike ahead of the hip at the free optimum {placement_m(f0):.3f} m; change "
              f"{slope_pl:+.1f} % per 10 steps/min (x{ratio:.2f} of Lieberman's) -> {lieberman[objective]}")
    print(f"  VERDICT impact loss with step length: {combine(derrick)} ({derrick})")
    print(f"  VERDICT placement with cadence: {combine(lieberman)} ({lieberman})")


def heiderscheit_section(curves: Curves, objectives) -> None:
    print("\n== Heiderscheit 2011 (3.0 m/s): +5/+10 % cadence lower the stance knee's negative "
          "work; -10 % raises it at every joint (stance leg, J per step)")
    verdicts = {}
    for objective, f0, at in per_objective(curves, objectives, 3.0, [verdicts], factors=CURVE_3):
        rows = {1.0: f0, **{f: at[f] for f in (0.9, 0.95, 1.05, 1.1)}}
        if not solved(*rows.values()):
            print(f"  {objective:9s}: a stride at 0.9-1.1 x free is missing or did not converge")
            verdicts[objective] = "no verdict"
            continue
        neg = {f: {j: joint_work(s)[f"stance_{j}"]["negative_J"] for j in ("hip", "knee", "ankle")}
               for f, s in sorted(rows.items())}
        for f, w in neg.items():
            print(f"  {objective:9s} x{f:4.2f} ({rows[f].cadence_spm:5.1f} steps/min): negative work "
                  f"hip {w['hip']:6.2f}, knee {w['knee']:6.2f}, ankle {w['ankle']:6.2f} J")
        knee_lower = neg[1.05]["knee"] < neg[1.0]["knee"] and neg[1.1]["knee"] < neg[1.0]["knee"]
        all_higher = all(neg[0.9][j] > neg[1.0][j] for j in ("hip", "knee", "ankle"))
        verdicts[objective] = "reproduced" if knee_lower and all_higher else "not reproduced"
        print(f"    knee lower at +5 and +10 %: {knee_lower}; every joint higher at -10 %: {all_higher}"
              f" -> {verdicts[objective]}")
    print(f"  VERDICT Heiderscheit: {combine(verdicts)} ({verdicts})")


def share_section(curves: Curves, objectives) -> None:
    print(f"\n== the impacts' share of the positive work at 3.0 m/s against ~{SCHROEDER:.0%} "
          "(Schroeder & Kuo 2021)")
    verdicts = {}
    for objective, f0, _ in per_objective(curves, objectives, 3.0, [verdicts], factors=CURVE_3):
        share = f0.budget["impacts_J"] / f0.budget["positive_work_J"]
        verdicts[objective] = "reproduced" if 0.5 <= share / SCHROEDER <= 2 else "not reproduced"
        print(f"  {objective:9s}: impacts {f0.budget['impacts_J']:.2f} J of W+ "
              f"{f0.budget['positive_work_J']:.2f} J per step: {share:.1%} -> {verdicts[objective]}")
    print(f"  VERDICT impacts' share: {combine(verdicts)} ({verdicts})")


SECTIONS = {"cadence": cadence_section, "step": step_section, "impacts": impacts_section,
            "heiderscheit": heiderscheit_section, "share": share_section}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objectives", nargs="+", default=list(OBJECTIVES), choices=OBJECTIVES)
    ap.add_argument("--strike", default="heel", choices=("heel", "forefoot", "flat"))
    ap.add_argument("--nodes", type=int, default=NODES)
    ap.add_argument("--starts", type=int, default=1)
    ap.add_argument("--sections", nargs="+", default=list(SECTIONS), choices=list(SECTIONS))
    args = ap.parse_args(argv)
    curves = Curves(paper_body(), args.strike, args.nodes, args.starts)
    print(f"the paper's body, {args.strike} strike, {args.nodes} nodes, {args.starts} start(s); "
          "'!' marks a stride that did not converge")
    for name in args.sections:
        SECTIONS[name](curves, args.objectives)


if __name__ == "__main__":
    main()
