"""Speed and accuracy of the landing simulation (two impacts and the contact phase between).

    python benchmarks/landing_speed.py [--scene problems/landing_spring.toml] [--repeats 20]

Prints, against a reference at dt = 12.5 us: the error of T_c_total and of the second
impact's time for each step size, the median time of one landing after build, the build time,
a 41-point ankle sweep, and the differentiable landing (value and gradient of T_c_total).
No peer simulates this impact sequence (Pinocchio has impulseDynamics but no event-driven
landing); its impulseDynamics figure is in impact_speed.py.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import casadi as ca

from formopt import load
from formopt.studies import sweep
from formopt.mechanics.landing import absorbed_function, simulate_state

ROOT = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "problems" / "landing_spring.toml"))
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    scene = load(args.scene)
    t = time.perf_counter()
    lm = scene.landing()

    def run(dt):
        return simulate_state(lm, scene.strike, scene.state, scene.friction, dt, 0.2)

    run(2e-4)
    print(f"{scene.name}; joints {scene.joints.model}; one core\n")
    print(f"build (model, compiled step functions): {time.perf_counter() - t:.2f} s\n")
    ref = run(1.25e-5)
    print(f"reference (dt 12.5 us): T_c_total {ref.T_c_total:.10f} J, second impact at "
          f"{ref.impacts[1].time * 1e3:.6f} ms\n")
    print(f"{'dt (ms)':>8s} {'rel. error T_c_total':>22s} {'error t_e (us)':>15s} {'median time (ms)':>17s}")
    for dt in (1e-3, 5e-4, 2.5e-4, 1.25e-4):
        result = run(dt)
        times = []
        for _ in range(args.repeats):
            t = time.perf_counter()
            run(dt)
            times.append(time.perf_counter() - t)
        err = abs(result.T_c_total - ref.T_c_total) / ref.T_c_total
        print(f"{dt * 1e3:8.4f} {err:22.2e} {abs(result.impacts[1].time - ref.impacts[1].time) * 1e6:15.4f} "
              f"{statistics.median(times) * 1e3:17.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        t = time.perf_counter()
        sweep.run(scene, [sweep.parse_param("ankle_deg=-20:20:41")], Path(tmp) / "s.csv", progress=False)
        print(f"\n41-point ankle sweep (dt {scene.integration.dt * 1e3:g} ms, with its CSV): "
              f"{time.perf_counter() - t:.3f} s")
    t = time.perf_counter()
    absorbed = absorbed_function(lm, scene.strike, ref.impacts[1].time, steps=60)
    x = ca.MX.sym("x", len(scene.state))
    gradient = ca.Function("gradient", [x], [ca.gradient(absorbed(x)[0], x)])
    build = time.perf_counter() - t
    value_t, grad_t = [], []
    for _ in range(args.repeats):
        t = time.perf_counter()
        absorbed(scene.state)
        value_t.append(time.perf_counter() - t)
        t = time.perf_counter()
        gradient(scene.state)
        grad_t.append(time.perf_counter() - t)
    print(f"differentiable landing (60 RK4 steps, Newton on the event time): build {build:.2f} s, "
          f"value {statistics.median(value_t) * 1e3:.1f} ms, gradient {statistics.median(grad_t) * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
