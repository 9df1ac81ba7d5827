"""The paper's results under fair comparisons: Figs. 4-6, each claim with a verdict.

    python problems/paper.py [--out out/paper]

Every comparison holds the leg posture and velocities fixed and changes one thing. The base
touchdown is formopt/scenes/landing_spring.toml's (the paper's body at 3.5 m/s; trunk 5, hip 30,
knee 20 deg, so the shank is 5 deg ahead of vertical; the foot swept back at -300 deg/s) with
the running joints (RBDS001's stiffness and touchdown moments). A heel strike puts the sole
toe-up (ankle dorsiflexed), a forefoot strike toe-down (plantarflexed), by the same angle.
Each quantity is the one the paper compares, under each contact law, and a landing or an
impact that breaks its own assumptions (a slip under no-slip, a contact the ground would have
to pull, a landing that never brings the second point down) is counted apart and drawn
hollow, never mixed into a mean.

(a) Fig. 4: T_c over the whole landing and the trunk's velocity change, heel against forefoot.
(b) Fig. 5: T_c and the impulses of the impact against the ankle angle; T_c against the
    impulse (the paper's T_c = -1/2 p . v_c ties them).
(c) Fig. 6: downhill (-10 deg, 3.5 m/s) against a flat marathon pace (5 m/s), same posture.
(d) Shank + foot and the effective mass against the full leg.
(e) Which joint model carries a landing: free hinges, the running joints, locked.

Each of (a)-(c) ends with a line "VERDICT <claim>: reproduced, refuted, or depends on the
contact law (per law)", after the numbers it rests on.
"""

from __future__ import annotations

import argparse
import copy
import math
import tomllib
from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from formopt import impact
from formopt import simulate as land
from formopt.io.files import save_figure
from formopt.io.scene import load, parse
from formopt.mechanics.contact import LAWS
from formopt.mechanics.landing import Joints
from formopt.studies import sweep

HERE = Path(__file__).resolve().parent
BASE = HERE.parent / "formopt" / "scenes" / "landing_spring.toml"
FOOT_ANGLES = (5.0, 10.0, 15.0)  # deg, |sole angle| at touchdown, toe-up (heel) or toe-down
COLORS = {"heel": "tab:orange", "forefoot": "tab:blue"}


def touchdown(strike: str, foot_deg: float, law: str, **values):
    """The base scene with the sole at `foot_deg` from the ground (toe-up positive) by the
    ankle alone, struck on `strike`, under contact law `law`; `values` as sweep parameters."""
    base = load(BASE)
    trunk, hip, knee = (math.degrees(base.state[k]) for k in range(3))
    shank = hip - trunk - knee  # deg from the downward vertical, distal end ahead
    scene = sweep.apply(base, {"ankle_deg": foot_deg - shank, **values})
    return replace(scene, strike=strike, contact=law)


def verdict(name: str, by_law: dict) -> str:
    """'reproduced' / 'refuted' / 'depends on the contact law' from {law: True/False/None}
    (None: no valid case under that law)."""
    known = {law: v for law, v in by_law.items() if v is not None}
    if not known:
        word = "not testable (no valid case)"
    elif all(known.values()):
        word = "reproduced" + ("" if len(known) == len(by_law) else " where testable")
    elif not any(known.values()):
        word = "refuted" + ("" if len(known) == len(by_law) else " where testable")
    else:
        word = "depends on the contact law"
    laws = ", ".join(f"{law}: {'yes' if v else 'no' if v is not None else 'no valid case'}"
                     for law, v in by_law.items())
    return f"VERDICT {name}: {word} ({laws})"


