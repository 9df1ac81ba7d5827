"""Cost of the contact laws at the impact: compiled, mapped over the bench's states, one core.

    python benchmarks/contact_laws_speed.py

Prints states/s for the no-slip indicators alone, the Coulomb indicators alone, and all three
laws together (medians of 7 runs over 10,000 states).
"""

import statistics
import time

import casadi as ca
import numpy as np

from formopt.mechanics.body import paper_body
from formopt.mechanics.compiled import external
from formopt.mechanics.impact import impact_function, on_ground
from formopt.mechanics.model import build_model
from formopt.studies.bench import read_states

N = 10000
FRICTION = 0.8  # the shipped scenes' (a shoe on a belt): Coulomb's outputs depend on it
OUTPUTS = {
    "no-slip alone": ["T_c_no_slip", "impulse_no_slip", "dv_trunk_no_slip", "dv_com_no_slip"],
    "Coulomb alone": ["T_c_coulomb", "impulse_coulomb", "slip_coulomb", "mode_coulomb",
                      "dv_trunk_coulomb", "dv_com_coulomb"],
    "all three laws": [f"{k}_{law}" for law in ("no_slip", "coulomb", "frictionless")
                       for k in ("T_c", "impulse", "slip", "dv_trunk", "dv_com")] + ["mode_coulomb"],
}


def main():
    leg = build_model(paper_body(), "leg")
    states = np.resize(read_states(), (N, 10)).T
    X = ca.DM(states)
    base = None
    for label, outputs in OUTPUTS.items():
        f = on_ground(impact_function(leg, "forefoot", outputs=outputs), FRICTION, 0.0)
        batch = external(f.map(N, "serial"))
        batch(X)
        times = []
        for _ in range(7):
            t = time.perf_counter()
            batch(X)
            times.append(time.perf_counter() - t)
        rate = N / statistics.median(times)
        base = base or rate
        print(f"{label:16s} {rate:12,.0f} states/s   cost {base / rate:4.2f} x no-slip alone")


if __name__ == "__main__":
    main()
