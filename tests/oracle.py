"""The paper's leg in Pinocchio (package `pin`, the `test` extra): an independent oracle.

Pinocchio builds the paper's leg as a kinematic tree (a planar free joint at the hip carrying
the thigh and the trunk and swing leg as a point mass, revolute joints at knee and ankle) and knows nothing of
natural coordinates. Tests compare the projection with its `impulseDynamics`; benchmarks time
the same work side by side.
"""

from __future__ import annotations

import numpy as np

from formopt.mechanics.body import Body

POINTS = ("hip", "knee", "ankle", "heel", "forefoot")


def pinocchio_leg(body: Body):
    """A pinocchio.Model of the leg with frames at hip, knee, ankle, heel and forefoot."""
    import pinocchio as pin

    model = pin.Model()
    thigh, shank, foot = body["thigh"], body["shank"], body["foot"]

    def inertia(seg):
        return pin.Inertia(seg.mass, np.array([*seg.com, 0.0]), seg.inertia_com * np.eye(3))

    def offset(x, z):
        return pin.SE3(np.eye(3), np.array([x, z, 0.0]))

    root = model.addJoint(0, pin.JointModelPlanar(), pin.SE3.Identity(), "hip")
    model.appendBodyToJoint(root, inertia(thigh), pin.SE3.Identity())
    at_hip = body["trunk"].mass + (body["swing_leg"].mass if "swing_leg" in body.segments else 0.0)
    model.appendBodyToJoint(root, pin.Inertia(at_hip, np.zeros(3), 1e-300 * np.eye(3)),
                            pin.SE3.Identity())
    knee = model.addJoint(root, pin.JointModelRZ(), offset(0.0, -thigh.length), "knee")
    model.appendBodyToJoint(knee, inertia(shank), pin.SE3.Identity())
    ankle = model.addJoint(knee, pin.JointModelRZ(), offset(0.0, -shank.length), "ankle")
    model.appendBodyToJoint(ankle, inertia(foot), pin.SE3.Identity())
    for name, joint, local in (("hip", root, (0, 0)), ("knee", knee, (0, 0)), ("ankle", ankle, (0, 0)),
                               ("heel", ankle, foot.landmarks["heel"]),
                               ("forefoot", ankle, foot.landmarks["forefoot"])):
        model.addFrame(pin.Frame(name, joint, offset(*local), pin.FrameType.OP_FRAME))
    return model


def pinocchio_state(x, hip_position):
    """formopt's touchdown state (model.STATE) -> Pinocchio's (q, v)."""
    trunk, hip, knee, ankle, vx, vz, _, w_thigh, w_shank, w_foot = x
    thigh = hip - trunk
    c, s = np.cos(thigh), np.sin(thigh)
    q = np.array([hip_position[0], hip_position[1], c, s, -knee, ankle])
    v_local = np.array([[c, s], [-s, c]]) @ np.array([vx, vz])  # the planar joint's own frame
    return q, np.array([*v_local, w_thigh, w_shank - w_thigh, w_foot - w_shank])


def contact_jacobian(model, data, q, strike: str) -> np.ndarray:
    """World-aligned Jacobian of the held contact: a point (x, z), or the whole foot (x, z, rotation)."""
    import pinocchio as pin

    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    if strike == "flat":
        return pin.getJointJacobian(model, data, model.getJointId("ankle"),
                                    pin.LOCAL_WORLD_ALIGNED)[[0, 1, 5]]
    return pin.getFrameJacobian(model, data, model.getFrameId(strike), pin.LOCAL_WORLD_ALIGNED)[:2]


def point_velocities(model, data, q, v) -> np.ndarray:
    """World velocities of POINTS, stacked like formopt's natural coordinates."""
    import pinocchio as pin

    pin.forwardKinematics(model, data, q, v)
    pin.updateFramePlacements(model, data)
    return np.concatenate([pin.getFrameVelocity(model, data, model.getFrameId(p),
                                                pin.LOCAL_WORLD_ALIGNED).linear[:2] for p in POINTS])