def figure4(out: Path) -> list[str]:
    """Whole landings, heel (toe-up) against forefoot (toe-down), per contact law."""
    findings, claim = [], {}
    fig, axes = plt.subplots(2, len(LAWS), figsize=(4.2 * len(LAWS), 6.5), sharex=True)
    for j, law in enumerate(LAWS):
        means = {}
        for k, strike in enumerate(("heel", "forefoot")):
            sign = 1.0 if strike == "heel" else -1.0
            totals, dvs, oks = [], [], []
            for foot in FOOT_ANGLES:
                L = land(touchdown(strike, sign * foot, law))
                dv = np.sum([e.dv_trunk for e in L.impacts], axis=0)
                totals.append(L.T_c_total)
                dvs.append(dv[0])
                oks.append(L.valid)
            x = np.arange(len(FOOT_ANGLES)) + (k - 0.5) * 0.38
            for ax, values in ((axes[0, j], totals), (axes[1, j], dvs)):
                ax.bar(x, values, 0.36, color=[COLORS[strike] if ok else "none" for ok in oks],
                       edgecolor=COLORS[strike], hatch=None, label=strike)
            valid = [t for t, ok in zip(totals, oks) if ok]
            means[strike] = np.mean(valid) if valid else None
            findings.append(f"{law:12s} {strike:8s}: T_c over the landing "
                            + ", ".join(f"{t:.2f}{'' if ok else '*'}" for t, ok in zip(totals, oks))
                            + f" J at sole {', '.join(f'{sign * a:+.0f}' for a in FOOT_ANGLES)} deg; "
                            f"trunk dv_x {', '.join(f'{d:+.3f}' for d in dvs)} m/s; "
                            f"valid {sum(oks)}/{len(oks)}")
        axes[0, j].set_title(f"{law}", fontsize=10)
        claim[law] = None if None in means.values() else bool(means["forefoot"] < means["heel"])
        if claim[law] is not None:
            findings.append(f"{law:12s} mean of the valid landings: forefoot {means['forefoot']:.2f} J, "
                            f"heel {means['heel']:.2f} J")
    for ax in axes[1]:
        ax.set_xticks(range(len(FOOT_ANGLES)), [f"{a:g} deg" for a in FOOT_ANGLES])
        ax.set_xlabel("|sole angle| at touchdown")
    axes[0, 0].set_ylabel("T_c over the landing (J)")
    axes[1, 0].set_ylabel("trunk velocity change x (m/s)")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Fig. 4, same leg: heel strike toe-up against forefoot strike toe-down "
                 "(hollow: an invalid landing)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, out / "fig4_heel_vs_forefoot.png")
    plt.close(fig)
    findings.append("(* an invalid landing: a slip under no-slip, a pulled contact or no second contact)")
    findings.append(verdict("Fig. 4, a forefoot strike absorbs less over the landing than a heel strike", claim))
    return findings


