"""Speed and accuracy of the landing simulation (two impacts and the contact phase between).

    python benchmarks/landing_speed.py [--scene formopt/scenes/landing_spring.toml] [--repeats 20]

Prints, against a reference (RK4 at dt = 12.5 us): for the default integrator (adaptive
Dormand-Prince, tolerance 1e-8, steps up to the scene's dt) and for fixed-step RK4 at
several steps, the error of T_c_total and of the second impact's time and the median time of
one landing after build; the build time; a sweep of 1,000 landings (40 ankle x 25 knee
angles) on 2 worker processes, wall time and how many were valid; and the differentiable
landing (value and gradient of T_c_total). Targets (issue 14): one landing <= 2 ms at the
default accuracy, 1,000 landings <= 10 s on 2 cores. No peer simulates this impact sequence
(Pinocchio has impulseDynamics but no event-driven landing); its impulseDynamics figure is
in impact_speed.py.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import casadi as ca

from formopt import load
from formopt.mechanics.landing import LandingModel, simulate_state
from formopt.mechanics.landing_function import absorbed_function
from formopt.studies import sweep

ROOT = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "formopt" / "scenes" / "landing_spring.toml"))
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    scene = load(args.scene)
    t = time.perf_counter()
    lm = scene.landing(many=True)  # compiled, as a sweep's landings are

    models = {None: lm, "rk4": LandingModel(lm.model, lm.joints, lm.slope, True, "rk4", lm.law)}

    def run(dt, integrator=None):
        return simulate_state(models[integrator], scene.strike, scene.state, scene.friction, dt, 0.2)

    def median_ms(f):
        times = []
        for _ in range(args.repeats):
            t = time.perf_counter()
            f()
            times.append(time.perf_counter() - t)
        return statistics.median(times) * 1e3

    run(scene.integration.dt)
    print(f"{scene.name}; joints {scene.joints.model}; one core\n")
    print(f"build (model, compiled step functions): {time.perf_counter() - t:.2f} s\n")
    ref = run(1.25e-5, "rk4")
    print(f"reference (RK4, dt 12.5 us): T_c_total {ref.T_c_total:.10f} J, second impact at "
          f"{ref.impacts[1].time * 1e3:.6f} ms\n")
    print(f"{'integrator':>22s} {'rel. error T_c_total':>22s} {'error t_e (us)':>15s} {'median time (ms)':>17s}")
    cases = [(f"adaptive (default), {scene.integration.dt * 1e3:g} ms max", scene.integration.dt, None)]
    cases += [(f"rk4, dt {dt * 1e3:g} ms", dt, "rk4") for dt in (1e-3, 5e-4, 2.5e-4, 1.25e-4)]
    for label, dt, integrator in cases:
        result = run(dt, integrator)
        err = abs(result.T_c_total - ref.T_c_total) / ref.T_c_total
        print(f"{label:>22s} {err:22.2e} {abs(result.impacts[1].time - ref.impacts[1].time) * 1e6:15.4f} "
              f"{median_ms(lambda dt=dt, integrator=integrator: run(dt, integrator)):17.2f}")
    with tempfile.TemporaryDirectory() as tmp:
        params = [sweep.parse_param("ankle_deg=-18:-5:40"), sweep.parse_param("knee_deg=8:32:25")]
        t = time.perf_counter()
        rows = sweep.run(scene, params, Path(tmp) / "s.csv", progress=False, workers=2)
        wall = time.perf_counter() - t
        print(f"\nsweep of {len(rows)} landings (ankle -18..-5 x knee 8..32 deg, CSV written as they "
              f"finish) on 2 workers: {wall:.2f} s wall, {sum(sweep.valid(r) for r in rows)} valid, "
              f"{sum(bool(r['error']) for r in rows)} failed")
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
