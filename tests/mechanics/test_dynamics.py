"""dynamics.py: the motion per contact set against physics it must obey (the centre of mass
falls at g in flight, joint moments are internal, the energy rate is minus the power taken, a
held point does not accelerate, kinetic friction opposes sliding) and its interface."""

import casadi as ca
import numpy as np
import pytest
from helpers import SHIPPED, random_states

from formopt import load
from formopt.mechanics import dynamics
from formopt.mechanics.dynamics import FEET, GRAVITY, Dynamics, Joints
from formopt.mechanics.landing import LandingModel
from formopt.optim import objective

SETS = [((), False), (("forefoot",), False), (("heel",), False), (("heel", "forefoot"), False),
        (("forefoot",), True), (("heel", "forefoot"), True)]


@pytest.fixture(scope="module")
def spring():
    scene = load(SHIPPED / "landing_spring.toml")
    return scene, Dynamics(scene.model(), scene.joints, scene.slope)


def evaluate(dyn, active, sliding, q, qd, moments=None, friction=0.3):
    joint = dyn.joint_parameters(q) * 1.0
    joint[:len(dyn.hinges)] -= 0.05  # the springs away from their rest angles
    anchor = float(q[dyn.model.cols(active[0])] @ dyn.t_axis) if active else 0.0
    moments = np.zeros(len(dyn.hinges)) if moments is None else moments
    out = dyn.motion(active, sliding)(q=q, qd=qd, s_anchor=anchor, joint=joint, friction=friction,
                                     t=0.0, moments=moments)
    return {k: np.asarray(v, float).ravel() for k, v in out.items()}, joint, anchor


def touchdown(scene, dyn, x):
    return dyn.model.state_numeric(x, "forefoot")


def test_gravity_has_one_home():
    assert objective.GRAVITY is dynamics.GRAVITY


def test_flight_centre_of_mass_falls_at_g_whatever_the_joint_moments(spring):
    """In flight the whole body's centre of mass accelerates at (0, -g): springs, dampers and
    applied joint moments are internal forces (A q'' / m, A the momentum matrix)."""
    scene, dyn = spring
    m = dyn.model
    rng = np.random.default_rng(1)
    for x in random_states(5, seed=4):
        q, qd = touchdown(scene, dyn, x)
        out, _, _ = evaluate(dyn, (), False, q, qd, moments=rng.normal(0, 100, len(dyn.hinges)))
        com = m.momentum_matrix @ out["qdd"] / m.body.mass
        assert com == pytest.approx([0.0, -GRAVITY], abs=1e-6)


@pytest.mark.parametrize("active,sliding", SETS)
def test_energy_rate_is_minus_the_power_taken(spring, active, sliding):
    """dE/dt = (dE/dq) q' + (dE/dq') q'' = -power for E = T + V_g + V_springs: the dampers,
    the applied moments and sliding friction take `power`; the rows do no work when q' meets
    them (Phi_q q' = 0: q' projected by the no-slip impact map for a held set, the
    frictionless one, normal rows only, for a sliding set; Baumgarte's terms do no work)."""
    scene, dyn = spring
    n, h = dyn.model.n, len(dyn.hinges)
    q_s, qd_s, j_s = ca.SX.sym("q", n), ca.SX.sym("qd", n), ca.SX.sym("j", 4 * h)
    E = dyn.energy(q_s, qd_s, j_s)
    grad = ca.Function("grad", [q_s, qd_s, j_s], [ca.gradient(E, q_s), ca.gradient(E, qd_s)])
    law = "frictionless" if sliding else "no-slip"
    lm = LandingModel(dyn.model, dyn.joints, dyn.slope, False, "adaptive", law)
    for x in random_states(3, seed=5):
        q, qd = touchdown(scene, dyn, x)
        if active:
            qd = np.asarray(lm.impact_map(active)(q, qd, dyn.joint_parameters(q), 0.8)[0]).ravel()
        out, joint, _ = evaluate(dyn, active, sliding, q, qd, moments=np.full(h, 20.0))
        g_q, g_qd = (np.asarray(v, float).ravel() for v in grad(q, qd, joint))
        rate = g_q @ qd + g_qd @ out["qdd"]
        assert abs(out["power"][0]) > 1.0  # something is taken
        assert rate == pytest.approx(-out["power"][0], rel=1e-8, abs=1e-8)


