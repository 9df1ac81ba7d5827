"""The posture optimum: checked independently of IPOPT's own claim."""

import copy
import json
import tomllib
from dataclasses import replace
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from helpers import SHIPPED, assert_nlp_derivatives

from formopt import load, solve
from formopt.cli import main
from formopt.io.scene import parse

DEMO = SHIPPED / "demo_support.toml"
BOUNDED = Path(__file__).with_name("bounded.toml")  # a vertex optimum: multipliers on bounds


@pytest.fixture(scope="module")
def demo():
    scene = load(BOUNDED)
    problem = scene.posture_problem()
    return scene, problem, problem.solve()


def test_demo_converges_to_a_valid_optimum(demo):
    _scene, _problem, opt = demo
    assert opt.success and opt.status == "Solve_Succeeded"
    assert opt.impact.valid
    assert opt.impact.T_c < opt.reference.T_c
    assert opt.objective == pytest.approx(opt.impact.T_c, rel=1e-9)
    assert all(s.converged == (s.status in ("Solve_Succeeded", "Solved_To_Acceptable_Level"))
               for s in opt.starts if s.converged)


def test_feasible_perturbations_do_not_beat_the_optimum(demo):
    _scene, problem, opt = demo
    rng = np.random.default_rng(123)
    u_opt = problem.to_unit(opt.state)
    tried = 0
    for _ in range(3000):
        u = np.clip(u_opt + rng.normal(scale=0.05, size=u_opt.size), 0.0, 1.0)
        g = np.asarray(problem.constraint_function(u, problem.p0), float).ravel()
        if np.all(g >= problem.lbg) and np.all(g <= problem.ubg):
            tried += 1
            value = float(problem.objective_function(u, problem.p0))
            assert value >= opt.objective - 1e-9 * abs(opt.objective)
    assert tried > 50, "the test must try enough feasible neighbours"


def test_nlp_derivatives_match_finite_differences(demo):
    _scene, problem, opt = demo
    rng = np.random.default_rng(4)
    assert_nlp_derivatives(problem, [problem.to_unit(opt.state),
                                     *rng.uniform(0.1, 0.9, (4, len(problem.index)))])


def test_speed_sensitivity_matches_a_resolve(demo):
    """The envelope theorem's dT_c*/dv against re-solving at v +- dv."""
    _scene, problem, opt = demo
    dv = 1e-3
    u0 = problem.to_unit(opt.state)
    values = []
    for v in (problem.p0[0] + dv, problem.p0[0] - dv):
        sol, stats, _ = problem.solve_from(u0, problem.posture.parameters(speed=v, friction=problem.friction))
        assert stats["return_status"] == "Solve_Succeeded"
        values.append(float(sol["f"]) / problem.scale)
    fd = (values[0] - values[1]) / (2 * dv)
    assert fd == pytest.approx(opt.sensitivity["d_objective_d_speed"], rel=1e-3, abs=1e-6)


def test_multipliers_predict_a_moved_bound(demo):
    """Moving an active bound by delta changes the optimum by multiplier * delta."""
    scene, problem, opt = demo
    active = {c.name: c for c in opt.active}
    assert "hip_height_max" in active
    _lo, hi = scene.problem.hip_height
    delta = 1e-4
    moved = copy.copy(problem)
    moved.ubg = problem.ubg.copy()
    k = [r.name for r in problem.records].index("hip_height_max")
    moved.ubg[k] = hi + delta
    sol, stats, _ = moved.solve_from(problem.to_unit(opt.state))
    assert stats["return_status"] == "Solve_Succeeded"
    change = float(sol["f"]) / problem.scale - opt.objective
    assert change == pytest.approx(active["hip_height_max"].multiplier * delta, rel=2e-2)


