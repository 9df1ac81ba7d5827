"""optim.stride.contact: the NLP's impact rows against formopt's natural-coordinate impact map
at random joint states (an independent method), and the friction cone's side, at an impact
and at a node."""

import casadi as ca
import numpy as np
import pytest
from helpers import SEED

from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.checks import impact_check, joint_impact
from formopt.optim.stride.contact import RigidContact
from formopt.optim.stride.guess import ballistic
from formopt.optim.stride.layout import Rows
from formopt.optim.stride.ocp import Impact
from formopt.optim.stride.problem import APPROACH_SPEED

MU, SLOPE = 0.8, 0.05


@pytest.fixture(scope="module")
def js():
    return JointSpace(paper_body())


@pytest.fixture(scope="module")
def states(js):
    """Touchdown-like joint states: the generic guess's start, angles moved by up to 10 deg and
    rates by up to 2 rad/s, the hip falling at 0.2-1 m/s."""
    nlp = StrideNLP(js, StrideSettings(strike="heel", nodes=14 + 4))
    x0 = ballistic(nlp, 3.5)["X_heel"][:, 0]
    rng = np.random.default_rng(SEED)
    out = []
    for _ in range(12):
        x = x0.copy()
        x[3:9] += rng.uniform(-0.17, 0.17, 6)
        x[12:] += rng.uniform(-2, 2, 6)
        x[10] = -rng.uniform(0.2, 1.0)
        out.append(x)
    return out


def _rows(contact, theta, v_minus, v_plus, p, mass):
    rows = Rows()
    T_c = contact.impact(rows, ca.DM(theta), ca.DM(v_minus), ca.DM(v_plus), ca.DM(p), SLOPE, MU, mass)
    values = np.concatenate([np.asarray(ca.DM(e), float).ravel() for e in rows.expr])
    return values, np.concatenate(rows.lower), np.concatenate(rows.upper), float(T_c)


@pytest.mark.parametrize("rows", [(("heel_R", "t"), ("heel_R", "n")),
                                  (("forefoot_R", "t"), ("forefoot_R", "n"))])
def test_impact_rows_hold_at_the_projection_and_agree_with_the_impact_map(js, states, rows):
    """At each state, the joint-space projection's theta'+ and impulses satisfy every equality
    row of RigidContact.impact to 1e-9, and its T_c equals mechanics.impact.projection's on the
    natural-coordinate model to 1e-9 J."""
    contact, m = RigidContact(js, rows), js.mass_total
    for x in states:
        theta, v_minus = x[:9], x[9:]
        plus, p, _ = joint_impact(js, rows, theta, v_minus, SLOPE)
        values, lower, upper, T_c = _rows(contact, theta, v_minus, plus, p / m, m)
        equal = lower == upper
        assert np.abs(values[equal]).max() < 1e-9
        assert T_c == pytest.approx(impact_check(js, rows, theta, v_minus, SLOPE, MU)["T_c_formopt"], abs=1e-9)


def test_the_cone_holds_an_impulse_inside_and_refuses_one_outside(js, states):
    rows = (("heel_R", "t"), ("heel_R", "n"))
    contact, x = RigidContact(js, rows), states[0]
    for ratio, inside in ((0.5, True), (-0.5, True), (1.5, False), (-1.5, False)):
        values, lower, upper, _ = _rows(contact, x[:9], x[9:], x[9:], [ratio * MU * 0.1, 0.1], js.mass_total)
        cone = np.isinf(upper) & (lower == 0)
        assert np.all(values[cone] >= 0) == inside


def test_the_node_cone_and_the_slide_take_their_sides(js, states):
    """At a node: a sticking force inside the cone passes its rows, outside fails them; a
    sliding point's force is -s mu f_n (its row zero only there)."""
    x = states[0]
    th, thd, a = ca.DM(x[:9]), ca.DM(x[9:]), ca.DM.zeros(9)
    stick = RigidContact(js, (("heel_R", "t"), ("heel_R", "n")))
    for f_t, inside in ((0.3, True), (1.0, False)):
        rows = Rows()
        stick.node(rows, th, thd, a, ca.DM([f_t, 1.0]), SLOPE, MU, js.mass_total)
        values = np.concatenate([np.asarray(e, float).ravel() for e in rows.expr])
        cone = np.isinf(np.concatenate(rows.upper)) & (np.concatenate(rows.lower) == 0)
        clearance = len(stick.free)
        assert np.all(values[cone][clearance:] >= 0) == inside
    slide = RigidContact(js, (("heel_R", "t"), ("heel_R", "n")), sliding="heel_R", slip=1)
    rows = Rows()
    slide.node(rows, th, thd, a, ca.DM([-MU * 1.0, 1.0]), SLOPE, MU, js.mass_total)
    friction_row = [e for e in rows.expr if e.shape[0] == 1][-2]
    assert abs(float(friction_row)) < 1e-12


@pytest.mark.parametrize("rows, swing", [((("heel_R", "t"), ("heel_R", "n")), ("heel_L", "forefoot_L")),
                                         ((("forefoot_R", "t"), ("forefoot_R", "n")), ("heel_L", "forefoot_L")),
                                         ((), ())])
def test_the_swing_leg_has_its_clearance_and_the_rest_the_ground(js, states, rows, swing):
    """While leg R holds the ground, leg L's points are bounded below by the clearance and R's
    free point by the ground; in flight every point by the ground."""
    contact = RigidContact(js, rows, clearance=0.02)
    assert contact.swing == swing
    node = Rows()
    theta = ca.DM(states[0][:9])
    contact.node(node, theta, ca.DM(states[0][9:]), ca.DM.zeros(9), ca.DM.zeros(len(rows)), SLOPE, MU, 70.0)
    lower = np.concatenate(node.lower)[:len(contact.free)]
    assert list(lower) == [0.02 if p in swing else 0.0 for p in contact.free]



@pytest.mark.parametrize("approach", [0.0, APPROACH_SPEED])
def test_an_impact_holds_its_least_approach_speed(js, states, approach):
    """Impact's rows for each point: its height, then its normal velocity before the impact
    with v_n- <= -approach (StrideSettings.approach_speed; 0 allows a grazing touchdown)."""
    rows = (("heel_R", "t"), ("heel_R", "n"))
    theta, v_minus = ca.DM(states[0][:9]), ca.DM(states[0][9:])
    out = Rows()
    Impact(("heel_R",), RigidContact(js, rows), approach).rows(
        out, js, theta, v_minus, v_minus, ca.DM.zeros(2), [3.5, SLOPE, MU], js.mass_total)
    v_n = float(js.points["heel_R"](theta, v_minus, SLOPE)[1][1])
    assert float(out.expr[1]) == pytest.approx(v_n, abs=1e-12)
    assert (out.lower[1].item(), out.upper[1].item()) == (-np.inf, -approach)
