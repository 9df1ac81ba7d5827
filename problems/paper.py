"""The paper's results, reproduced: Figs. 4-6 and the argument for modelling the body's inertia.

    python problems/paper.py [--out out/paper]

(a) Fig. 4: heel and forefoot landings at several ankle angles: kinetic energy over time with
    its drops at the impacts, the energy absorbed per impact and the trunk's dv, and the ankle
    angle when the second point comes down.
(b) Fig. 5: ankle-angle sweeps for both strike patterns; does T_c track the contact force?
(c) Fig. 6: downhill (-10 deg) braking against a flat marathon landing (5 m/s).
(d) Shank + foot against the full leg: the paper's argument that the body must be modelled.
(e) Which joint model each figure needs: free hinges, springs and dampers, or locked joints.

Scenes: problems/landing_spring.toml (forefoot) and landing_heel.toml (heel), passive knee and
ankle. Each section prints what it finds; figures go to --out.
"""

from __future__ import annotations

import argparse
import copy
import math
import tempfile
import tomllib
from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from formopt import impact  # noqa: E402
from formopt.studies import sweep  # noqa: E402
from formopt import simulate as land  # noqa: E402
from formopt.io.files import save_figure  # noqa: E402
from formopt.io.scene import load, parse  # noqa: E402

HERE = Path(__file__).resolve().parent
SCENES = {"forefoot": HERE / "landing_spring.toml", "heel": HERE / "landing_heel.toml"}
ANKLES = {"forefoot": (-15.0, -10.0, -7.0), "heel": (0.0, 5.0, 10.0)}


def scene(strike: str, **values):
    """A landing scene with parameter values set (sweep parameter names)."""
    return sweep.apply(load(SCENES[strike]), values)


def figure4(out: Path) -> list[str]:
    """Kinetic energy over time (4a) and absorbed energy and dv per strike pattern (4b)."""
    findings, bars = [], {}
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, strike in zip(axes, ("heel", "forefoot")):
        for ankle in ANKLES[strike]:
            L = land(scene(strike, ankle_deg=ankle))
            ax.plot(L.t * 1e3, L.T, label=f"ankle {ankle:+.0f} deg: T_c {L.T_c_total:.2f} J")
            bars[(strike, ankle)] = L
            if len(L.impacts) > 1:
                q = L.q[-1]
                model = load(SCENES[strike]).model()
                at = math.degrees(model.segment_angle(q, "foot") - model.segment_angle(q, "shank"))
                findings.append(f"{strike} strike, ankle {ankle:+.0f} deg: second contact after "
                                f"{L.impacts[1].time * 1e3:.1f} ms, ankle then {at:+.1f} deg "
                                f"({at - ankle:+.1f} deg)")
            else:
                findings.append(f"{strike} strike, ankle {ankle:+.0f} deg: no second contact "
                                f"within {L.t[-1] * 1e3:.0f} ms ({L.ended})")
        ax.set_title(f"{strike} strike", fontsize=10)
        ax.set_xlabel("time after touchdown (ms)")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("kinetic energy T (J)")
    save_figure(fig, out / "fig4a_kinetic_energy.png")
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    labels = [f"{s[0]}{a:+.0f}" for s, a in bars]
    first = [L.impacts[0].T_c for L in bars.values()]
    second = [L.impacts[1].T_c if len(L.impacts) > 1 else 0.0 for L in bars.values()]
    axes[0].bar(labels, first, label="first impact")
    axes[0].bar(labels, second, bottom=first, label="second impact")
    axes[0].set_ylabel("absorbed energy T_c (J)")
    axes[0].legend(fontsize=8)
    dv = np.array([np.sum([e.dv_trunk for e in L.impacts], axis=0) for L in bars.values()])
    axes[1].bar(np.arange(len(labels)) - 0.2, dv[:, 0], 0.4, label="dv x")
    axes[1].bar(np.arange(len(labels)) + 0.2, dv[:, 1], 0.4, label="dv z")
    axes[1].set_xticks(range(len(labels)), labels)
    axes[1].set_ylabel("trunk velocity change over the impacts (m/s)")
    axes[1].legend(fontsize=8)
    fig.suptitle("h: heel strike, f: forefoot strike, with the touchdown ankle angle (deg)", fontsize=9)
    save_figure(fig, out / "fig4b_absorbed_and_dv.png")
    plt.close(fig)
    heel = np.mean([L.T_c_total for (s, _), L in bars.items() if s == "heel"])
    fore = np.mean([L.T_c_total for (s, _), L in bars.items() if s == "forefoot"])
    findings.append(f"mean T_c_total over these landings: heel strike {heel:.2f} J, forefoot strike {fore:.2f} J")
    return findings


