"""The torque rungs' torque-velocity limit (StrideSettings.torque_velocity): each joint's extensor
and flexor moments within limit g(+-theta'/w), g De Groote's f_V floored at zero
(actuation.Torques.rows), against the formula written here; the setting's errors; the NLP's rows and their bounds (derivatives:
test_derivatives.py's moment-dynamics case)."""

import math

import casadi as ca
import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.io.scene import SceneError
from formopt.io.stride_scene import parse
from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JOINTS, JointSpace
from formopt.mechanics.muscles import FORCE_VELOCITY
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.actuation import JOINT_MAX_RATE, VELOCITY_FLOOR, Torques
from formopt.optim.stride.layout import Rows


def f_v(v: float) -> float:
    """De Groote et al. 2016's force-velocity, written again: lengthening positive, v in v_max."""
    d1, d2, d3, d4 = FORCE_VELOCITY
    return d1 * math.log(d2 * v + d3 + math.sqrt((d2 * v + d3) ** 2 + 1)) + d4


def g(v: float) -> float:
    """f_V floored smoothly at zero (past v_max a muscle makes no force; it does not pull back)."""
    return 0.5 * (f_v(v) + math.sqrt(f_v(v) ** 2 + VELOCITY_FLOOR ** 2))


@pytest.mark.parametrize("dynamic", [False, True])
def test_the_limit_is_the_written_formula(dynamic):
    """Rows tau/limit - g(theta'/w) and -tau/limit - g(-theta'/w), both <= 0 (g: f_V floored at
    zero): at rest the limit itself; extending a joint at its w the extensors cannot push
    (g(-1) = 0.01), nor faster; lengthening, g reaches 1.8 at w (the moments' box caps it)."""
    limit, rng = 4.0, np.random.default_rng(7)
    tau, rate = rng.uniform(-3.0, 3.0, 6), rng.uniform(-20.0, 20.0, 9)
    rows = Rows()
    zero = np.zeros(6)
    Torques(62.0, limit, dynamic, velocity=True).rows(rows, np.zeros(9), ca.DM(rate), ca.DM(tau) if dynamic else zero,
                                                      zero if dynamic else ca.DM(tau))
    (expr,), (lower,), (upper,) = rows.expr, rows.lower, rows.upper
    w = np.array([JOINT_MAX_RATE[j[:-2]] for j in JOINTS])
    expected = np.r_[[t / limit - g(r / s) for t, r, s in zip(tau, rate[3:], w)],
                     [-t / limit - g(-r / s) for t, r, s in zip(tau, rate[3:], w)]]
    np.testing.assert_allclose(np.asarray(ca.evalf(expr)).ravel(), expected, rtol=1e-12, atol=1e-12)
    assert (lower == -np.inf).all() and (upper == 0.0).all()
    assert g(0.0) == pytest.approx(1.0, abs=0.005) and abs(g(-1.0)) < 0.02 and g(1.0) == pytest.approx(1.8, abs=0.05)
    assert f_v(-1.5) < -0.05 and 0.0 < g(-1.5) < VELOCITY_FLOOR  # past w: no force, not a pull back


def test_without_the_setting_there_are_no_rows():
    rows = Rows()
    Torques(62.0, 4.0).rows(rows, np.zeros(9), np.zeros(9), np.zeros(6), np.zeros(6))
    assert rows.expr == []


def test_the_nlp_has_two_rows_per_joint_and_node():
    """12 more node rows per column, each <= 0."""
    js = JointSpace(paper_body())
    plain, limited = (StrideNLP(js, StrideSettings(strike="heel", nodes=18, torque_velocity=tv)) for tv in (False, True))
    added = limited.lbg.size - plain.lbg.size
    assert added == 12 * sum(limited.columns)
    assert np.isinf(limited.lbg).sum() - np.isinf(plain.lbg).sum() == added


def test_the_setting_is_for_the_torque_rungs():
    with pytest.raises(InputError, match="torque_velocity"):
        StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", torque_velocity=True)


@pytest.mark.parametrize("edit, message", [({"torque_velocity": 1}, "true or false"),
                                           ({"actuation": "muscles", "torque_velocity": True}, "force-velocity")])
def test_bad_scene_keys_are_named(edit, message):
    toml = {"scene": {"name": "s"}, "ground": {"friction": 0.8}, "stride": {"speed_mps": 3.5, **edit}}
    with pytest.raises(SceneError, match=rf"stride\.torque_velocity.*{message}"):
        parse(toml)


def test_its_stride_says_what_its_mesh_was_measured_to_move():
    """The torque scenes' stride with the limit is not RUNNER_MESH's: its own figures (VELOCITY_MESH)."""
    from formopt.optim.stride.notes import RUNNER_MESH, VELOCITY_MESH, mesh_note
    from formopt.optim.stride.problem import APPROACH_SPEED, MOMENT_TIME, RUNNER_ANKLE, RUNNER_IMPACT_WEIGHT

    runner = dict(transcription="hermite-simpson", tendons=RUNNER_ANKLE, impact_weight=RUNNER_IMPACT_WEIGHT,
                  moment_time=MOMENT_TIME, approach_speed=APPROACH_SPEED)
    assert RUNNER_MESH in mesh_note(StrideSettings(**runner))
    said = mesh_note(StrideSettings(**runner, torque_velocity=True))
    assert VELOCITY_MESH in said and RUNNER_MESH not in said and "other strikes not measured" in said
    other = mesh_note(StrideSettings(**{**runner, "impact_weight": 1.0}, torque_velocity=True))
    assert "not measured on these settings" in other and VELOCITY_MESH not in other
