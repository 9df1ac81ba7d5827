"""CasADi derivatives of the indicators against central finite differences."""

import casadi as ca
import numpy as np
import pytest
from helpers import central_difference, random_states

from formopt.mechanics.impact import impact_function, on_ground

OUTPUTS = ("T_c", "impulse", "impulse_total", "dv_trunk", "dv_com", "T_a")


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
def test_jacobians_match_finite_differences(leg, strike):
    f = on_ground(impact_function(leg, strike), 0.8, 0.0)
    x_sym = ca.SX.sym("x", f.size1_in(0))
    out = ca.vertcat(*[f(x=x_sym)[k] for k in OUTPUTS])
    value = ca.Function("value", [x_sym], [out])
    jac = ca.Function("jacobian", [x_sym], [ca.jacobian(out, x_sym)])
    states = random_states(8, seed=5, strike=strike)
    for x in states:  # the map is smooth in x everywhere, flat-foot states included
        exact = np.asarray(jac(x), float)
        approx = central_difference(lambda z: np.asarray(value(z), float).ravel(), x)
        scale = np.maximum(np.abs(exact), 1.0)
        assert np.max(np.abs(exact - approx) / scale) < 1e-6
