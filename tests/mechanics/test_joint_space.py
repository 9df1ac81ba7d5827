"""The joint-space body (mechanics.joint_space) against the natural-coordinate model it comes
from: the same kinematics and kinetic energy, the same accelerations and ground force as the
landing's constrained natural-coordinate dynamics (with torque joints), the same impact T_c
as formopt's projection, and derivatives that match finite differences."""

import casadi as ca
import numpy as np
import pytest
from helpers import SEED

from formopt.mechanics.body import paper_body, scaled_body
from formopt.mechanics.impact import projection
from formopt.mechanics.joint_space import JOINTS, POINTS, WALL_K, JointSpace, passive_moments, swap_legs
from formopt.mechanics.landing import Joints, LandingModel
from formopt.mechanics.model import build_model
from formopt.optim.stride.checks import joint_impact

DEG = np.pi / 180


@pytest.fixture(scope="module", params=["paper", "rbds001"])
def js(request):
    return JointSpace(paper_body() if request.param == "paper" else scaled_body(62.0, 1.81))


def running_states(n, seed=SEED):
    """Joint states inside the ranges of motion (theta: m, rad; theta': m/s, rad/s)."""
    rng = np.random.default_rng(seed)
    lo = np.r_[-0.5, 0.8, -10 * DEG, [-20, 5, -30, -20, 5, -30] * np.full(6, DEG)]
    hi = np.r_[0.5, 1.0, 30 * DEG, [60, 90, 20, 60, 90, 20] * np.full(6, DEG)]
    theta = rng.uniform(lo, hi, (n, 9))
    thetad = rng.normal(0, 3, (n, 9))
    thetad[:, :2] = rng.uniform([2, -1.5], [6, 1.0], (n, 2))
    return theta, thetad


