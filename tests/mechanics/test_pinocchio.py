"""The projection equals Pinocchio's impulseDynamics on the same body and state
(formopt.oracle builds the leg as a kinematic tree; flat foot holds the foot's planar motion)."""

import numpy as np
import pinocchio as pin
import pytest
from helpers import random_states
from oracle import contact_jacobian, pinocchio_leg, pinocchio_state, point_velocities

from formopt import Impact


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
@pytest.mark.parametrize("slope_deg", [0.0, -10.0])
def test_projection_equals_pinocchio(body, leg, strike, slope_deg):
    slope = np.radians(slope_deg)
    pmodel = pinocchio_leg(body)
    data = pmodel.createData()
    impact = Impact(leg, strike, slope, 0.8)
    t = np.array([np.cos(slope), np.sin(slope)])
    n = np.array([-np.sin(slope), np.cos(slope)])
    for x in random_states(25, seed=11, strike=strike, slope=slope):
        r = impact(x)
        q_nc, _ = leg.state_numeric(x, "heel" if strike == "flat" else strike)
        q, v = pinocchio_state(x, q_nc[leg.cols("hip")])
        # the same state: every point's velocity before the impact agrees
        assert np.allclose(point_velocities(pmodel, data, q, v), r.qd_minus, atol=1e-12)
        J = contact_jacobian(pmodel, data, q, strike)
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
