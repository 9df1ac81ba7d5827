"""The step builders of integrators.py against scipy's solve_ivp on the same dynamics, their
orders of accuracy, the step-size control and the event locator."""

import itertools
import math

import casadi as ca
import numpy as np
import pytest
from helpers import SHIPPED
from scipy.integrate import solve_ivp

from formopt import load
from formopt.mechanics import integrators
from formopt.mechanics.landing import LandingModel, simulate_state

T_END = 0.02  # s of a forefoot-pinned leg with spring-damper joints (the landing's contact phase)
SCHEMES = {"midpoint": (integrators.midpoint, 2), "rk4": (integrators.rk4, 4),
           "dormand_prince": (lambda f, x, t, h: integrators.dormand_prince(f, x, t, h)[0], 5)}


@pytest.fixture(scope="module")
def pinned():
    """x' = f(x, t) of the paper's leg held at the forefoot after its impact (the motion of
    dynamics.py with springs, dampers and Baumgarte terms), x0, and solve_ivp's x(T_END)."""
    scene = load(SHIPPED / "landing_spring.toml")
    lm = LandingModel(scene.model(), scene.joints, scene.slope, False, "adaptive", "no-slip")
    m = lm.model
    q0, qd0 = m.state_numeric(scene.state, "forefoot")
    joint = lm.joint_parameters(q0)
    qd0 = np.asarray(lm.impact_map(("forefoot",))(q0, qd0, joint, 0.8)[0], float).ravel()
    anchor = float(q0[m.cols("forefoot")] @ lm.t_axis)
    motion, n = lm.motion(("forefoot",)), m.n

    def f(x, t):
        out = motion(x[:n], x[n:2 * n], anchor, joint, 0, t, ca.DM.zeros(len(lm.hinges)))
        return ca.vertcat(out[0], out[1], out[3])

    X, T = ca.SX.sym("x", 2 * n + 1), ca.SX.sym("t")
    rhs = ca.Function("rhs", [X, T], [f(X, T)])
    x0 = np.concatenate([q0, qd0, [0.0]])
    ref = solve_ivp(lambda t, x: np.asarray(rhs(x, t), float).ravel(), (0.0, T_END), x0,
                    method="DOP853", rtol=1e-13, atol=1e-13)
    assert ref.success
    return f, x0, ref.y[:, -1], n


def integrate(f, x0, builder, steps):
    """x(T_END) by `steps` fixed steps of `builder` (a CasADi step Function of (x, t, h))."""
    X, T, H = ca.SX.sym("x", x0.size), ca.SX.sym("t"), ca.SX.sym("h")
    step = ca.Function("step", [X, T, H], [builder(f, X, T, H)])
    x, h = x0.copy(), T_END / steps
    for k in range(steps):
        x = np.asarray(step(x, k * h, h), float).ravel()
    return x


@pytest.mark.parametrize("scheme", SCHEMES)
def test_each_scheme_reaches_solve_ivp(pinned, scheme):
    """At 0.125 ms steps each scheme lands on DOP853 (rtol 1e-13) within its own error:
    h^2, h^4, h^5 times the solution's scale."""
    f, x0, reference, n = pinned
    builder, order = SCHEMES[scheme]
    x = integrate(f, x0, builder, 160)
    bound = {2: 5e-6, 4: 1e-10, 5: 1e-12}[order]
    assert np.max(np.abs(x - reference)[:2 * n]) < bound


@pytest.mark.parametrize("scheme", SCHEMES)
def test_order_of_accuracy(pinned, scheme):
    """The error against solve_ivp falls as h^p when h halves (5, 10, 20, 40 steps):
    measured slopes 2.04-2.16 (midpoint), 4.02-4.17 (RK4), 5.06-5.44 (Dormand-Prince)."""
    f, x0, reference, n = pinned
    builder, order = SCHEMES[scheme]
    errors = [np.max(np.abs(integrate(f, x0, builder, steps) - reference)[:2 * n])
              for steps in (5, 10, 20, 40)]
    slopes = [math.log2(a / b) for a, b in itertools.pairwise(errors)]
    assert all(order - 0.1 < s < order + 0.6 for s in slopes), slopes


def test_dormand_prince_error_estimate_tracks_the_true_error(pinned):
    """The embedded 4th-order estimate (in TOLERANCE units, 1 = accepted) bounds the local
    error of one step against solve_ivp from the same state."""
    f, x0, _, _ = pinned
    X, H = ca.SX.sym("x", x0.size), ca.SX.sym("h")
    x5, error = integrators.dormand_prince(f, X, 0.0, H)
    step = ca.Function("step", [X, H], [x5, error])
    X_, T_ = ca.SX.sym("x", x0.size), ca.SX.sym("t")
    rhs = ca.Function("rhs", [X_, T_], [f(X_, T_)])
    for h in (1e-3, 5e-4):
        exact = solve_ivp(lambda t, x: np.asarray(rhs(x, t), float).ravel(), (0.0, h), x0,
                          method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
        x_h, e = (np.asarray(v, float).ravel() for v in step(x0, h))
        true = np.max(np.abs(x_h - exact) / (integrators.TOLERANCE * (1 + np.abs(x0))))
        assert true <= e[0] + 1e-3


def test_fixed_steps_report_no_error():
    x = ca.SX.sym("x")
    for scheme in ("rk4", "midpoint"):
        assert integrators.step(scheme, lambda x, t: -x, x, 0.0, 0.1)[1] == 0


def test_step_control():
    """Rejected steps shrink by 0.9 e^-1/5, never below a tenth (or a tenth when the error is
    not finite); accepted ones grow by 0.9 e^-1/5, at most five times."""
    assert integrators.shrink(1.0, 32.0) == pytest.approx(0.45)
    assert integrators.shrink(1.0, 1e9) == pytest.approx(0.1)
    assert integrators.shrink(1.0, float("nan")) == pytest.approx(0.1)
    assert integrators.grow(1.0, 1.0) == pytest.approx(0.9)
    assert integrators.grow(1.0, 0.0) == pytest.approx(5.0)


def test_locate_finds_the_crossing():
    """g(s) = cos(s) - 1/2 on [0, 2] crosses at pi/3; an event already reached is at 0, one
    exactly at the end at h."""
    assert integrators.locate(lambda s: math.cos(s) - 0.5, 2.0) == pytest.approx(math.pi / 3, abs=1e-15)
    assert integrators.locate(lambda s: -s - 1.0, 1.0) == 0.0
    assert integrators.locate(lambda s: 1.0 - s, 1.0) == 1.0


def test_the_landing_strikes_at_the_ground():
    """The heel's impact of the spring landing is at the ground to within 1e-13 m, the
    tolerance the hand-written locator had on the event value (the adaptive integrator,
    where the event cuts a step)."""
    scene = load(SHIPPED / "landing_spring.toml")
    lm = LandingModel(scene.model(), scene.joints, scene.slope, False, "adaptive", "no-slip")
    L = simulate_state(lm, scene.strike, scene.state, scene.friction, scene.integration.dt,
                       scene.integration.duration)
    k = int(np.searchsorted(L.t, L.impacts[1].time))
    heel = L.q[k][lm.model.cols("heel")] @ lm.n_axis
    assert L.t[k] == L.impacts[1].time and abs(heel) < 1e-13
