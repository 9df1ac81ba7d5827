"""The projection equals Pinocchio's impulseDynamics on the same body and state.

Pinocchio (package `pin`, the test extra) builds the paper's leg as a kinematic tree: a
planar free joint at the hip carrying the thigh and the trunk point mass, revolute joints at
knee and ankle. It knows nothing of natural coordinates.
"""

import casadi as ca
import numpy as np
import pinocchio as pin
import pytest

from formopt import Impact

from conftest import random_states

POINTS = ("hip", "knee", "ankle", "heel", "forefoot")


def pinocchio_leg(body):
    model = pin.Model()
    thigh, shank, foot = body["thigh"], body["shank"], body["foot"]

    def inertia(seg):
        c = seg.com
        return pin.Inertia(seg.mass, np.array([c[0], c[1], 0.0]), seg.inertia_com * np.eye(3))

    root = model.addJoint(0, pin.JointModelPlanar(), pin.SE3.Identity(), "hip")
    model.appendBodyToJoint(root, inertia(thigh), pin.SE3.Identity())
    model.appendBodyToJoint(root, pin.Inertia(body["trunk"].mass, np.zeros(3), 1e-300 * np.eye(3)),
                            pin.SE3.Identity())
    knee = model.addJoint(root, pin.JointModelRZ(),
                          pin.SE3(np.eye(3), np.array([0.0, -thigh.length, 0.0])), "knee")
    model.appendBodyToJoint(knee, inertia(shank), pin.SE3.Identity())
    ankle = model.addJoint(knee, pin.JointModelRZ(),
                           pin.SE3(np.eye(3), np.array([0.0, -shank.length, 0.0])), "ankle")
    model.appendBodyToJoint(ankle, inertia(foot), pin.SE3.Identity())
    for name, joint, local in (("hip", root, (0, 0)), ("knee", knee, (0, 0)), ("ankle", ankle, (0, 0)),
                               ("heel", ankle, foot.landmarks["heel"]),
                               ("forefoot", ankle, foot.landmarks["forefoot"])):
        model.addFrame(pin.Frame(name, joint, pin.SE3(np.eye(3), np.array([*local, 0.0])),
                                 pin.FrameType.OP_FRAME))
    return model


def pinocchio_state(x, hip_position):
    """formopt's touchdown state -> Pinocchio's (q, v)."""
    trunk, hip, knee, ankle, vx, vz, _, w_thigh, w_shank, w_foot = x
    thigh = hip - trunk
    c, s = np.cos(thigh), np.sin(thigh)
    q = np.array([hip_position[0], hip_position[1], c, s, -knee, ankle])
    v_local = np.array([[c, s], [-s, c]]) @ np.array([vx, vz])  # planar joint: local frame
    v = np.array([*v_local, w_thigh, w_shank - w_thigh, w_foot - w_shank])
    return q, v


def point_velocities(model, data, q, v):
    pin.forwardKinematics(model, data, q, v)
    pin.updateFramePlacements(model, data)
    return np.concatenate([pin.getFrameVelocity(model, data, model.getFrameId(p),
                                                pin.LOCAL_WORLD_ALIGNED).linear[:2] for p in POINTS])


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
@pytest.mark.parametrize("slope_deg", [0.0, -10.0])
def test_projection_equals_pinocchio(body, leg, strike, slope_deg):
    slope = np.radians(slope_deg)
    pmodel = pinocchio_leg(body)
    data = pmodel.createData()
    impact = Impact(leg, strike, slope)
    t = np.array([np.cos(slope), np.sin(slope)])
    n = np.array([-np.sin(slope), np.cos(slope)])
    for x in random_states(25, seed=11, strike=strike, slope=slope):
        r = impact(x)
        q_nc, _ = leg.state(ca.DM(x), "heel" if strike == "flat" else strike)
        q_nc = np.asarray(ca.evalf(q_nc), float).ravel()
        q, v = pinocchio_state(x, q_nc[leg.cols("hip")])
        # the same state: every point's velocity before the impact agrees
        assert np.allclose(point_velocities(pmodel, data, q, v), r.qd_minus, atol=1e-12)
        pin.computeJointJacobians(pmodel, data, q)
        pin.updateFramePlacements(pmodel, data)
        if strike == "flat":  # the foot held: its planar velocity (x, y, rotation z)
            J = pin.getJointJacobian(pmodel, data, pmodel.getJointId("ankle"),
                                     pin.LOCAL_WORLD_ALIGNED)[[0, 1, 5]]
        else:
            J = pin.getFrameJacobian(pmodel, data, pmodel.getFrameId(strike),
                                     pin.LOCAL_WORLD_ALIGNED)[:2]
        v_after = pin.impulseDynamics(pmodel, data, q, v, J, 0.0, 0.0).copy()
        impulse = data.impulse_c.copy()
        M = pin.crba(pmodel, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        T, T_a = 0.5 * v @ M @ v, 0.5 * v_after @ M @ v_after
        assert abs(T - r.T) <= 1e-9 * r.T
        assert abs((T - T_a) - r.T_c) <= 1e-9 * r.T
        assert np.allclose(point_velocities(pmodel, data, q, v_after), r.qd_plus,
                           atol=1e-9 * np.max(np.abs(r.qd_minus)))
        total = np.array([impulse[:2] @ t, impulse[:2] @ n])  # world x, z -> ground t, n
        assert np.allclose(total, r.impulse_total, rtol=1e-9, atol=1e-9)
