"""Heel-only versus forefoot-only optima: the least absorbed energy for each strike pattern.

    python problems/strike_optima.py [--scene demo] [--out out/strike_optima]

Solves the scene's problem twice, once with each strike pattern (everything else equal),
prints the two optima side by side with what holds each, and draws them over each other.
"""

import argparse
from dataclasses import replace
from pathlib import Path

from formopt import load, solve
from formopt.io.files import save_figure, write_json
from formopt.io.scene import touchdown_table
from formopt.report.figures import indicator_figure, posture_figure
from formopt.report.tables import solve_report


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="demo")
    parser.add_argument("--out", default="out/strike_optima")
    args = parser.parse_args()
    base = load(args.scene)
    out = Path(args.out)
    optima, reports = {}, {}
    for strike in ("heel", "forefoot"):
        scene = replace(base, strike=strike)
        opt = solve(scene)
        optima[strike] = (scene, opt)
        reports[strike] = solve_report(scene, opt, [])
    print(f"{'':28s} {'heel strike':>14s} {'forefoot strike':>16s}")
    for key in ("trunk", "hip", "knee", "ankle"):
        cells = [touchdown_table(s.strike, o.state)["angles_deg"][key] for s, o in optima.values()]
        print(f"{key + ' (deg)':28s} {cells[0]:14.2f} {cells[1]:16.2f}")
    rows = (("T_c (J)", lambda o: o.impact.T_c), ("normal impulse (N s)", lambda o: o.impact.impulse_total[1]),
            ("tangential impulse (N s)", lambda o: o.impact.impulse_total[0]),
            ("mu_c", lambda o: o.impact.mu_c), ("dv trunk x (m/s)", lambda o: o.impact.dv_trunk[0]),
            ("dv trunk z (m/s)", lambda o: o.impact.dv_trunk[1]))
    for name, value in rows:
        cells = [value(o) for _, o in optima.values()]
        print(f"{name:28s} {cells[0]:14.4f} {cells[1]:16.4f}")
    for strike, (_, opt) in optima.items():
        held = ", ".join(c.name for c in opt.active) or "nothing (interior)"
        print(f"{strike}: {opt.status}; held by {held}")
    save_figure(posture_figure(base.body, "forefoot", base.slope,
                               [(optima["heel"][1].state, "heel-strike optimum", "tab:orange"),
                                (optima["forefoot"][1].state, "forefoot-strike optimum", "tab:blue")]),
                out / "postures.png")
    save_figure(indicator_figure({s: o.impact for s, (_, o) in optima.items()}), out / "indicators.png")
    write_json(out / "optima.json", reports)
    print(f"wrote {out / 'postures.png'}, {out / 'indicators.png'}, {out / 'optima.json'}")


if __name__ == "__main__":
    main()
