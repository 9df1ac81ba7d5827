"""The model ladder, coarse to fine, on one code path (design.md section 3)."""

import math
import tomllib

import numpy as np
import pytest
from helpers import ROOT, land, random_states, touchdown

from formopt import Impact, SceneError, impact, load
from formopt.io.scene import parse
from formopt.mechanics.angular_momentum import angular_momentum_impact
from formopt.mechanics.model import Swing, build_model

FULL = ROOT / "formopt" / "studies" / "data" / "full_body.toml"
SWING = Swing(math.radians(-10), math.radians(80), 0.0, math.radians(400), 0.0, 0.0)


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
def test_effective_mass_is_one_vertical_degree_of_freedom(body, leg, strike):
    model = build_model(body, "effective-mass", strike)
    assert model.n == 2 and len(model.guides) == 1
    m = body["shank"].mass + body["foot"].mass
    impact = Impact(model, strike, 0.0, 0.8)
    for x in random_states(20, strike=strike):
        r = impact(x)
        _, qd = leg.state_numeric(x, strike)
        v_z = qd[leg.cols(strike)][1]
        assert r.T_c == pytest.approx(0.5 * m * v_z**2, rel=1e-12)  # it stops completely
        assert r.T_a == pytest.approx(0.0, abs=1e-12) and r.impulse_total[0] == 0.0


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
def test_full_body_invariants_and_angular_momentum(body, strike):
    model = build_model(body, "full-body", strike, SWING)
    assert model.n == 20 and len(model.bodies) == 7
    impact_map = Impact(model, strike, 0.0, 0.8)
    for x in random_states(15, seed=9, strike=strike):
        r = impact_map(x)
        assert abs(r.T_c + r.T_a - r.T) <= 1e-10 * r.T and r.T_c >= 0
        if strike != "flat":  # a tree: one equation per branch beyond each hinge
            q, qd = model.state_numeric(x, strike)
            qd_plus = angular_momentum_impact(model, q, qd, strike)
            assert np.max(np.abs(qd_plus - r.qd_plus)) <= 1e-9 * np.max(np.abs(qd))


def test_full_body_kinetic_energy_adds_the_swing_leg(body):
    """The swing chain carries the swing leg's mass: T exceeds the rigid-trunk model's by the
    swing leg's own kinetic energy (its point mass at the hip moved with the hip)."""
    x = touchdown()
    full = Impact(build_model(body, "full-body", "forefoot", SWING), "forefoot", 0.0, 0.8)(x)
    trunk = Impact(build_model(body, "leg-trunk"), "forefoot", 0.0, 0.8)(x)
    assert full.T > trunk.T  # the swing thigh's 400 deg/s adds energy
    assert full.T_c == pytest.approx(trunk.T_c, rel=0.02)  # free hinges: the foot's impact barely reaches it


def test_full_body_scene_and_landing():
    scene = load(FULL)
    assert scene.swing is not None and scene.model().kind == "full-body"
    L = land(scene)
    assert L.energy_error < 1e-6 and L.impacts[0].contact == "forefoot"
    assert L.impacts[0].T_c == pytest.approx(impact(scene).T_c, rel=1e-10)


def test_full_body_needs_the_swing_posture():
    data = tomllib.loads(FULL.read_text())
    del data["touchdown"]["swing_angles_deg"]
    with pytest.raises(SceneError) as err:
        parse(data)
    assert err.value.key == "touchdown.swing_angles_deg"


def test_effective_mass_is_impact_only():
    data = tomllib.loads(FULL.read_text())
    data["scene"]["model"] = "effective-mass"
    with pytest.raises(SceneError, match="impact-only"):
        parse(data)
    del data["joints"]
    scene = parse(data)
    assert impact(scene).T_c > 0
    with pytest.raises(ValueError, match="impact-only"):
        land(scene)


def test_the_ladder_on_one_touchdown(body):
    """Every level gives a finite, valid-to-compute T_c for the same touchdown."""
    x = touchdown(trunk=5.0, hip=25.0, knee=15.0, ankle=-12.0, v=(3.5, -0.7), w=(0.0, 40.0, -220.0, -140.0))
    values = {kind: Impact(build_model(body, kind, "forefoot", SWING), "forefoot", 0.0, 0.8)(x).T_c
              for kind in ("effective-mass", "shank-foot", "leg", "leg-trunk", "full-body")}
    assert all(v > 0 and np.isfinite(v) for v in values.values())
    assert values["leg"] == pytest.approx(values["full-body"], rel=0.01)
