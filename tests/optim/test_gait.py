"""The gait-anchored optimum (formopt/scenes/demo_support.toml): the gait held to 1e-9 m, the optimum
interior and confirmed by a brute-force scan and 3,000 feasible perturbations, its
multipliers and sensitivities against re-solves, its posture free of the weights' scale."""

import copy
import math
import tomllib
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from helpers import SHIPPED, assert_nlp_derivatives

from formopt import load, solve
from formopt.io.scene import parse
from formopt.mechanics.model import STATE

DEMO = SHIPPED / "demo_support.toml"
HIP, KNEE, ANKLE = (STATE.index(k) for k in ("hip", "knee", "ankle"))


@pytest.fixture(scope="module")
def demo():
    scene = load(DEMO)
    problem = scene.posture_problem()
    return scene, problem, problem.solve()


def edited(**optimize):
    data = tomllib.loads(DEMO.read_text())
    data["optimize"].update(optimize)
    return parse(data, "edited.toml")


def on_gait(problem, x, ankles) -> list:
    """x with each of `ankles` set and hip and knee moved (Newton) back onto the gait's
    placement, or None where the placement is out of the leg's reach at that ankle angle (one
    mapped call for them all)."""
    newton, F = _gait_newton(problem)
    n = len(ankles)
    args = (np.tile(x[[HIP, KNEE]][:, None], n), np.tile(np.asarray(x, float)[:, None], n), np.reshape(ankles, (1, n)))
    hk = np.asarray(newton.map(n)(*args), float)
    reached = np.all(np.abs(np.asarray(F.map(n)(hk, *args[1:]), float)) < 1e-10, axis=0)
    out = []
    for k in range(n):
        moved = np.array(x, float)
        moved[HIP], moved[KNEE], moved[ANKLE] = hk[0, k], hk[1, k], ankles[k]
        out.append(moved if reached[k] else None)
    return out


_NEWTONS: dict = {}


def _gait_newton(problem):
    """The placement's residual F(hip and knee, state, ankle) and its Newton solver, built once
    per problem (each scan maps them over its thousands of ankle angles: on_gait)."""
    if id(problem) not in _NEWTONS:
        u, x, ankle = ca.SX.sym("u", 2), ca.SX.sym("x", len(STATE)), ca.SX.sym("ankle")
        state = ca.vertcat(*[u[0] if k == HIP else u[1] if k == KNEE else ankle if k == ANKLE else x[k]
                             for k in range(len(STATE))])
        g = [r.expression for r in problem.records if r.name.startswith("hip_from_strike")]
        target = np.array([r.bound for r in problem.records if r.name.startswith("hip_from_strike")])
        residual = ca.Function("r", [problem.nlp["x"], problem.nlp["p"]], [ca.vertcat(*g)])
        w = ca.vertcat(*[(state[i] - lo) / (hi - lo) for i, lo, hi in zip(
            problem.index, problem.posture.lower, problem.posture.upper)])
        F = ca.Function("F", [u, x, ankle], [residual(w, problem.p0) - target])
        # at most 50 Newton steps: the default 1,000 were spent on the angles out of the leg's
        # reach (the scans' 6,000 angles: the same 5,002 reached, to the bit, in half the CPU)
        newton = ca.rootfinder("newton", "newton", F, {"abstol": 1e-13, "error_on_fail": False, "max_iter": 50})
        _NEWTONS[id(problem)] = (newton, F, problem)
    return _NEWTONS[id(problem)][:2]


def test_the_gait_is_held_and_the_optimum_is_interior(demo):
    scene, problem, opt = demo
    assert opt.success and opt.impact.valid
    assert opt.verdict == "interior optimum" and opt.held_by == ()
    held = {c.name: c for c in opt.active if c.equality}
    assert set(held) == {"hip_from_strike_x", "hip_from_strike_z"}
    placement = problem.hip_from_strike(scene.state)
    for (name, c), target in zip(sorted(held.items()), placement):
        assert c.bound == pytest.approx(target, abs=1e-15)
        assert abs(c.value - target) <= 1e-9, name
    assert np.allclose(problem.hip_from_strike(opt.state), placement, atol=1e-9, rtol=0)
    assert np.allclose(opt.state[4:], scene.state[4:])  # hip velocity and segment rates held
    assert opt.power == pytest.approx(opt.saving * scene.problem.gait.cadence_spm / 60)  # J/step -> W


def test_a_brute_force_scan_of_the_free_angle_confirms_the_optimum(demo):
    """The leg has one free angle under the gait: scan the ankle in 0.02 deg steps."""
    _scene, problem, opt = demo
    best = math.inf
    for x in on_gait(problem, opt.state, np.radians(np.arange(-40.0, 0.0, 0.02))):
        if x is not None and problem.feasible(w := problem.start(x)):
            best = min(best, float(problem.objective_function(w, problem.p0)))
    assert best >= opt.objective - 1e-9
    assert best <= opt.objective + 1e-4  # the scan's resolution


def test_feasible_perturbations_do_not_beat_the_optimum(demo):
    _scene, problem, opt = demo
    rng = np.random.default_rng(12)
    tried = 0
    deltas = rng.normal(scale=3.0, size=4000)  # deg of ankle, hip and knee back on the gait
    for x in on_gait(problem, opt.state, opt.state[ANKLE] + np.radians(deltas)):
        if tried == 3000:
            break
        if x is not None and problem.feasible(w := problem.start(x)):
            tried += 1
            assert float(problem.objective_function(w, problem.p0)) >= opt.objective - 1e-10
    assert tried >= 3000