def figure5(out: Path) -> list[str]:
    """The impact against the sole angle, both strikes, each law: T_c and impulses."""
    findings, claim = [], {}
    angles = {"heel": np.linspace(2.0, 20.0, 10), "forefoot": -np.linspace(2.0, 20.0, 10)}
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    rows = {}
    for strike, feet in angles.items():
        for foot in feet:
            r = impact(touchdown(strike, foot, "no-slip"))
            for law, v in r.contact_laws.items():
                (p_t, p_n), = v.impulse.values()
                rows.setdefault((strike, law), []).append((foot, v.T_c, p_t, p_n, v.valid))
    styles = {"no-slip": "-", "coulomb": "--", "frictionless": ":"}
    for (strike, law), values in rows.items():
        foot, T_c, p_t, p_n, ok = (np.array(c) for c in zip(*values))
        ok = ok.astype(bool)
        for ax, y in ((axes[0], T_c), (axes[1], np.hypot(p_t, p_n))):
            ax.plot(foot, y, styles[law], color=COLORS[strike], lw=1,
                    label=f"{strike}, {law}" if ax is axes[0] else None)
            ax.plot(foot[ok], y[ok], "o", ms=3, color=COLORS[strike])
            ax.plot(foot[~ok], y[~ok], "o", ms=4, mfc="none", color=COLORS[strike])
        axes[2].plot(np.hypot(p_t, p_n)[ok], T_c[ok], "o", ms=3, color=COLORS[strike])
        corr = np.corrcoef(np.hypot(p_t, p_n)[ok], T_c[ok])[0, 1] if ok.sum() > 2 else float("nan")
        findings.append(f"{law:12s} {strike:8s}: T_c {T_c.min():.2f}..{T_c.max():.2f} J, |p| "
                        f"{np.hypot(p_t, p_n).min():.2f}..{np.hypot(p_t, p_n).max():.2f} N s over sole "
                        f"{foot.min():+.0f}..{foot.max():+.0f} deg; valid {ok.sum()}/{len(ok)}; "
                        f"correlation T_c / |p| over the valid ones {corr:+.3f}")
        claim.setdefault(law, []).append(corr)
    axes[0].set_ylabel("T_c of the impact (J)")
    axes[1].set_ylabel("impulse |p| (N s)")
    for ax in axes[:2]:
        ax.set_xlabel("sole angle at touchdown (deg, toe-up +)")
    axes[0].legend(fontsize=7)
    axes[2].set_xlabel("impulse |p| (N s), valid impacts")
    axes[2].set_ylabel("T_c (J)")
    fig.suptitle("Fig. 5: the impact against the foot angle (hollow: invalid impact)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, out / "fig5_ankle_sweep.png")
    plt.close(fig)
    tracks = {law: (None if all(math.isnan(c) for c in cs) else all(c > 0.9 for c in cs if not math.isnan(c)))
              for law, cs in claim.items()}
    findings.append(verdict("Fig. 5, T_c rises and falls with the impact's impulse across ankle angles", tracks))
    return findings


def figure6(out: Path) -> list[str]:
    """Downhill (-10 deg, 3.5 m/s) against flat ground at 5 m/s, the same forefoot posture."""
    findings, claim = [], {}
    fig, ax = plt.subplots(figsize=(7, 4))
    for j, law in enumerate(LAWS):
        results = {}
        for name, values in (("downhill -10 deg, 3.5 m/s", {"slope_deg": -10.0}),
                             ("flat, 5 m/s", {"hip_vx": 5.0})):
            L = land(touchdown("forefoot", -10.0, law, **values))
            braking = -sum(e.dv_trunk[0] for e in L.impacts)
            ok = L.valid
            results[name] = (L.T_c_total, ok)
            ax.bar(j + (0.2 if "flat" in name else -0.2), L.T_c_total, 0.38,
                   color=("tab:brown" if "down" in name else "tab:gray") if ok else "none",
                   edgecolor="tab:brown" if "down" in name else "tab:gray", label=name if j == 0 else None)
            findings.append(f"{law:12s} {name:26s}: T_c over the landing {L.T_c_total:.2f} J, trunk "
                            f"braking {braking:+.3f} m/s, largest mu_c {L.mu_c_max:.2f}, "
                            f"{'valid' if ok else 'INVALID'} ({L.ended})")
        (down, ok_d), (flat, ok_f) = results.values()
        claim[law] = bool(down > flat) if ok_d and ok_f else None
    ax.set_xticks(range(len(LAWS)), LAWS)
    ax.set_ylabel("T_c over the landing (J)")
    ax.legend(fontsize=8)
    ax.set_title("Fig. 6: same forefoot posture (sole -10 deg); hollow: invalid", fontsize=9)
    fig.tight_layout()
    save_figure(fig, out / "fig6_downhill_vs_marathon.png")
    plt.close(fig)
    findings.append(verdict("Fig. 6, downhill at 3.5 m/s absorbs more than flat at 5 m/s", claim))
    return findings


def models(out: Path) -> list[str]:
    """First-impact T_c of the coarse models against the full leg over the forefoot ankle range."""
    data = tomllib.loads(BASE.read_text())
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
    for strike, foot in (("forefoot", -10.0), ("heel", 10.0)):
        scene = touchdown(strike, foot, "no-slip")
        for joints in (Joints("free"), scene.joints, Joints("locked", locked=("knee", "ankle"))):
            L = land(replace(scene, joints=joints))
            pulls = ", ".join(f"{p} {f:.0f} N at {t * 1e3:.1f} ms" for t, p, f in L.releases[:3])
            findings.append(f"{strike} strike, {joints.model:13s}: {len(L.impacts)} impacts, "
                            f"T_c_total {L.T_c_total:.2f} J, {L.ended}; "
                            f"contacts that would pull: {pulls or 'none'}"
                            + (f" (+{len(L.releases) - 3} more)" if len(L.releases) > 3 else ""))
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
        print(title, flush=True)
        for line in section():
            print("   ", line)
    print(f"figures in {out}")


if __name__ == "__main__":
    main()
