"""Contact laws at the impact (mechanics/contact.py): invariants, limits, and two
independent checks of the Coulomb impulse."""

import casadi as ca
import numpy as np
import pytest

from formopt.mechanics import contact
from formopt.mechanics.impact import impact_function
from helpers import random_states

MUS = (0.2, 0.5, 0.8, 1.5, 4.0)


def outputs(leg, strike, mu, states):
    f = impact_function(leg, strike, friction=mu)
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
    f = impact_function(leg, strike, friction=0.6, outputs=["T_c", "impulse", "slip", "mode"],
                        law="coulomb")
    x = ca.SX.sym("x", f.size1_in(0))
    out = f(x=x)
    values = ca.vertcat(out["T_c"], out["impulse"], out["slip"])
    jac = ca.Function("jacobian_of_coulomb", [x], [values, ca.jacobian(values, x), out["mode"]])
    seen = set()
    for state in random_states(60, seed=5, strike=strike):
        v, J, mode = (np.asarray(a, float) for a in jac(state))
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
    f = impact_function(leg, "forefoot", friction=0.8, law="coulomb",
                        outputs=["T_c", "T", "T_a", "impulse", "qd_minus", "qd_plus"])
    for x in random_states(20, seed=9):
        o = {k: np.asarray(v, float).ravel() for k, v in f(x=x).items()}
        assert o["T"] - o["T_a"] == pytest.approx(o["T_c"], rel=1e-9, abs=1e-12)


def test_eq7_is_the_friction_of_a_touchdown_with_no_tangential_velocity(leg):
    """mu_posture = W_tn / W_tt: the no-slip impulse ratio when the contact point's
    tangential velocity at touchdown is zero."""
    f = impact_function(leg, "forefoot", outputs=["mu_posture"])
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

    r = Impact(build_model(body, "effective-mass"), "forefoot", np.radians(10.0))(
        random_states(1, seed=2)[0])
    assert r.mu_c == pytest.approx(np.tan(np.radians(10.0)), rel=1e-9)
    assert r.mu_c_momentum == pytest.approx(r.mu_c, rel=1e-9)


def test_impact_json_shows_every_law(tmp_path):
    import json
    import subprocess
    import sys

    from helpers import PROBLEMS

    text = (PROBLEMS / "forefoot_strike.toml").read_text().replace(
        "friction = 0.8", 'friction = 0.8\ncontact = "coulomb"')
    scene = tmp_path / "coulomb.toml"
    scene.write_text(text)
    out = subprocess.run([sys.executable, "-m", "formopt.cli", "impact", str(scene), "--json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout)
    assert set(report["contact_laws"]) == set(contact.LAWS) and report["law"] == "coulomb"
    coulomb = report["contact_laws"]["coulomb"]
    assert report["T_c"] == coulomb["T_c"] < report["contact_laws"]["no-slip"]["T_c"]
    assert coulomb["mode"] == "slide" and coulomb["slip_velocity"] > 3.0 and coulomb["valid"]
    assert {"T_c", "impulse", "mode", "slip_velocity", "dv_trunk", "dv_com", "valid"} <= set(coulomb)
    assert report["mu_c_posture"] > 0 and report["valid"]
