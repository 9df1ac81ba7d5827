"""Joints that carry a runner: the flexion signs, the preload, torque joints, the running
defaults measured from RBDS001, stiff joints integrated or refused, and no foot point through
the floor over hundreds of random landings."""

import math
import runpy

import numpy as np
import pytest
from helpers import PROBLEMS, SEED, SHIPPED, random_states

from formopt import load
from formopt.cli import main
from formopt.mechanics.dynamics import FLEXION
from formopt.mechanics.landing import RUNNING_JOINTS, Diverged, Joints, LandingModel, simulate_state
from formopt.mechanics.model import STATE

SPRING = SHIPPED / "landing_spring.toml"
ENDS = ("heel and forefoot both down", "duration reached", "contact chatter")


@pytest.fixture(scope="module")
def spring():
    return load(SPRING)


def landing(scene, joints, integrator="adaptive", dt=1e-3, state=None, strike=None, law="no-slip"):
    """One landing, its functions interpreted: compiling them costs more than the landing (21 C
    builds in this file); compiled against interpreted is compared in studies/test_bench.py (one scene)."""
    lm = LandingModel(scene.model(), joints, scene.slope, False, integrator, law)
    return simulate_state(lm, strike or scene.strike, scene.state if state is None else state,
                          scene.friction, dt, 0.2)


@pytest.mark.parametrize("kind", ["leg", "full-body"])
def test_flexion_signs_follow_the_touchdown_angles(spring, kind):
    """d(hinge angle)/d(joint angle of model.STATE) is the sign FLEXION says: knee and ankle
    on the paper's leg, and the hip too where the trunk is a rigid body (full body)."""
    from formopt.mechanics.model import Swing, build_model

    model = spring.model() if kind == "leg" else build_model(
        spring.body, "full-body", spring.strike, Swing(0.3, 0.5, 0.0, 0.0, 0.0, 0.0))
    lm = LandingModel(model, Joints("spring-damper"))
    assert kind == "leg" or "hip" in [name for name, _, _ in lm.hinges]
    for k, (name, _, _) in enumerate(lm.hinges):
        if name not in STATE:  # the swing leg's joints are not in the touchdown state
            continue
        i = STATE.index(name)
        step = np.zeros(len(STATE))
        step[i] = 1e-6
        angles = [lm.joint_angles(model.state_numeric(spring.state + s * step, "forefoot")[0])
                  for s in (-1, 1)]
        assert np.sign((angles[1][k] - angles[0][k]) / 2e-6) == FLEXION[name]


def test_a_constant_moment_table_is_a_preload_without_a_spring(spring):
    """Two routes to the same mechanics: torque joints holding M constant over time, and a
    spring-damper with k = c = 0 and preload M."""
    moments = {"knee": 30.0, "ankle": 8.0}  # extensor and plantarflexor: the foot pressed down
    spring_form = landing(spring, Joints("spring-damper", {"knee": 0.0, "ankle": 0.0},
                                         {"knee": 0.0, "ankle": 0.0}, preload=moments))
    table = landing(spring, Joints("torque", times=(0.0, 0.1, 0.25),
                                   moments={j: (m, m, m) for j, m in moments.items()}))
    assert [e.contact for e in table.impacts] == [e.contact for e in spring_form.impacts]
    assert table.T_c_total == pytest.approx(spring_form.T_c_total, rel=1e-8)
    assert table.energy_error < 1e-6 and spring_form.energy_error < 1e-6


def test_a_moment_that_varies_in_time_keeps_the_energy_balance(spring):
    """Work done by a time-varying moment enters the balance (what the joints take)."""
    L = landing(spring, Joints("torque", times=(0.0, 0.02, 0.05, 0.2),
                               moments={"knee": (20.0, 60.0, 120.0, 0.0),
                                        "ankle": (5.0, 40.0, 80.0, 0.0)}))
    assert L.energy_error < 1e-6
    assert np.any(np.abs(np.diff(L.dissipated)) > 1e-3)  # the moments did work


