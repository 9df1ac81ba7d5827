"""Heel against forefoot strike under each contact law, compared fairly, and against RBDS001.

    python problems/strike_laws.py [--out out/strike_laws]

The leg of RBDS subject 001 at its right touchdowns of the 3.5 m/s trial (mean of 43 steps:
trunk, hip and knee angles, hip velocity, thigh, shank and foot rates, measured by
`formopt compare`), on the paper's leg scaled to the runner (de Leva; 62 kg, 1.81 m). Only
the ankle changes: dorsiflexed until the heel strikes with the sole 5 to 15 deg toe-up,
plantarflexed until the forefoot strikes 5 to 15 deg toe-down. Each touchdown goes through
the impact under the three laws (friction 0.8). Printed per law: the mean T_c of each strike,
their ratio (forefoot / heel), the impulse ratio |p_t| / p_n (over the impacts where the
ground pushes), and how many impacts are valid; then the data set's own early-stance force ratio |Fx| / Fy (RBDS001processed.txt,
mean right-foot cycle at 3.5 m/s) for the impulse ratios to be read against. Writes a CSV
of every touchdown and a figure.
"""

import argparse
import math
from pathlib import Path

import numpy as np

from formopt import Impact
from formopt.io import mocap
from formopt.io.files import save_figure, write_csv
from formopt.measure import measure
from formopt.mechanics.body import scaled_body
from formopt.mechanics.contact import LAWS
from formopt.mechanics.model import STATE, build_model, positions

DATA = Path(__file__).resolve().parent.parent / "data" / "rbds"
MASS, HEIGHT = 62.0, 1.81  # RBDSinfo.txt, subject 001
FRICTION = 0.8
FOOT_ANGLES = (5.0, 15.0)  # deg, |sole angle| of the strikes compared
EARLY = (2, 3, 5)  # % of the gait cycle (about 7 ms each at 171 steps/min)


def measured_leg():
    """Mean touchdown state of RBDS001's right foot, T35 (model.STATE, SI)."""
    static = mocap.read(DATA / "RBDS001static.c3d")
    trial = mocap.read(DATA / "RBDS001runT35.c3d")
    steps = measure(trial, static, HEIGHT).steps
    right = [td.state() for td in steps.valid if td.side == "R"]
    return np.mean(right, axis=0), len(right)


def foot_angle(x, body) -> float:
    """The sole's angle to the ground (deg): + toe up (heel lower), - toe down."""
    p = positions(x, body, "hip")
    (hx, hz), (fx, fz) = p["heel"], p["forefoot"]
    return math.degrees(math.atan2(fz - hz, fx - hx))


def touchdowns(reference, body):
    """(strike, foot angle, state) for every whole-degree ankle angle in the compared range."""
    out = []
    ankle = STATE.index("ankle")
    for deg in np.arange(-45.0, 30.5, 1.0):
        x = reference.copy()
        x[ankle] = math.radians(deg)
        a = foot_angle(x, body)
        if FOOT_ANGLES[0] <= abs(a) <= FOOT_ANGLES[1]:
            out.append(("heel" if a > 0 else "forefoot", a, x))
    return out