def test_equations_of_motion_hold(spring):
    """M q'' = Q + F^T lambda and Phi_q q'' = gamma, rebuilt from the returned multipliers with
    an independent Jacobian (finite differences of the constraint rows)."""
    scene, dyn = spring
    m = dyn.model
    q, qd = touchdown(scene, dyn, scene.state)
    active = ("forefoot",)
    out, joint, anchor = evaluate(dyn, active, False, q, qd)
    phi = ca.Function("phi", [q_s := ca.SX.sym("q", m.n)],
                      [dyn.constraints(q_s, active, anchor, joint)])
    h = 1e-6
    Phi = np.column_stack([(np.asarray(phi(q + h * e)) - np.asarray(phi(q - h * e))).ravel() / (2 * h)
                           for e in np.eye(m.n)])
    # the forces: gravity and the springs' and dampers' J^T tau (the landing's own pieces)
    Q = np.asarray(ca.Function("Q", [q_s], [dyn.joint_forces(q_s, ca.DM(qd), ca.DM(joint), 0)[0]])(q),
                   float).ravel() + dyn.gravity
    assert m.M @ out["qdd"] == pytest.approx(Q + Phi.T @ out["lambda"], abs=1e-5)


def test_a_held_point_does_not_accelerate(spring):
    """After a no-slip impact the forefoot is at rest on the ground (Phi = 0, Phi_q q' = 0),
    so the contact rows give it no acceleration, tangential or normal."""
    scene, dyn = spring
    lm = LandingModel(dyn.model, dyn.joints, dyn.slope, False, "adaptive", "no-slip")
    q, qd = touchdown(scene, dyn, scene.state)
    qd = np.asarray(lm.impact_map(("forefoot",))(q, qd, dyn.joint_parameters(q), 0.8)[0]).ravel()
    out, _, _ = evaluate(dyn, ("forefoot",), False, q, qd)
    for axis in (dyn.t_axis, dyn.n_axis):
        assert float(dyn.contact_row("forefoot", axis) @ out["qdd"]) == pytest.approx(0.0, abs=1e-8)


def test_kinetic_friction_opposes_the_slide(spring):
    """A sliding point: f_t = -mu s f_n (friction = mu s), and the normal row still holds."""
    scene, dyn = spring
    q, qd = touchdown(scene, dyn, scene.state)
    out, _, _ = evaluate(dyn, ("forefoot",), True, q, qd, friction=0.5)
    assert out["force"][0] == pytest.approx(-0.5 * out["force"][1])
    assert out["force"][1] == pytest.approx(out["normal"][0])


def test_heights_and_rows(spring):
    scene, dyn = spring
    q, _ = touchdown(scene, dyn, scene.state)
    heights = np.asarray(dyn.heights(q), float).ravel()
    for k, p in enumerate(FEET):
        assert heights[k] == pytest.approx(float(dyn.contact_row(p, dyn.n_axis) @ q))
    assert heights[1] == pytest.approx(0.0, abs=1e-12)  # the forefoot strikes


def test_motion_interface_names(spring):
    """The Function a collocation scheme calls: inputs and outputs by name, one per set."""
    _, dyn = spring
    f = dyn.motion(("heel",))
    assert f.name_in() == ["q", "qd", "s_anchor", "joint", "friction", "t", "moments"]
    assert f.name_out() == ["qd_out", "qdd", "lambda", "power", "force", "normal", "slip",
                            "residual", "energy"]
    assert f.size_in("moments") == (len(dyn.hinges), 1)
    assert dyn.motion(("heel",)) is f  # built once per contact set


def test_bad_joint_model(spring):
    scene, _ = spring
    with pytest.raises(ValueError, match="joint model 'springy'"):
        Dynamics(scene.model(), Joints("springy"))
