"""The projection equals the angular-momentum impact map (seed eq. 3) for one contact point."""

import numpy as np
import pytest
from helpers import random_states, split_leg

from formopt import Impact
from formopt.mechanics.angular_momentum import angular_momentum_impact
from formopt.mechanics.model import build_model


@pytest.mark.parametrize("kind", ["leg", "shank-foot", "leg-trunk", "split-leg"])
@pytest.mark.parametrize("strike", ["heel", "forefoot"])
def test_projection_equals_angular_momentum(body, kind, strike):
    model = split_leg(body) if kind == "split-leg" else build_model(body, kind)
    impact = Impact(model, strike, 0.0, 0.8)
    for x in random_states(30, seed=7, strike=strike):
        r = impact(x)
        q, _qd = model.state_numeric(x, strike)
        qd_plus = angular_momentum_impact(model, q, r.qd_minus, strike)
        scale = np.max(np.abs(r.qd_minus))
        assert np.max(np.abs(qd_plus - r.qd_plus)) <= 1e-9 * scale
        T_a = 0.5 * qd_plus @ model.M @ qd_plus
        assert abs((r.T - T_a) - r.T_c) <= 1e-9 * r.T
