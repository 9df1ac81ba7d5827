"""Actuation models of the stride: what moves the joints at a node.

An actuation model has `controls` (per node, with bounds) and gives the joint moments (N m,
JOINTS order, extensor positive) that enter the equations of motion,

    tau = tau_active(u) + tau_passive(theta, theta_td),

with the active part's power P_j = -tau_j phi_j' (W; what W+ and W- count) apart from the
passive elements' (the budget's `spring_J`). Symbolic (SX) or numeric arguments.
"""

from __future__ import annotations

import casadi as ca

from ...mechanics.joint_space import JOINTS

NU = len(JOINTS)


class Torques:
    """Joint torque sources: tau = m u, u (N m/kg, one per joint) within +-`limit`."""

    def __init__(self, mass: float, limit: float):
        self.mass, self.limit = mass, limit

    @property
    def controls(self) -> int:
        return NU

    def bounds(self) -> tuple[float, float]:
        """(lower, upper) of each control (N m/kg)."""
        return -self.limit, self.limit

    def active(self, u):
        """The active joint moments (N m, 6) of controls u (N m/kg, 6)."""
        return self.mass * u

    def passive(self, theta, theta_td, stance: bool):
        """The passive elements' joint moments (N m, 6): none."""
        return ca.DM.zeros(NU)


class TorquesWithSprings(Torques):
    """Torque sources with a spring in parallel at the stance leg's joints (tendons):

        tau_spring_j = k_j m (phi_j - phi_j(touchdown))   while R holds the ground, else 0,

    k_j in N m/rad per kg (problem.TENDON_JOINTS, RUNNER_TENDONS), engaged unloaded at the
    touchdown and released at toe-off: what it still holds then is lost (budget's `spring_J`).
    """

    def __init__(self, mass: float, limit: float, stiffness: dict):
        super().__init__(mass, limit)
        self.stiffness = {f"{joint}_R": k for joint, k in stiffness.items() if k}

    def passive(self, theta, theta_td, stance: bool):
        out = [0.0] * NU
        if stance:
            for joint, k in self.stiffness.items():
                j = JOINTS.index(joint)
                out[j] = k * self.mass * (theta[3 + j] - theta_td[3 + j])
        return ca.vertcat(*out)


def actuation(mass: float, limit: float, tendons: dict) -> Torques:
    """The actuation model of a stride's settings: torques, with springs where tendons are set."""
    return TorquesWithSprings(mass, limit, tendons) if any(tendons.values()) else Torques(mass, limit)