def test_nlp_derivatives_match_finite_differences(demo):
    _scene, problem, opt = demo
    rng = np.random.default_rng(5)
    assert_nlp_derivatives(problem, [problem.to_unit(opt.state),
                                     *rng.uniform(0.1, 0.9, (3, problem.posture.size))], h=1e-6)


def test_the_hip_height_multiplier_predicts_a_re_solve(demo):
    scene, problem, opt = demo
    held = {c.name: c for c in opt.active}
    x, z = problem.hip_from_strike(scene.state)
    dz = 1e-4
    moved = edited(gait={"cadence_spm": 171.4, "hip_from_strike_m": [x, z + dz]}).posture_problem()
    sol, stats, _ = moved.solve_from(problem.to_unit(opt.state))
    assert stats["return_status"] == "Solve_Succeeded"
    change = float(moved.objective_function(sol["x"], moved.p0)) - opt.objective
    assert change == pytest.approx(held["hip_from_strike_z"].multiplier * dz, rel=1e-2)


def test_posture_sensitivity_to_speed_and_friction_matches_re_solves(demo):
    _scene, problem, opt = demo
    u0 = problem.to_unit(opt.state)
    for k, name in enumerate(("speed", "friction")):
        h = 1e-4
        moved = []
        for sign in (1, -1):
            p = problem.p0.copy()
            p[k] += sign * h
            sol, stats, _ = problem.solve_from(u0, p)
            assert stats["return_status"] == "Solve_Succeeded"
            moved.append(problem.to_state(np.asarray(sol["x"]).ravel(), p)[problem.index])
        fd = np.degrees((moved[0] - moved[1]) / (2 * h))
        kkt = np.array(list(opt.sensitivity[f"d_posture_d_{name}_deg"].values()))
        np.testing.assert_allclose(kkt, fd, rtol=1e-3, atol=1e-3)


@pytest.mark.parametrize("scale", [1e-12, 1e6])
def test_the_optimum_does_not_depend_on_the_weights_scale(demo, scale):
    _scene, _problem, opt = demo
    scaled = solve(edited(objective={"T_c": scale, "support": 0.1 * scale}))
    assert scaled.success and scaled.verdict == opt.verdict
    np.testing.assert_allclose(scaled.state, opt.state, atol=1e-9)
    assert scaled.objective == pytest.approx(scale * opt.objective, rel=1e-9)


def test_a_tiny_weight_on_T_c_alone_finds_the_same_optimum():
    """The issue's case: objective = { T_c = 1e-12 } stopped at 2.12 J against 0.921 J."""
    data = tomllib.loads((Path(__file__).with_name("bounded.toml")).read_text())
    optima = []
    for weight in (1e-12, 1.0):
        d = copy.deepcopy(data)
        d["optimize"]["objective"] = {"T_c": weight}
        opt = solve(parse(d, "bounded.toml"))
        assert opt.success
        optima.append(opt)
    # the same optimum at both weights (the bug stopped the tiny weight at 2.12 J, above it)
    assert optima[0].impact.T_c == pytest.approx(optima[1].impact.T_c, rel=1e-9)
    np.testing.assert_allclose(optima[0].state, optima[1].state, atol=1e-9)


def test_local_mode_reports_marginal_values_and_the_saving():
    scene = edited(around="reference", radius_deg=5.0, starts=2)
    problem = scene.posture_problem()
    opt = problem.solve()
    assert opt.success and opt.local is not None and opt.local.radius_deg == 5.0
    reached = np.degrees(opt.state[problem.index] - scene.state[problem.index])
    assert np.sum(reached ** 2) <= 25.0 * (1 + 1e-6)
    assert opt.saving >= 0
    w0 = problem.start(scene.state)
    for k, name in enumerate(problem.problem.variables):  # J per deg, against differences
        e = np.zeros_like(w0)
        e[k] = 1e-6
        fd = (float(problem.objective_function(w0 + e, problem.p0))
              - float(problem.objective_function(w0 - e, problem.p0))) / 2e-6 / problem.posture.per_unit()[k]
        assert opt.local.marginal[name] == pytest.approx(fd, rel=1e-5, abs=1e-9)


def test_support_term_is_the_elastic_energy_of_the_joint_moments(demo):
    from formopt.mechanics.landing import RUNNING_JOINTS
    from formopt.optim.objective import support_moments

    scene, _problem, opt = demo
    moments = {j: abs(float(m)) for j, m in
               support_moments(ca.DM(opt.state), scene.model(), "forefoot").items()}
    mass = scene.body.mass
    energy = sum(m ** 2 / (2 * RUNNING_JOINTS["stiffness"][j] * mass * 180 / math.pi)
                 for j, m in moments.items())
    assert opt.terms["support"] == pytest.approx(energy, rel=1e-12)
    assert 0 < moments["knee"] < 3.0 * mass and 0 < moments["ankle"] < 3.0 * mass  # below 3 N m/kg


@pytest.mark.parametrize("edit, key", [
    ({"gait": {"hip_from_strike_m": [0.3]}}, "optimize.gait.hip_from_strike_m"),
    ({"gait": {"cadence": 170}}, "optimize.gait"),
    ({"around": "optimum"}, "optimize.around"),
    ({"radius_deg": -1.0}, "optimize.radius_deg"),
])
def test_bad_gait_tables(edit, key):
    from formopt import SceneError
    with pytest.raises(SceneError) as err:
        edited(**edit)
    assert err.value.key.startswith(key)