def early_force_ratio(speed="35"):
    """∫|Fx| / ∫Fy over the first k % of RBDS001's mean right-foot cycle, k in EARLY."""
    rows = [line.rstrip("\n").split("\t") for line in open(DATA / "RBDS001processed.txt")]
    header, values = rows[0], np.array([[float(v) if v else np.nan for v in r] for r in rows[1:]])
    fx, fy = values[:, header.index("RgrfX" + speed)], values[:, header.index("RgrfY" + speed)]
    return {k: float(np.trapezoid(np.abs(fx[:k + 1])) / np.trapezoid(fy[:k + 1])) for k in EARLY}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/strike_laws")
    args = parser.parse_args()
    body = scaled_body(MASS, HEIGHT)
    model = build_model(body, "leg")
    reference, n = measured_leg()
    impacts = {s: Impact(model, s, 0.0, FRICTION) for s in ("heel", "forefoot")}
    rows = []
    for strike, angle, x in touchdowns(reference, body):
        r = impacts[strike](x)
        for law, v in r.contact_laws.items():
            t, p_n = (sum(p[k] for p in v.impulse.values()) for k in (0, 1))
            rows.append({"strike": strike, "foot_angle_deg": angle, "ankle_deg": math.degrees(x[3]),
                         "law": law, "T_c_J": v.T_c, "impulse_ratio": abs(t) / p_n if p_n > 0 else math.nan,
                         "slip_mps": v.slip_velocity, "mode": v.mode or "", "valid": v.valid})
    print(f"RBDS001, right touchdowns of T35 (n = {n}): trunk {math.degrees(reference[0]):.1f}, hip "
          f"{math.degrees(reference[1]):.1f}, knee {math.degrees(reference[2]):.1f} deg; hip velocity "
          f"({reference[4]:.2f}, {reference[5]:.2f}) m/s; only the ankle changes; friction {FRICTION}")
    print(f"heel strikes: sole {FOOT_ANGLES[0]:g} to {FOOT_ANGLES[1]:g} deg toe-up; forefoot strikes: "
          "the same toe-down\n")
    print(f"{'law':13s} {'heel T_c':>9s} {'fore T_c':>9s} {'fore/heel':>9s} {'heel |t|/n':>10s} "
          f"{'fore |t|/n':>10s} {'valid heel':>10s} {'valid fore':>10s}")
    for law in LAWS:
        cells = {}
        for strike in ("heel", "forefoot"):
            sel = [r for r in rows if r["law"] == law and r["strike"] == strike]
            pushed = [r["impulse_ratio"] for r in sel if not math.isnan(r["impulse_ratio"])]
            cells[strike] = (np.mean([r["T_c_J"] for r in sel]), np.mean(pushed) if pushed else math.nan,
                             f"{sum(r['valid'] for r in sel)}/{len(sel)}")
        h, f = cells["heel"], cells["forefoot"]
        print(f"{law:13s} {h[0]:9.3f} {f[0]:9.3f} {f[0] / h[0]:9.2f} {h[1]:10.3f} {f[1]:10.3f} "
              f"{h[2]:>10s} {f[2]:>10s}")
    ratios = early_force_ratio()
    print("\nRBDS001's own force ratio early in stance, ∫|Fx| dt / ∫Fy dt over the first "
          + ", ".join(f"{k} %: {v:.2f}" for k, v in ratios.items()) + " of the cycle (3.5 m/s)")
    out = Path(args.out)
    write_csv(out / "strike_laws.csv", [list(rows[0]), *[list(r.values()) for r in rows]])
    save_figure(figure(rows, ratios), out / "strike_laws.png")
    print(f"wrote {out / 'strike_laws.csv'}, {out / 'strike_laws.png'}")


def figure(rows, ratios):
    from matplotlib.figure import Figure
    fig = Figure(figsize=(10, 4))
    ax_t, ax_r = fig.subplots(1, 2)
    for law, colour in zip(LAWS, ("C0", "C1", "C2")):
        for strike, marker in (("heel", "o"), ("forefoot", "s")):
            sel = [r for r in rows if r["law"] == law and r["strike"] == strike]
            a = [r["foot_angle_deg"] for r in sel]
            ax_t.plot(a, [r["T_c_J"] for r in sel], marker, color=colour, ms=4,
                      label=f"{law}" if strike == "heel" else None)
            ax_r.plot(a, [r["impulse_ratio"] for r in sel], marker, color=colour, ms=4)
    for (k, v), style in zip(ratios.items(), (":", "--", "-.")):
        ax_r.axhline(v, color="grey", lw=0.8, ls=style, label=f"RBDS001 force ratio, first {k} %")
    ax_r.set_ylim(0, 3)
    ax_r.legend(fontsize=7, loc="upper right")
    ax_t.set(xlabel="sole angle at touchdown (deg, + heel strike)", ylabel="T_c (J)",
             title="absorbed energy (circles heel, squares forefoot)")
    ax_r.set(xlabel="sole angle at touchdown (deg)", ylabel="|p_t| / p_n",
             title="impulse ratio against the measured force ratio")
    ax_t.legend(fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    main()