def test_preload_pushes_the_strike_point_harder(spring):
    """An extensor knee and a plantarflexor ankle held at touchdown press the forefoot down."""
    free = landing(spring, Joints("spring-damper", {"knee": 500.0, "ankle": 350.0}, {"knee": 3.0, "ankle": 3.0}))
    pressed = landing(spring, Joints("spring-damper", {"knee": 500.0, "ankle": 350.0},
                                     {"knee": 3.0, "ankle": 3.0}, preload={"knee": 40.0, "ankle": 40.0}))
    after = [np.nanmax(L.force[1:6, 1]) for L in (free, pressed)]
    assert after[1] > after[0] + 50.0


def test_running_defaults_are_the_ones_measured_from_rbds001():
    script = runpy.run_path(str(PROBLEMS / "joint_stiffness.py"))  # reads data/rbds
    measured = script["measure"]()["35"]
    for joint in ("knee", "ankle"):
        assert RUNNING_JOINTS["stiffness"][joint] == pytest.approx(measured[joint]["stiffness"], abs=0.001)
        assert RUNNING_JOINTS["preload"][joint] == pytest.approx(measured[joint]["preload"], abs=0.005)
        assert measured[joint]["r"] > 0.99


def test_scene_defaults_scale_with_body_mass(spring):
    scene = load(SHIPPED / "forefoot_strike.toml")  # no [joints]: the running joints
    mass = scene.body.mass
    assert scene.joints.model == "spring-damper"
    assert math.radians(scene.joints.stiffness["knee"]) == pytest.approx(RUNNING_JOINTS["stiffness"]["knee"] * mass)
    assert scene.joints.preload["ankle"] == pytest.approx(RUNNING_JOINTS["preload"]["ankle"] * mass)


def test_stiff_damping_is_integrated_by_the_adaptive_scheme_and_refused_by_the_fixed_one(spring):
    """Knee damping of 70 N m s/deg (the issue's case, beyond the scene limit): the adaptive
    integrator shortens its steps and keeps the balance; RK4 at 0.2 ms raises Diverged."""
    stiff = Joints("spring-damper", {"knee": math.degrees(5.0), "ankle": math.degrees(7.0)},
                   {"knee": math.degrees(70.0), "ankle": math.degrees(0.1)})
    L = landing(spring, stiff)
    assert np.all(np.isfinite(L.energy)) and L.energy_error < 1e-5
    assert L.ended == "heel and forefoot both down"
    with pytest.raises(Diverged, match=r"diverged at .* ms"):
        landing(spring, stiff, integrator="rk4", dt=2e-4)


def test_a_diverged_landing_exits_1_with_its_reason(tmp_path, capsys):
    text = SPRING.read_text().replace("[landing]", "[numerics]\nintegrator = \"midpoint\"\n\n[landing]\ndt_ms = 5.0")
    text = text.replace("stiffness_nm_per_deg = { knee = 9.49, ankle = 6.06 }",
                        "stiffness_nm_per_deg = { knee = 73.0, ankle = 73.0 }")
    scene = tmp_path / "stiff.toml"
    scene.write_text(text)
    assert main(["simulate", str(scene), "--out", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert "diverged" in err and "adaptive" in err and "Traceback" not in err


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
def test_no_foot_point_below_the_ground_in_random_landings(spring, strike):
    """252 landings in all (3 joint models x 2 strikes x 42 random touchdowns, seeded): no
    recorded sample has a foot point below -1e-6 m, and each ends for a named reason. The
    functions are interpreted (compiled against interpreted: studies/test_bench.py, one scene),
    and compiling them would cost more than these landings."""
    model = spring.model()
    joints = (Joints("free"), spring.joints, Joints("locked", locked=("knee", "ankle")))
    models = [LandingModel(model, j, 0.0, False, "adaptive", "no-slip") for j in joints]
    other = "heel" if strike == "forefoot" else "forefoot"
    count = 0
    for x in random_states(400, seed=SEED + (strike == "heel"), strike=strike):
        q, _ = model.state_numeric(x, strike)
        if q[model.cols(other)][1] < 1e-3:  # the other point must start above the ground
            continue
        for lm in models:
            L = simulate_state(lm, strike, x, 0.8, 1e-3, 0.1)
            low = min(min(q[model.cols(p)][1] for p in ("heel", "forefoot")) for q in L.q)
            assert low > -1e-6, f"{lm.joints.model}: {low:.2e} m ({L.ended})"
            assert L.ended.startswith(ENDS)
            count += 1
        if count >= 126:
            break
    assert count >= 126
