"""Invariants of the projection (design.md section 5) over random touchdowns."""

import numpy as np
import pytest
from helpers import random_states, split_leg

from formopt import Impact
from formopt.mechanics.model import STRIKES, build_model


def numeric_projection(model, q, points, slope):
    """P_c and Phi_q at q, assembled in numpy from the model's pieces."""
    Phi = np.vstack([np.asarray(model.constraint_jacobian(q), float),
                     model.contact_rows(points, slope)])
    G = Phi @ model.M_inv @ Phi.T
    Pc = model.M_inv @ Phi.T @ np.linalg.pinv(G, rcond=1e-12) @ Phi
    return Pc, Phi


@pytest.mark.parametrize("kind", ["shank-foot", "leg", "leg-trunk"])
@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
@pytest.mark.parametrize("slope", [0.0, np.radians(-10.0), np.radians(12.0)])
def test_energy_split_and_projection(body, kind, strike, slope):
    model = build_model(body, kind)
    impact = Impact(model, strike, slope, 0.8)
    points = STRIKES[strike]
    for x in random_states(25, strike=strike, slope=slope):
        r = impact(x)
        assert r.T_c >= 0.0
        assert abs(r.T_c + r.T_a - r.T) <= 1e-10 * r.T
        q, _ = model.state_numeric(x, points[0])  # its map built once (DM arithmetic: half the test's CPU)
        Pc, Phi = numeric_projection(model, q, points, slope)
        Pa = np.eye(model.n) - Pc
        assert np.allclose(Pa @ Pa, Pa, atol=1e-10)
        # every active constraint holds after the impact, velocities only move along P_c
        assert np.max(np.abs(Phi @ r.qd_plus)) <= 1e-10 * np.max(np.abs(r.qd_minus))
        assert np.allclose(Pa @ r.qd_minus, r.qd_plus, atol=1e-10)
        assert abs(0.5 * r.qd_minus @ Pc.T @ model.M @ Pc @ r.qd_minus - r.T_c) <= 1e-9 * r.T


def test_energy_is_never_created(leg):
    for strike in ("heel", "forefoot"):
        impact = Impact(leg, strike, 0.0, 0.8)
        results = [impact(x) for x in random_states(200, strike=strike)]
        assert all(r.T_a <= r.T * (1 + 1e-12) for r in results)


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
def test_independent_of_the_natural_coordinates(body, leg, strike):
    """The same body in other natural coordinates gives the same indicators."""
    other = split_leg(body)
    assert other.n == 12 and leg.n == 10
    a, b = Impact(leg, strike, 0.0, 0.8), Impact(other, strike, 0.0, 0.8)
    for x in random_states(20, strike=strike):
        ra, rb = a(x), b(x)
        assert abs(ra.T_c - rb.T_c) <= 1e-10 * ra.T
        assert abs(ra.T - rb.T) <= 1e-10 * ra.T
        for p in ra.impulse:
            assert np.allclose(ra.impulse[p], rb.impulse[p], rtol=1e-9, atol=1e-10)
        assert np.allclose(ra.dv_trunk, rb.dv_trunk, atol=1e-10)
        assert np.allclose(ra.dv_com, rb.dv_com, atol=1e-10)


def test_mass_matrix_reproduces_the_bar_formula(body, leg):
    """design.md's 2x2 block for a bar (thigh) inside the assembled matrix."""
    thigh = body["thigh"]
    m, L, c, Ii = thigh.mass, thigh.length, -thigh.com[1], thigh.inertia_proximal
    block = np.array([[m - 2 * m * c / L + Ii / L**2, m * c / L - Ii / L**2],
                      [m * c / L - Ii / L**2, Ii / L**2]])
    trunk = body["trunk"].mass + body["swing_leg"].mass
    expected_hip = block[0, 0] + trunk
    M = leg.M
    hip, knee = leg.cols("hip"), leg.cols("knee")
    assert np.allclose(M[hip, hip], expected_hip * np.eye(2))
    assert np.allclose(M[hip, knee], block[0, 1] * np.eye(2))
    assert np.allclose(M, M.T) and np.all(np.linalg.eigvalsh(M) > 0)