def test_box_multiplier_predicts_a_moved_bound(demo):
    scene, _problem, opt = demo
    active = {c.name: c for c in opt.active}
    assert "ankle_lower" in active
    delta = 0.01  # deg
    k = scene.problem.variables.index("ankle")
    lower = list(scene.problem.lower)
    lower[k] -= np.radians(delta)
    moved = scene.posture_problem(lower=tuple(lower))
    sol, stats, _ = moved.solve_from(moved.to_unit(opt.state))
    assert stats["return_status"] == "Solve_Succeeded"
    change = float(sol["f"]) / moved.scale - opt.objective
    assert change == pytest.approx(active["ankle_lower"].multiplier * -delta, rel=2e-2)


def test_infeasible_scene_reports_its_status_and_no_optimum():
    data = tomllib.loads(BOUNDED.read_text())
    data["ground"]["friction"] = 0.01  # no posture keeps the foot from slipping
    data["optimize"]["starts"] = 3
    opt = solve(parse(data, "infeasible.toml"))
    assert not opt.success
    assert not any(s.converged for s in opt.starts)
    # IPOPT's own word, from one of the starts, and not a success
    assert opt.status in {s.status for s in opt.starts}
    assert opt.status not in ("Solve_Succeeded", "Solved_To_Acceptable_Level")
    assert opt.active == () and opt.sensitivity == {}
    assert any("not an optimum" in n for n in opt.notes)


def test_a_converged_solution_whose_checks_fail_is_no_optimum_and_says_why(monkeypatch):
    """IPOPT's status is not enough: a solution whose T_c is not the checked impact's within
    solution.AGREE (here the tolerance made negative: every solution fails it) is not a
    success, and the verdict (the headline of `formopt solve`, exit 1) names the check."""
    from formopt.optim import posture

    monkeypatch.setattr(posture, "AGREE", -1.0)
    data = tomllib.loads(BOUNDED.read_text())
    data["optimize"]["starts"] = 1
    opt = solve(parse(data, "bounded.toml"))
    assert not opt.success and opt.status == "Solve_Succeeded"
    assert opt.verdict.startswith("NO OPTIMUM (IPOPT converged, but its T_c ")
    assert "differs from the checked impact's" in opt.verdict
    assert opt.starts[0].rejected and not opt.starts[0].converged
    assert any("rejected: its T_c" in n for n in opt.notes)