def test_kinematics_and_kinetic_energy_match_the_natural_model(js):
    """q(theta) and J theta' against model.state's segment kinematics; T = 1/2 q'^T M q'."""
    for theta, thetad in zip(*running_states(20)):
        x, swing = js.segment_rates(theta, thetad)
        model = build_model(js.body, "full-body", swing=swing)
        q, qd = model.state_numeric(x, "hip")
        hip = np.tile(theta[:2], model.n // 2)
        assert np.allclose(np.asarray(js.q(theta)).ravel(), q + hip, atol=1e-13)
        assert np.allclose(np.asarray(js.J(theta)) @ thetad, qd, atol=1e-12)
        assert float(js.kinetic(theta, thetad)) == pytest.approx(float(model.kinetic_energy(qd)), rel=1e-13)
        assert np.max(np.abs(np.asarray(model.constraints(ca.DM(np.asarray(js.q(theta)).ravel()))))) < 1e-13


@pytest.mark.parametrize("active", [(), ("heel",), ("forefoot",)])
def test_dynamics_match_the_landing_with_torque_joints(js, active):
    """theta'' and the ground force of M(theta) theta'' + ... = J^T Q_g - S tau + J_c^T f
    against the landing's natural-coordinate dynamics (constant M, constraint multipliers,
    torque joints with the same extensor-positive moments): q'' = J theta'' + J' theta'."""
    rng = np.random.default_rng(SEED + 1)
    names = {"hip_R": "hip", "knee_R": "knee", "ankle_R": "ankle", "hip_L": "swing_hip",
             "knee_L": "swing_knee", "ankle_L": "swing_ankle"}
    for theta, thetad in zip(*running_states(5)):
        tau = rng.normal(0, 60, 6)
        joints = Joints("torque", times=(0.0, 1.0),
                        moments={names[j]: (t, t) for j, t in zip(JOINTS, tau)})
        lm = LandingModel(js.model, joints, compiled=False)
        if active:  # the held point on the ground, at rest (the landing's Baumgarte terms vanish)
            point = f"{active[0]}_R"
            theta[1] -= float(js.points[point](theta, thetad, 0.0)[0][1])
            Jp = np.asarray(js.points[point](theta, thetad, 0.0)[2], float)
            thetad = thetad - np.linalg.pinv(Jp) @ (Jp @ thetad)
        q = np.asarray(js.q(theta), float).ravel()
        J = np.asarray(js.J(theta), float)
        qd = J @ thetad
        anchor = q[js.model.cols(active[0])][0] if active else 0.0
        out = lm.motion(active).call({"q": q, "qd": qd, "s_anchor": anchor,
                                   "joint": lm.joint_parameters(q), "friction": 0.0, "t": 0.5})
        rows = tuple((f"{p}_R", a) for p in active for a in "tn")
        # the landing has no passive joint moments: solve without them
        M = np.asarray(js.mass(theta), float)
        Jc = np.vstack([np.asarray(js.points[p](theta, thetad, 0.0)[2], float)[0 if a == "t" else 1]
                        for p, a in rows]) if rows else np.zeros((0, 9))
        rhs = (np.asarray(js.gravity(theta), float).ravel()
               - np.asarray(js.bias(theta, thetad), float).ravel() - np.r_[0, 0, 0, tau])
        drift = np.array([float(js.points[p](theta, thetad, 0.0)[3][0 if a == "t" else 1])
                          for p, a in rows])
        K = np.block([[M, -Jc.T], [Jc, np.zeros((len(rows), len(rows)))]])
        sol = np.linalg.solve(K, np.r_[rhs, -drift])
        qdd = J @ sol[:9] + _jdot_thetad(js, theta, thetad)
        reference = np.asarray(out["qdd"]).ravel()
        assert np.allclose(qdd, reference, atol=1e-6 * np.max(np.abs(reference)))
        if active:
            assert np.allclose(sol[9:], np.asarray(out["force"]).ravel(), rtol=1e-7, atol=1e-6)


def _jdot_thetad(js, theta, thetad):
    """(dJ/dt) theta' by central finite differences of J along theta' (a check independent of
    the symbolic jtimes)."""
    eps = 1e-6
    Jp = np.asarray(js.J(theta + eps * thetad), float)
    Jm = np.asarray(js.J(theta - eps * thetad), float)
    return (Jp - Jm) @ thetad / (2 * eps)


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
def test_impact_equals_formopt_projection(js, strike):
    """T_c of the joint-space projection equals mechanics.impact.projection on the natural
    model at the same state (q = q(theta), q' = J theta') to 1e-9 J, for both legs."""
    rows = {"heel": (("heel_R", "t"), ("heel_R", "n")),
            "forefoot": (("forefoot_R", "t"), ("forefoot_R", "n")),
            "flat": (("heel_R", "t"), ("heel_R", "n"), ("forefoot_R", "n"))}[strike]
    for theta, thetad in zip(*running_states(10, SEED + 2)):
        for leg in "RL":
            leg_rows = tuple((p[:-1] + leg, a) for p, a in rows)
            plus, _p, T_c = joint_impact(js, leg_rows, theta, thetad, 0.1)
            q = np.asarray(js.q(theta), float).ravel()
            qd = np.asarray(js.J(theta), float) @ thetad
            points = tuple(dict.fromkeys(POINTS[pt] for pt, _ in leg_rows))
            C = js.model.contact_rows(points, 0.1, tangential=points[:1])
            ref = projection(js.model, ca.DM(q), ca.DM(qd), C)
            # 1e-9 J, or 1e-11 of T_c for the random states' large ones (up to 200 J)
            assert T_c == pytest.approx(float(ref["T_c"]), abs=max(1e-9, 1e-11 * T_c))
            assert np.allclose(np.asarray(js.J(theta), float) @ plus, np.asarray(ref["qd_plus"]).ravel(), atol=1e-9)


def test_energy_and_swap(js):
    """The potential energy is m g z_com; swapping the legs twice is the identity."""
    theta, _thetad = running_states(1)
    theta = theta[0]
    assert float(js.potential(theta)) == pytest.approx(js.mass_total * 9.81 * float(js.com(theta)[1]))
    assert np.array_equal(swap_legs(swap_legs(theta)), theta)


def test_derivatives_match_finite_differences(js):
    """The Jacobians CasADi takes of the mass matrix times a vector, the bias term and the
    passive joint moments against central finite differences."""
    theta, thetad = (v[0] for v in running_states(1, SEED + 3))
    a = np.random.default_rng(SEED).normal(size=9)
    th, thd = ca.SX.sym("th", 9), ca.SX.sym("thd", 9)
    f = ca.Function("f", [th, thd], [js.mass(th) @ a + js.bias(th, thd) - js.gravity(th) - js.passive(th)])
    jacobian = ca.Function("jacobian", [th, thd], [ca.jacobian(f(th, thd), ca.vertcat(th, thd))])
    analytic = np.asarray(jacobian(theta, thetad), float)
    eps = 1e-6
    x0 = np.r_[theta, thetad]
    numeric = np.column_stack([
        (np.asarray(f(*np.split(x0 + eps * e, 2)), float) - np.asarray(f(*np.split(x0 - eps * e, 2)), float)).ravel()
        / (2 * eps) for e in np.eye(18)])
    assert np.allclose(analytic, numeric, rtol=1e-6, atol=1e-5)


@pytest.mark.parametrize(("angles_deg", "published"), [
    ((0, 60, 0), (10.618, -4.454, -1.053)),  # knee -4.454 = e^(1.8-2.112) - e^(-3.971+2.97) - 4.82 + e^(2.22-9)
    ((0, 0, 20), (8.582, 19.549, -42.358)),  # ankle: -(e^(2.1016+1.686) - e^(-7.9763-3.898) - 1.792)
    ((-20, 10, 0), (25.172, -0.049, -5.067)),  # hip: e^(1.4655-0.034+1.5) - e^(1.3403-0.226-0.61) + 8.072
    ((0, -5, 0), (8.199, 21.871, -7.139)),  # knee 5 deg into hyperextension: e^(2.22+0.75) and the rest
])
def test_passive_moments_are_riener_and_edrichs(angles_deg, published):
    """passive_moments against Riener & Edrich (1999)'s equations evaluated by hand (N m; hip
    flexion, knee flexion, ankle dorsiflexion moments; their ankle angle and moment are
    plantarflexion-positive, so both change sign)."""
    moments = passive_moments(np.array(angles_deg) * DEG)
    assert [float(m) for m in moments] == pytest.approx(published, abs=2e-3)


def test_passive_moments_resist_the_ends_of_the_ranges():
    """Each joint's own moment falls as its angle rises (a stiffness, no negative spring) over
    the running ranges +- 15 deg, the other joints anywhere in theirs."""
    rng = np.random.default_rng(SEED)
    angle = ca.SX.sym("angle", 3)
    stiffness = ca.Function("k", [angle], [ca.diag(ca.jacobian(ca.vertcat(*passive_moments(angle)), angle))])
    lo, hi = np.array([-55, -15, -65]) * DEG, np.array([125, 155, 45]) * DEG
    for angles in rng.uniform(lo, hi, (200, 3)):
        assert np.all(np.asarray(stiffness(angles), float) < 0)


def test_the_range_walls_act_beyond_the_ranges_only(js):
    """js.limits, the muscle rung's joint moments (the muscles hold their own passive force):
    2.7 N m at 5 deg beyond a limit (e^1 K), 0.14 N m 10 deg inside (e^-2 K), against the limit."""
    theta = np.zeros(9)
    theta[3:] = np.array([0, 40, 0, 0, 40, 0]) * DEG  # mid-range: every wall nearly silent
    assert np.abs(np.asarray(js.limits(theta), float)).max() < 5e-3  # the ankle 30 deg from its limit: e^-6 K
    theta[4] = -5 * DEG  # the stance knee 5 deg into hyperextension: the wall flexes it
    theta[5] = 20 * DEG  # the stance ankle 10 deg short of its 30 deg of dorsiflexion
    tau = np.asarray(js.limits(theta), float).ravel()
    assert tau[4] == pytest.approx(WALL_K * np.e, rel=1e-3) and tau[5] == pytest.approx(-WALL_K * np.exp(-2.0), rel=1e-3)