def figure5(out: Path) -> list[str]:
    """Ankle-angle sweeps for both strike patterns: T_c per impact and the peak normal force."""
    findings = []
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    with tempfile.TemporaryDirectory() as tmp:
        for strike, grid in (("forefoot", "ankle_deg=-25:-5:21"), ("heel", "ankle_deg=-5:15:21")):
            rows = [r for r in sweep.run(load(SCENES[strike]), [sweep.parse_param(grid)],
                                         Path(tmp) / f"{strike}.csv", progress=False) if not r["error"]]
            ankle = np.array([float(r["ankle_deg"]) for r in rows])
            total = np.array([float(r["T_c_total"]) for r in rows])
            first = np.array([float(r["T_c_first"]) for r in rows])
            force = np.array([float(r["f_n_max_N"]) for r in rows])
            axes[0].plot(ankle, first, "--", label=f"{strike}: first impact")
            axes[0].plot(ankle, total, "-", label=f"{strike}: both impacts")
            axes[1].plot(ankle, force, label=strike)
            r = np.corrcoef(total, force)[0, 1] if len(rows) > 2 else float("nan")
            findings.append(f"{strike} strike, ankle {ankle.min():+.0f}..{ankle.max():+.0f} deg: T_c_total "
                            f"{total.min():.2f}..{total.max():.2f} J, peak normal force "
                            f"{force.min():.0f}..{force.max():.0f} N; correlation T_c_total/peak force {r:+.2f}")
    axes[0].set_xlabel("touchdown ankle angle (deg)")
    axes[0].set_ylabel("absorbed energy (J)")
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("touchdown ankle angle (deg)")
    axes[1].set_ylabel("peak normal contact force (N)")
    axes[1].legend(fontsize=8)
    save_figure(fig, out / "fig5_ankle_sweep.png")
    plt.close(fig)
    return findings


def figure6(out: Path) -> list[str]:
    """Downhill braking (-10 deg) against a flat marathon landing (5 m/s)."""
    downhill = replace(scene("heel", hip_vz=-0.9), slope=math.radians(-10.0), friction=0.6)
    marathon = scene("forefoot", hip_vx=5.0)
    findings = []
    fig, ax = plt.subplots(figsize=(6, 4))
    for name, s in (("downhill -10 deg, heel, 3.5 m/s", downhill), ("flat, forefoot, 5 m/s", marathon)):
        L = land(s)
        braking = -sum(e.dv_trunk[0] for e in L.impacts)
        ax.plot(L.t * 1e3, L.T - L.T[0], label=f"{name}: T_c {L.T_c_total:.1f} J")
        findings.append(f"{name}: T_c_total {L.T_c_total:.2f} J, trunk braking {braking:.3f} m/s, "
                        f"largest mu_c {L.mu_c_max:.2f}, no slip {'held' if L.no_slip_held else 'violated'}, "
                        f"{L.ended}")
    ax.set_xlabel("time after touchdown (ms)")
    ax.set_ylabel("change of kinetic energy (J)")
    ax.legend(fontsize=8)
    save_figure(fig, out / "fig6_downhill_vs_marathon.png")
    plt.close(fig)
    return findings


def models(out: Path) -> list[str]:
    """First-impact T_c of the coarse models against the full leg over the forefoot ankle range."""
    data = tomllib.loads(SCENES["forefoot"].read_text())
    ankles = np.linspace(-25.0, -6.0, 20)
    values = {}
    for kind in ("effective-mass", "shank-foot", "leg"):
        d = copy.deepcopy(data)
        d["scene"]["model"] = kind
        del d["joints"]  # the first impact does not depend on the joint model
        base = parse(d, "models")
        values[kind] = np.array([impact(sweep.apply(base, {"ankle_deg": a})).T_c for a in ankles])
    fig, ax = plt.subplots(figsize=(6, 4))
    for kind, v in values.items():
        ax.plot(ankles, v, label=kind)
    ax.set_xlabel("touchdown ankle angle (deg), forefoot strike")
    ax.set_ylabel("T_c of the first impact (J)")
    ax.legend(fontsize=8)
    save_figure(fig, out / "models_shank_foot_vs_leg.png")
    plt.close(fig)
    findings = []
    for kind in ("effective-mass", "shank-foot"):
        error = (values[kind] - values["leg"]) / values["leg"]
        trend = np.corrcoef(values[kind], values["leg"])[0, 1]
        findings.append(f"{kind} against the full leg: T_c differs by {100 * error.min():+.0f}% to "
                        f"{100 * error.max():+.0f}% over the ankle range; correlation of the two "
                        f"curves {trend:+.2f}")
    return findings


def joint_models() -> list[str]:
    """Which joint model gives a landing that carries the body through both contacts."""
    findings = []
    for strike in ("forefoot", "heel"):
        data = tomllib.loads(SCENES[strike].read_text())
        for joints in ({"model": "free"}, data["joints"], {"model": "locked"}):
            d = copy.deepcopy(data)
            d["joints"] = joints
            L = land(parse(d, "joints"))
            pulls = ", ".join(f"{p} {f:.0f} N at {t * 1e3:.1f} ms" for t, p, f in L.releases[:3])
            findings.append(f"{strike} strike, {joints['model']:13s}: {len(L.impacts)} impacts, "
                            f"T_c_total {L.T_c_total:.2f} J, {L.ended}; "
                            f"contacts that would pull: {pulls or 'none'}")
    return findings


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/paper")
    out = Path(parser.parse_args().out)
    for title, section in (("(a) Fig. 4, heel and forefoot landings", lambda: figure4(out)),
                           ("(b) Fig. 5, ankle sweeps", lambda: figure5(out)),
                           ("(c) Fig. 6, downhill braking and marathon", lambda: figure6(out)),
                           ("(d) shank + foot against the full leg", lambda: models(out)),
                           ("(e) joint models", joint_models)):
        print(title)
        for line in section():
            print("   ", line)
    print(f"figures in {out}")


if __name__ == "__main__":
    main()