def test_cli_solve_json(tmp_path, capsys):
    code = main(["solve", str(DEMO), "--json", "--out", str(tmp_path), "--starts", "3"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["success"] is True
    for key in ("success", "status", "touchdown", "T_c", "impulse", "verdict", "held_by", "terms"):
        assert key in data
    assert set(data["touchdown"]) == {"strike", "hip_velocity", "angles_deg", "angular_velocity_dps"}
    assert data["verdict"] == "interior optimum" and data["held_by"] == []
    assert data["objective"] == pytest.approx(data["terms"]["T_c"] + 0.1 * data["terms"]["support"])
    assert (tmp_path / "posture.png").stat().st_size > 0
    assert json.loads((tmp_path / "result.json").read_text())["T_c"] == data["T_c"]
    assert len(data["starts"]) == 3 and data["seed"] == 0


def test_cli_solve_not_converged_exits_1(tmp_path, capsys):
    text = BOUNDED.read_text().replace("friction = 0.8", "friction = 0.01").replace("starts = 8", "starts = 2")
    path = tmp_path / "scene.toml"
    path.write_text(text)
    assert main(["solve", str(path), "--out", str(tmp_path)]) == 1
    assert "NOT CONVERGED" in capsys.readouterr().out


def test_solve_without_optimize_table_is_bad_input(capsys):
    scene = SHIPPED / "heel_strike.toml"
    assert main(["solve", str(scene)]) == 2
    assert "no [optimize] table" in capsys.readouterr().err


@pytest.mark.parametrize("edit,key", [
    ({"variables": ["kne"]}, "optimize.variables"),
    ({"variables": ["trunk"]}, "optimize.variables"),
    ({"objective": "energy"}, "optimize.objective"),
    ({"bounds_deg": {"knee": [40.0, 10.0]}}, "optimize.bounds_deg.knee"),
    ({"bounds_deg": {"knee": [140.0, 150.0]}}, "optimize.bounds_deg.knee"),
    ({"starts": 0}, "optimize.starts"),
    ({"starts": 2.5}, "optimize.starts"),
    ({"variables": ["omega_thigh"]}, "optimize.bounds_dps.thigh"),
])
def test_bad_optimize_tables(edit, key):
    from formopt import SceneError
    data = tomllib.loads(BOUNDED.read_text())
    data["optimize"].update(edit)
    with pytest.raises(SceneError) as err:
        parse(data)
    assert err.value.key == key


def test_compiled_solver_gives_the_same_optimum(demo, compile_cache, monkeypatch):
    from formopt.mechanics import compiled as libraries

    loaded = []  # the libraries the solver was built from (compiled now or found in the cache)
    compile_ = libraries._compile
    monkeypatch.setattr(libraries, "_compile", lambda *a: loaded.append(compile_(*a)) or loaded[-1])
    scene, problem, opt = demo
    compiled = replace(scene, numerics=replace(scene.numerics, compiled=True)).posture_problem()
    sol, stats, _ = compiled.solve_from(problem.to_unit(opt.state))
    assert stats["return_status"] == "Solve_Succeeded"
    assert float(sol["f"]) / compiled.scale == pytest.approx(opt.objective, rel=1e-9)
    assert [p.name.startswith("touchdown_nlp_") and p.parent == compile_cache and p.exists()
            for p in loaded] == [True], "the solver runs one compiled NLP, kept in the cache"


LANDING = SHIPPED / "landing_optimum.toml"


@pytest.fixture(scope="module")
def landing_optimum():
    """The shipped landing objective's optimum from two of its four starts: all four reach the
    same optimum (0.41726 J, 2026-11-28), and each start costs about 1.2 s of CPU."""
    scene = load(LANDING)
    scene = replace(scene, problem=replace(scene.problem, starts=2))
    return scene, solve(scene)


def test_landing_optimum_agrees_with_the_event_driven_simulation(landing_optimum):
    from helpers import land

    scene, opt = landing_optimum
    assert opt.success and all(s.converged for s in opt.starts)
    simulated = land(replace(scene, state=opt.state))
    assert [e.contact for e in simulated.impacts] == ["forefoot", "heel"]
    assert not simulated.releases
    assert simulated.T_c_total == pytest.approx(opt.objective, rel=1e-3)
    assert simulated.no_slip_held  # contact_friction = true: no slip at impacts or between
    reference = land(scene)
    assert opt.objective < reference.T_c_total


def test_landing_nlp_gradient_matches_finite_differences(landing_optimum):

    scene, _opt = landing_optimum
    problem = scene.posture_problem()
    w0 = problem.start(scene.state)
    w = ca.MX.sym("w", w0.size)
    f = problem.objective_function(w, problem.p0)
    grad = ca.Function("grad", [w], [ca.gradient(f, w)])
    exact = np.asarray(grad(w0), float).ravel()
    h = 1e-6
    for k in range(w0.size):
        e = np.zeros_like(w0)
        e[k] = h
        fd = (float(problem.objective_function(w0 + e, problem.p0)) -
              float(problem.objective_function(w0 - e, problem.p0))) / (2 * h)
        assert fd == pytest.approx(exact[k], rel=1e-5, abs=1e-7)


def test_landing_objective_needs_a_landing_that_happens():
    """With the slower sweep the reference landing pulls the forefoot: said, not optimised."""
    data = tomllib.loads(LANDING.read_text())
    data["touchdown"]["angular_velocity_dps"] = {"thigh": 40.0, "shank": -220.0, "foot": -140.0}
    data["touchdown"]["angles_deg"]["ankle"] = -25.0
    with pytest.raises(ValueError, match="never brings the other foot point down"):
        solve(parse(data, "no-landing.toml"))


def test_angular_velocities_as_variables():
    data = tomllib.loads(BOUNDED.read_text())
    data["optimize"].update({"variables": ["hip", "knee", "omega_shank"],
                             "bounds_dps": {"shank": [-400.0, 0.0]}, "starts": 3})
    scene = parse(data, "rates.toml")
    opt = solve(scene)
    assert opt.success and opt.impact.valid
    omega = np.degrees(opt.state[8])
    assert -400.0 - 1e-6 <= omega <= 1e-6
    assert opt.objective <= opt.reference.T_c


def test_iteration_limit_is_reported_not_claimed():
    data = tomllib.loads(BOUNDED.read_text())
    data["optimize"].update({"max_iterations": 2, "starts": 2})
    opt = solve(parse(data, "limited.toml"))
    assert not opt.success and opt.status == "Maximum_Iterations_Exceeded"
    assert any("iteration limit" in n for n in opt.notes)


def test_every_status_has_a_plain_explanation():
    from formopt.optim.solution import explain
    for status in ("Infeasible_Problem_Detected", "Restoration_Failed", "Maximum_Iterations_Exceeded"):
        assert "IPOPT's documentation" not in explain(status)


def test_the_verdict_does_not_depend_on_the_scale_of_the_weights(demo):
    """The active set is decided on the normalised NLP: bounded.toml's vertex at weights
    1e-12, 1 and 1e6 is held by the same constraints, with multipliers in proportion."""
    _scene, _problem, opt = demo
    for weight in (1e-12, 1.0, 1e6):
        data = tomllib.loads(BOUNDED.read_text())
        data["optimize"]["objective"] = {"T_c": weight}
        scaled = parse(data, "bounded.toml").posture_problem().solve()
        assert scaled.verdict == opt.verdict == (
            "HELD BY approach_forefoot, hip_height_max, ankle_lower")
        np.testing.assert_allclose([c.multiplier / weight for c in scaled.held_by],
                                   [c.multiplier for c in opt.held_by], rtol=1e-6)


@pytest.mark.parametrize("edit, law, strike, key", [
    ({"objective": "T_c_total"}, "coulomb", "forefoot", "ground.contact"),
    ({}, "coulomb", "flat", "ground.contact"),
    ({"max_slip_mps": 1.0}, "no-slip", "forefoot", "optimize.max_slip_mps"),
    ({"gait": {"foot_velocity_mps": 1.0}}, "no-slip", "flat", "optimize.gait.foot_velocity_mps"),
    ({"variables": ["hip", "knee", "ankle"]}, "no-slip", "flat", "optimize.variables"),
])
def test_one_admissibility_rule_for_scenes_and_the_api(edit, law, strike, key):
    """A scene and a PostureProblem built in Python refuse the same law, strike and problem
    with the same words (optim.posture.admissible)."""
    from formopt import SceneError
    from formopt.mechanics.errors import InputError
    from formopt.optim.posture import PostureProblem
    data = tomllib.loads(BOUNDED.read_text())
    data["optimize"].update({"variables": ["hip", "knee"], **edit})
    data["optimize"].pop("hip_height_m")
    data["ground"]["contact"], data["touchdown"]["strike"] = law, strike
    with pytest.raises(SceneError) as from_scene:
        parse(data)
    assert from_scene.value.key == key
    valid = dict(data, ground={**data["ground"], "contact": "no-slip"},
                 touchdown={**data["touchdown"], "strike": "forefoot"},
                 optimize={**data["optimize"], "variables": ["hip", "knee"]})
    valid["optimize"].pop("max_slip_mps", None)
    scene = parse(valid)
    problem = scene.problem
    if "objective" in edit:
        problem = replace(problem, objective={"T_c_total": 1.0})
    if "max_slip_mps" in edit:
        problem = replace(problem, max_slip=1.0)
    if "gait" in edit:
        from formopt.optim.posture import Gait
        problem = replace(problem, gait=Gait(foot_velocity=1.0))
    if edit.get("variables"):
        problem = replace(problem, variables=("hip", "knee", "ankle"),
                          lower=problem.lower + (-0.5,), upper=problem.upper + (0.3,))
    with pytest.raises(InputError) as from_api:
        PostureProblem(scene.model(), strike, scene.state, problem, 0.0, 0.8, law=law)
    assert str(from_api.value) == str(from_scene.value)