def test_kinetic_energy_matches_segment_sums(body, leg):
    """T from the constant mass matrix equals the sum of 1/2 m v^2 + 1/2 J w^2 per segment."""
    x = random_states(1)[0]
    r = Impact(leg, "forefoot", 0.0, 0.8)(x)
    qd = r.qd_minus
    w = {"thigh": x[7], "shank": x[8], "foot": x[9]}
    at_hip = body["trunk"].mass + body["swing_leg"].mass
    T = 0.5 * at_hip * qd[leg.cols("hip")] @ qd[leg.cols("hip")]
    for seg in ("thigh", "shank", "foot"):
        v = leg.com_matrix(seg) @ qd
        T += 0.5 * body[seg].mass * v @ v + 0.5 * body[seg].inertia_com * w[seg] ** 2
    assert abs(T - r.T) <= 1e-12 * T


def test_mu_c_two_ways(leg):
    for strike in STRIKES:
        impact = Impact(leg, strike, 0.0, 0.8)
        for x in random_states(20, strike=strike):
            r = impact(x)
            assert (r.mu_c is None) == (r.mu_c_momentum is None) == (r.impulse_total[1] <= 0)
            if r.mu_c is not None:
                assert abs(r.mu_c - r.mu_c_momentum) <= 1e-8 * max(1.0, r.mu_c)


@pytest.mark.parametrize("strike", ["heel", "forefoot", "flat"])
@pytest.mark.parametrize("law", ["no-slip", "coulomb", "frictionless"])
def test_one_graph_serves_every_ground(leg, strike, law):
    """Friction and slope are inputs of the impact Function: one Impact moved to another
    ground (`at`) gives what an Impact built there gives, and the result says which ground."""
    slope, mu = np.radians(8.0), 0.45
    built_here = Impact(leg, strike, slope, mu, law=law)
    moved = Impact(leg, strike, 0.0, 0.8, law=law).at(mu, slope)
    assert moved.function is not built_here.function  # another graph, the same map
    for x in random_states(10, strike=strike, slope=slope):
        a, b = built_here(x), moved(x)
        assert (b.friction, b.slope) == (mu, slope)
        assert b.to_dict()["friction"] == mu and b.to_dict()["slope"] == slope
        assert a.T_c == b.T_c and a.valid == b.valid and a.checks == b.checks
        assert a.contact_laws == b.contact_laws


@pytest.mark.parametrize("friction, slope", [(-1.0, 0.0), (0.0, 0.0), (np.nan, 0.0), (np.inf, 0.0),
                                             (0.8, np.radians(70.0)), (0.8, np.nan)])
def test_a_ground_the_impact_cannot_take_is_refused(leg, friction, slope):
    from formopt.mechanics.errors import InputError
    with pytest.raises(InputError, match=r"friction|slope"):
        Impact(leg, "forefoot", slope, friction)
    with pytest.raises(InputError, match=r"friction|slope"):
        Impact(leg, "forefoot", 0.0, 0.8).at(friction, slope)


def test_checks_name_what_each_warning_is(leg):
    """valid follows the check codes: every check but the flat foot's split fails."""
    from formopt.mechanics.impact import INFORMATION, Check
    for strike in ("heel", "forefoot", "flat"):
        impact = Impact(leg, strike, 0.0, 0.8)
        for x in random_states(30, strike=strike):
            r = impact(x)
            assert len(r.checks) == len(r.warnings)
            assert r.valid == all(c in INFORMATION for c in r.checks)
            assert (Check.FLAT_SPLIT in r.checks) == (strike == "flat")
            assert r.to_dict()["checks"] == [c.value for c in r.checks]
