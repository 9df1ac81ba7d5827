"""Contact laws at the impact (mechanics/contact.py): invariants, limits, and two
independent checks of the Coulomb impulse."""

import casadi as ca
import numpy as np
import pytest
from helpers import random_states

from formopt.mechanics import contact
from formopt.mechanics.impact import impact_function, on_ground

MUS = (0.2, 0.5, 0.8, 1.5, 4.0)


def outputs(leg, strike, mu, states):
    f = on_ground(impact_function(leg, strike), mu, 0.0)
    keys = ("T_c_no_slip", "T_c_coulomb", "T_c_frictionless", "impulse_coulomb",
            "mode_coulomb", "approach", "impulse_no_slip")
    out = {k: [] for k in keys}
    for x in states:
        o = f(x=x)
        for k in keys:
            out[k].append(np.asarray(o[k], float).ravel())
    return {k: np.array(v) for k, v in out.items()}


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
@pytest.mark.parametrize("mu", MUS)
def test_coulomb_invariants(leg, strike, mu):
    o = outputs(leg, strike, mu, random_states(300, strike=strike))
    approaching = o["approach"][:, 0] < 0
    ns, cb, fl = (o[k][approaching, 0] for k in ("T_c_no_slip", "T_c_coulomb", "T_c_frictionless"))
    p = o["impulse_coulomb"][approaching]
    mode = o["mode_coulomb"][approaching, 0]
    scale = np.maximum(ns, 1.0)
    assert np.all(cb <= ns + 1e-9 * scale)  # T_c(no-slip) - T_c(p) = 1/2 |p - p_ns|^2_Wc >= 0
    assert np.all(cb >= -1e-12) and np.all(fl >= -1e-12)  # no energy is created
    assert np.all(p[:, 1] >= -1e-12)  # the ground pushes
    assert np.all(np.abs(p[:, 0]) <= mu * p[:, 1] * (1 + 1e-9) + 1e-12)  # inside the cone
    forward = mode != contact.REVERSE
    assert np.all(fl[forward] <= cb[forward] + 1e-9 * scale[forward])  # typical, not a law
    stick = mode == contact.STICK  # ends with v = 0: the no-slip impulse
    np.testing.assert_allclose(cb[stick], ns[stick], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(p[stick], o["impulse_no_slip"][approaching][stick], rtol=1e-7,
                               atol=1e-10)


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
def test_coulomb_limits_in_mu(leg, strike):
    """As mu falls Coulomb tends to frictionless. As mu grows it converges, to no-slip wherever
    the point sticks; not everywhere: where the friction impulse lifts the point (s b < 0 and
    |v_t| |b| > |v_n| a), the normal velocity reaches zero first and the point leaves sliding
    however large mu is (38 % of these random heel states, 6 % of forefoot ones)."""
    states = random_states(100, strike=strike)
    high, higher = outputs(leg, strike, 1e5, states), outputs(leg, strike, 1e7, states)
    low = outputs(leg, strike, 1e-9, states)
    approaching = high["approach"][:, 0] < 0
    np.testing.assert_allclose(high["T_c_coulomb"][approaching], higher["T_c_coulomb"][approaching],
                               rtol=1e-3)
    stick = approaching & (higher["mode_coulomb"][:, 0] == contact.STICK)
    assert stick.mean() > 0.5
    np.testing.assert_allclose(higher["T_c_coulomb"][stick], higher["T_c_no_slip"][stick], rtol=1e-8)
    np.testing.assert_allclose(low["T_c_coulomb"][approaching], low["T_c_frictionless"][approaching],
                               rtol=1e-6)


def darboux_keller(W_c, v0, mu, steps=2000):
    """The Coulomb impulse by integrating dv = W_c dp with p_n as the clock, in fine steps;
    the switch where v_t crosses zero is located exactly within its step."""
    W_c, v = np.asarray(W_c, float), np.asarray(v0, float).copy()
    p = np.zeros(2)
    h = 4.0 * abs(v[1]) / W_c[1, 1] / steps  # covers any impact with room to spare
    sticking = False
    for _ in range(50 * steps):
        if sticking:
            d = np.array([-W_c[0, 1] / W_c[0, 0], 1.0])
        else:
            d = np.array([-mu * np.sign(v[0]), 1.0])
        dv = W_c @ d
        step = h
        if not sticking and v[0] != 0 and np.sign(v[0] + dv[0] * h) != np.sign(v[0]):
            step = -v[0] / dv[0]  # the tangential velocity reaches zero inside this step
        if v[1] + dv[1] * step >= 0 and dv[1] > 0:
            step = min(step, -v[1] / dv[1])  # the impact ends
            p, v = p + d * step, v + dv * step
            return p
        p, v = p + d * step, v + dv * step
        if not sticking and abs(v[0]) < 1e-14 * max(1.0, abs(v0[0])):
            v[0] = 0.0
            sticking = abs(W_c[0, 1]) <= mu * W_c[0, 0]
            if not sticking:
                v[0] = np.sign(W_c[0, 1]) * 1e-300  # slides on in the direction of b
    raise AssertionError("the integration did not end")


@pytest.mark.parametrize("mu", (0.3, 0.8, 2.5, 8.0))
def test_coulomb_matches_integrated_darboux_keller_equations(mu):
    W_c, v0 = ca.SX.sym("W", 2, 2), ca.SX.sym("v", 2)
    closed = ca.Function("coulomb", [W_c, v0], list(contact.coulomb(W_c, v0, mu)))
    rng = np.random.default_rng(3)
    modes = set()
    for _ in range(25):
        L = rng.normal(size=(2, 2))
        W = L @ L.T + 0.1 * np.eye(2)
        v = np.array([rng.uniform(-3, 3), rng.uniform(-2, -0.1)])
        p, mode, _ = (np.asarray(a, float).ravel() for a in closed(W, v))
        modes.add(int(mode[0]))
        np.testing.assert_allclose(p, darboux_keller(W, v, mu), rtol=1e-6, atol=1e-9)
    assert len(modes) >= 2, "the draws reach more than one mode"


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
def test_coulomb_gradients_match_finite_differences_in_each_mode(leg, strike):
    f = on_ground(impact_function(leg, strike, outputs=["T_c", "impulse", "slip", "mode"],
                                  law="coulomb"), 0.6, 0.0)
    x = ca.SX.sym("x", f.size1_in(0))
    out = f(x=x)
    values = ca.vertcat(out["T_c"], out["impulse"], out["slip"])
    jac = ca.Function("jacobian_of_coulomb", [x], [values, ca.jacobian(values, x), out["mode"]])
    seen = set()
    for state in random_states(60, seed=5, strike=strike):
        _v, J, mode = (np.asarray(a, float) for a in jac(state))
        h = 1e-6
        numeric = np.column_stack([
            (np.asarray(jac(state + h * e)[0], float) - np.asarray(jac(state - h * e)[0], float)).ravel() / (2 * h)
            for e in np.eye(len(state))])
        same_mode = all(int(np.asarray(jac(state + s * h * e)[2])[0, 0]) == int(mode[0, 0])
                        for e in np.eye(len(state)) for s in (1, -1))
        if not same_mode:
            continue  # at a switch the derivative is one-sided
        seen.add(int(mode[0, 0]))
        np.testing.assert_allclose(J, numeric, rtol=1e-5, atol=1e-6 * max(1.0, np.abs(J).max()))
    assert seen, "some states away from a switch"


def test_absorbed_energy_is_tied_to_impulse_and_velocities(leg):
    f = on_ground(impact_function(leg, "forefoot", law="coulomb",
                                  outputs=["T_c", "T", "T_a", "impulse", "qd_minus", "qd_plus"]), 0.8, 0.0)
    for x in random_states(20, seed=9):
        o = {k: np.asarray(v, float).ravel() for k, v in f(x=x).items()}
        assert o["T"] - o["T_a"] == pytest.approx(o["T_c"], rel=1e-9, abs=1e-12)


def test_eq7_is_the_friction_of_a_touchdown_with_no_tangential_velocity(leg):
    """mu_posture = W_tn / W_tt: the no-slip impulse ratio when the contact point's
    tangential velocity at touchdown is zero."""
    f = on_ground(impact_function(leg, "forefoot", outputs=["mu_posture"]), 0.8, 0.0)
    W_c, v0 = ca.SX.sym("W", 2, 2), ca.SX.sym("v", 2)
    ns = ca.Function("ns", [W_c, v0], [contact.no_slip(W_c, v0)])
    W = np.array([[0.8, 0.5], [0.5, 0.9]])
    p = np.asarray(ns(W, [0.0, -1.0]), float).ravel()
    assert abs(p[0] / p[1]) == pytest.approx(0.5 / 0.8)
    assert np.isfinite(float(f(x=random_states(1)[0])["mu_posture"]))


def test_effective_mass_on_a_slope_needs_tan_slope(body):
    """The effective mass moves vertically: the ground's impulse on it is vertical, so on a
    10 deg slope both eq. 8 and its momentum check give |t| / n = tan(10 deg)."""
    from formopt.mechanics.impact import Impact
    from formopt.mechanics.model import build_model

    r = Impact(build_model(body, "effective-mass"), "forefoot", np.radians(10.0), 0.8)(
        random_states(1, seed=2)[0])
    assert r.mu_c == pytest.approx(np.tan(np.radians(10.0)), rel=1e-9)
    assert r.mu_c_momentum == pytest.approx(r.mu_c, rel=1e-9)


def test_impact_json_shows_every_law(tmp_path, capfd):
    import json

    from helpers import SHIPPED

    from formopt.cli import main

    text = (SHIPPED / "forefoot_strike.toml").read_text().replace(
        "friction = 0.8", 'friction = 0.8\ncontact = "coulomb"')
    scene = tmp_path / "coulomb.toml"
    scene.write_text(text)
    assert main(["impact", str(scene), "--json"]) == 0
    report = json.loads(capfd.readouterr().out)  # file descriptor 1 holds the JSON alone
    assert set(report["contact_laws"]) == set(contact.LAWS) and report["law"] == "coulomb"
    coulomb = report["contact_laws"]["coulomb"]
    assert report["T_c"] == coulomb["T_c"] < report["contact_laws"]["no-slip"]["T_c"]
    assert coulomb["mode"] == "slide" and coulomb["slip_velocity"] > 3.0 and coulomb["valid"]
    assert {"T_c", "impulse", "mode", "slip_velocity", "dv_trunk", "dv_com", "valid"} <= set(coulomb)
    assert report["mu_c_posture"] > 0 and report["valid"]


def compliant_impulse(model, strike, x, mu, stiffness, regularisation=1e-3):
    """The ground's impulse (N s, [t, n]) over the compression of a compliant contact: a
    linear spring of `stiffness` (N/m) along the normal and the regularised Coulomb force
    -mu f_n tanh(v_t / regularisation) along the ground, integrated in natural coordinates
    (positions move during the contact) until the normal velocity is zero again: the end of
    a perfectly plastic (e = 0) impact. Gravity is left out; its impulse vanishes with the
    contact's duration."""
    from scipy.integrate import solve_ivp
    q0, qd0 = model.state_numeric(x, strike)
    y = ca.SX.sym("y", 2 * model.n + 2)
    q, qd = y[:model.n], y[model.n:2 * model.n]
    C = ca.DM(model.contact_rows((strike,), 0.0))
    depth = -(C[1, :] @ q - float(C[1, :] @ q0))
    v = C @ qd
    force = ca.vertcat(-mu * stiffness * depth * ca.tanh(v[0] / regularisation), stiffness * depth)
    phi = model.constraints(q)
    Phi, M_inv = ca.jacobian(phi, q), ca.DM(model.M_inv)
    Q, phid, a = C.T @ force, Phi @ qd, 1e4  # a: Baumgarte rate, 1/s
    gamma = -ca.jtimes(phid, q, qd) - 2 * a * phid - a * a * phi
    qdd = M_inv @ (Q + Phi.T @ ca.solve(Phi @ M_inv @ Phi.T, gamma - Phi @ (M_inv @ Q)))
    rhs = ca.vertcat(qd, qdd, force)
    # three Functions, so that each call evaluates only what it returns (the Jacobian at every
    # right-hand side took half of the test's 5 s of CPU)
    f, jac, normal = (ca.Function(name, [y], [e]) for name, e in
                      (("compliant", rhs), ("jacobian", ca.jacobian(rhs, y)), ("normal", v[1])))

    def rebound(t, state):
        return float(normal(state))
    rebound.terminal, rebound.direction = True, 1
    sol = solve_ivp(lambda t, s: np.asarray(f(s), float).ravel(), (0.0, 0.5),
                    np.concatenate([q0, qd0, [0.0, 0.0]]), method="Radau",
                    jac=lambda t, s: np.asarray(jac(s), float), events=rebound, rtol=1e-9,
                    atol=1e-12)
    assert sol.status == 1, "the compression phase ends"
    return sol.y[-2:, -1]


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
@pytest.mark.parametrize("mu", (0.3, 0.8))
def test_compliant_contact_converges_to_the_coulomb_impulse(leg, strike, mu):
    """As the contact stiffens (1e5, 1e6, 1e7 N/m) the compliant impulse approaches the
    closed form, about as stiffness^-1/2 (the configuration moves for sqrt(m/k)); within
    2 % at 1e7 N/m. Both modes occur among these states (slide, and stick for the forefoot
    at mu 0.8)."""
    f = on_ground(impact_function(leg, strike, law="coulomb", outputs=["impulse", "approach"]), mu, 0.0)
    for x in random_states(2, seed=11, strike=strike):
        p, approach = (np.asarray(a, float).ravel() for a in f(x))
        assert approach[0] < 0
        errors = [np.max(np.abs(compliant_impulse(leg, strike, x, mu, k) - p)) / np.max(np.abs(p))
                  for k in (1e5, 1e6, 1e7)]
        assert errors[0] > errors[1] > errors[2]
        assert errors[2] < 0.02


@pytest.mark.parametrize("strike", ["heel", "forefoot"])
@pytest.mark.parametrize("mu", (0.3, 0.8, 2.0))
def test_velocity_level_law_equals_darboux_keller_outside_a_reversed_slide(leg, strike, mu):
    f = on_ground(impact_function(leg, strike, law="coulomb",
                                  outputs=["W_c", "v_contact", "impulse", "mode", "approach"]), mu, 0.0)
    W, v = ca.SX.sym("W", 2, 2), ca.SX.sym("v", 2)
    velocity_level = ca.Function("velocity_level", [W, v], list(contact.velocity_level(W, v, mu)))
    compared = 0
    for x in random_states(200, strike=strike):
        W_c, v0, p, mode, approach = f(x)
        if float(approach[0]) >= 0 or int(mode) == contact.REVERSE:
            continue
        p_v, mode_v, _ = velocity_level(W_c, v0)
        np.testing.assert_allclose(np.asarray(p_v).ravel(), np.asarray(p).ravel(), rtol=1e-8, atol=1e-10)
        assert int(mode_v) == int(mode)
        compared += 1
    assert compared > 150


def test_flat_strike_under_coulomb_keeps_the_invariants(leg):
    """Two contacts, the velocity-level law: inside the cone, pushing, no more than no-slip."""
    f = on_ground(impact_function(leg, "flat", law="coulomb"), 0.5, 0.0)
    for x in random_states(100, strike="flat"):
        o = f(x=x)
        if np.any(np.asarray(o["approach"]) >= 0):
            continue
        p = np.asarray(o["impulse_coulomb"], float).reshape(-1, 2)
        t, n = p.sum(axis=0)
        assert abs(t) <= 0.5 * n * (1 + 1e-9)
        assert float(o["T_c_coulomb"]) <= float(o["T_c_no_slip"]) * (1 + 1e-9) + 1e-12
        assert float(o["T_c_coulomb"]) >= -1e-12
