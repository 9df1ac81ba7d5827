"""The posture NLP's parameterisation: decision vector, parameters and the touchdown state.

Order of the decision vector w (opty's convention: documented, fixed):

    w = [u_1 .. u_n, tau]     u_k in [0, 1]: variable k scaled between its bounds,
                              x_k = lower_k + (upper_k - lower_k) u_k (rad or rad/s);
                              tau (landing problems only): the second impact at tau * duration

Parameters p = [hip_vx (m/s, the running speed), mu (friction coefficient), slope (rad, the
ground's, positive uphill), the reference touchdown state (model.STATE, SI)]: the NLP is built
once and solved for any speed, ground and reference (sweeps, sensitivities, one optimum per
measured step); a landing problem's slope is the one its landing model was built for. Every other entry of the
touchdown state stays at the reference's value, except the ankle of a flat strike, which
follows from the sole lying on the ground.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from ..mechanics.limits import RANGE_OF_MOTION_DEG  # noqa: F401  (re-exported, one home)
from ..mechanics.model import STATE, Model

PARAMETERS = 3 + len(STATE)  # speed, friction, slope, reference state
SPEED, FRICTION, SLOPE = 0, 1, 2  # their places in p


class Posture:
    """Variables (STATE names) with SI bounds around a reference touchdown state, on the
    problem's ground (friction, slope rad): the parameters p0 unless others are given."""

    def __init__(self, model: Model, strike: str, reference, variables, lower, upper,
                 friction: float, slope: float):
        self.model, self.strike, self.friction, self.slope = model, strike, friction, slope
        self.reference = np.asarray(reference, float)
        self.variables = tuple(variables)
        self.index = [STATE.index(v) for v in self.variables]
        self.lower, self.upper = np.asarray(lower, float), np.asarray(upper, float)
        u, p = ca.SX.sym("u", len(self.index)), ca.SX.sym("p", PARAMETERS)
        self.function = ca.Function("state", [u, p], [self.state(u, p)], ["u", "p"], ["x"])

    @property
    def size(self) -> int:
        return len(self.index)

    def parameters(self, speed: float | None = None, friction: float | None = None,
                   slope: float | None = None, reference=None) -> np.ndarray:
        """p = [speed (m/s), friction, slope (rad), reference state]; each one left out is the
        problem's own (the speed: the reference's hip_vx)."""
        reference = self.reference if reference is None else np.asarray(reference, float)
        return np.array([reference[STATE.index("hip_vx")] if speed is None else speed,
                         self.friction if friction is None else friction,
                         self.slope if slope is None else slope, *reference])

    @staticmethod
    def reference_of(p):
        """The reference touchdown state within parameters p (SX/MX or numbers)."""
        return p[3:3 + len(STATE)]

    def state(self, u, p):
        """The touchdown state (SX, SI) of scaled variables u and parameters p."""
        x = ca.SX(self.reference_of(p))
        for k, i in enumerate(self.index):
            x[i] = self.lower[k] + (self.upper[k] - self.lower[k]) * u[k]
        x[STATE.index("hip_vx")] = p[SPEED]
        if self.strike == "flat":  # the sole on the ground: the ankle follows the other angles
            heel, fore = (np.array(self.model.body["foot"].landmarks[k]) for k in ("heel", "forefoot"))
            sole = math.atan2(fore[1] - heel[1], fore[0] - heel[0])
            x[3] = p[SLOPE] - sole - x[1] + x[0] + x[2]
        return x

    def to_unit(self, x) -> np.ndarray:
        """Scaled variables u of a touchdown state (clipped to the bounds)."""
        x = np.asarray(x, float)
        return np.clip((x[self.index] - self.lower) / (self.upper - self.lower), 0.0, 1.0)

    def to_state(self, w, p) -> np.ndarray:
        """The touchdown state (SI) of a decision vector (its first `size` entries) and p."""
        u = np.asarray(w, float)[:self.size]
        return np.asarray(self.function(u, p), float).ravel()

    def degrees(self, x) -> dict[str, float]:
        """The variables of state x in deg (angles) or deg/s (rates)."""
        return {v: math.degrees(float(np.asarray(x)[i])) for v, i in zip(self.variables, self.index)}

    def per_unit(self) -> np.ndarray:
        """d(variable)/d(u) in deg per unit of u: converts gradients in u to per-degree values."""
        return np.degrees(self.upper - self.lower)
