"""Speed of the impact indicators on the paper's leg, with Pinocchio side by side.

    python benchmarks/impact_speed.py [--states 10000] [--repeats 20]

Prints medians over repeats (seed printed): build and compile time; a compiled, mapped CasADi
batch (states/s on one core); a single state through the Python API (compiled: ca.external
called through Function.buffer; the checked ImpactResult API; CasADi's interpreted call); the
gradient of T_c against its value; and, in the same run, Pinocchio's impulseDynamics on the
same states (a Python loop of C++ calls: Pinocchio has no batch API).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import casadi as ca
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from helpers import SEED, random_states  # the tests' touchdown distribution

from formopt import Impact
from formopt.mechanics.body import paper_body
from formopt.mechanics.compiled import Compiled, external
from formopt.mechanics.impact import impact_function, on_ground
from formopt.mechanics.model import build_model

FRICTION = 0.8  # the shipped scenes' ground (a shoe on a belt)

INDICATORS = ["T", "T_c", "T_a", "impulse", "mu_signed", "dv_trunk", "dv_com"]


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def per_call(f, args):
    times = []
    for a in args:
        t = time.perf_counter()
        f(a)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--states", type=int, default=10000)
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--strike", default="forefoot", choices=["heel", "forefoot", "flat"])
    args = parser.parse_args()
    os.environ["FORMOPT_CACHE"] = tempfile.mkdtemp(prefix="formopt-bench-")  # a cold cache
    print(f"seed {SEED}; {args.states} touchdown states; strike {args.strike}; "
          f"medians of {args.repeats} repeats; one core")
    body = paper_body()
    model = build_model(body, "leg")
    X = random_states(args.states, strike=args.strike)
    rows = []

    t = time.perf_counter()
    f = on_ground(impact_function(model, args.strike, outputs=INDICATORS), FRICTION, 0.0)
    build = time.perf_counter() - t
    rows.append(("build the indicator Function (SX)", f"{build * 1e3:.1f} ms", ""))
    rows.append(("  its instructions", f"{f.n_instructions()}", ""))

    batch = f.map(args.states, "serial")
    t = time.perf_counter()
    batch_c = external(batch)
    rows.append(("generate + compile the batch (cold cache)", f"{time.perf_counter() - t:.2f} s", ""))
    t = time.perf_counter()
    external(batch)
    rows.append(("load it again (cached)", f"{(time.perf_counter() - t) * 1e3:.1f} ms", ""))
    Xt = ca.DM(X.T)
    batch_c(Xt)
    tb = median_time(lambda: batch_c(Xt), args.repeats)
    rows.append(("batch, compiled + mapped", f"{args.states / tb:,.0f} states/s",
                 f"{tb / args.states * 1e9:.0f} ns/state"))

    single = Compiled(f)
    rows.append(("single state, compiled (buffer)", f"{per_call(single, X[:2000]) * 1e6:.2f} us", ""))
    checked = Impact(model, args.strike, 0.0, FRICTION, compiled=True)
    rows.append(("single state, checked ImpactResult", f"{per_call(checked, X[:2000]) * 1e6:.2f} us",
                 "condition number, warnings"))
    rows.append(("single state, CasADi interpreted", f"{per_call(f, X[:500]) * 1e6:.2f} us", ""))

    x = ca.SX.sym("x", X.shape[1])
    T_c = f(x=x)["T_c"]
    value = ca.Function("T_c_value", [x], [T_c]).map(args.states, "serial")
    grad = ca.Function("T_c_gradient", [x], [T_c, ca.gradient(T_c, x)]).map(args.states, "serial")
    value_c, grad_c = external(value), external(grad)
    value_c(Xt), grad_c(Xt)
    tv = median_time(lambda: value_c(Xt), args.repeats)
    tg = median_time(lambda: grad_c(Xt), args.repeats)
    rows.append(("T_c value, batch", f"{tv / args.states * 1e9:.0f} ns/state", ""))
    rows.append(("T_c value + gradient (10), batch", f"{tg / args.states * 1e9:.0f} ns/state",
                 f"{tg / tv:.2f} x the value"))

    peer = pinocchio_rows(body, model, X[:2000], args.strike)
    print()
    width = max(len(r[0]) for r in rows + peer) + 2
    for name, figure, note in rows + peer:
        print(f"{name:{width}s}{figure:>22s}   {note}")


def pinocchio_rows(body, model, X, strike):
    try:
        import pinocchio as pin
    except ImportError:
        return [("Pinocchio", "not installed", "pip install '.[test]'")]
    from oracle import contact_jacobian, pinocchio_leg, pinocchio_state

    pmodel = pinocchio_leg(body)
    data = pmodel.createData()
    point = "heel" if strike == "flat" else strike
    states = []
    for x in X:
        q_nc, _ = model.state(ca.DM(x), point)
        q, v = pinocchio_state(x, np.asarray(ca.evalf(q_nc), float).ravel()[model.cols("hip")])
        states.append((q, v))

    def one(state):
        q, v = state
        J = contact_jacobian(pmodel, data, q, strike)
        v_after = pin.impulseDynamics(pmodel, data, q, v, J, 0.0, 0.0)
        dv = v - v_after
        M = np.triu(data.M) + np.triu(data.M, 1).T  # crba fills the upper triangle
        return 0.5 * dv @ M @ dv, data.impulse_c

    t = per_call(one, states)
    return [("Pinocchio impulseDynamics + Jacobian + T_c, one state", f"{t * 1e6:.2f} us",
             f"{1 / t:,.0f} states/s (pin {pin.__version__})")]


if __name__ == "__main__":
    main()
