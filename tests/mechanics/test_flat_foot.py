"""Flat foot: four contact rows, one redundant. What is unique is exact; the rest is flagged."""

import casadi as ca
import numpy as np
import pytest
from helpers import random_states

from formopt import Impact


def full_system(model, x, slope):
    """Phi_q with all four contact rows (heel and forefoot, t and n), numeric."""
    q, qd = model.state(ca.DM(x), "heel")
    q = np.asarray(ca.evalf(q), float).ravel()
    qd = np.asarray(ca.evalf(qd), float).ravel()
    Phi = np.vstack([np.asarray(model.constraint_jacobian(q), float),
                     model.contact_rows(("heel", "forefoot"), slope)])
    return Phi, qd


@pytest.mark.parametrize("slope_deg", [0.0, 8.0])
def test_flat_matches_a_rank_revealing_solve(leg, slope_deg):
    slope = np.radians(slope_deg)
    impact = Impact(leg, "flat", slope, 0.8)
    nb = 5
    for x in random_states(30, seed=3, strike="flat", slope=slope):
        r = impact(x)
        Phi, qd = full_system(leg, x, slope)
        G = Phi @ leg.M_inv @ Phi.T
        s = np.linalg.svd(G, compute_uv=False)
        assert s[-1] < 1e-12 * s[0], "all four rows are one too many: G is singular"
        assert s[-2] > 1e-6 * s[0], "and only one too many"
        lam = -np.linalg.pinv(G, rcond=1e-12) @ (Phi @ qd)  # the minimum-norm impulses
        qd_plus = qd + leg.M_inv @ Phi.T @ lam
        assert np.allclose(qd_plus, r.qd_plus, atol=1e-10 * np.max(np.abs(qd)))
        assert abs(0.5 * (Phi @ qd) @ -lam - r.T_c) <= 1e-9 * r.T
        # the undetermined direction of the impulses: a null vector of Phi^T
        _, _, Vt = np.linalg.svd(Phi.T)
        null = Vt[-1]
        heel_t, heel_n, fore_t, fore_n = null[nb:]
        assert abs(heel_n) < 1e-12 and abs(fore_n) < 1e-12  # normal impulses are determined
        assert abs(heel_t + fore_t) < 1e-12  # and so is the total tangential
        assert abs(heel_t) > 0.1  # the split is not
        assert np.allclose([lam[nb + 1], lam[nb + 3]],
                           [r.impulse["heel"][1], r.impulse["forefoot"][1]], rtol=1e-9, atol=1e-9)
        assert np.isclose(lam[nb] + lam[nb + 2], r.impulse_total[0], rtol=1e-9, atol=1e-9)
        assert r.impulse_determined == {"heel": (False, True), "forefoot": (False, True)}
        assert any("not determined" in w for w in r.warnings)


def test_flat_split_needs_the_least_friction(leg):
    """The reported split gives both points the same ratio t/n: the total's mu_c."""
    r = Impact(leg, "flat", 0.0, 0.8)(random_states(1, strike="flat")[0])
    ratios = [t / n for t, n in r.impulse.values()]
    assert np.allclose(ratios, ratios[0]) and np.isclose(abs(ratios[0]), r.mu_c)


def test_flat_needs_a_flat_sole(leg):
    x = random_states(1, strike="flat")[0]
    x[3] += np.radians(2.0)
    with pytest.raises(ValueError, match="sole on the ground"):
        Impact(leg, "flat", 0.0, 0.8)(x)
