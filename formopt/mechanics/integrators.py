"""One step of x' = f(x, t) as a CasADi expression, its step-size control, and event location.

The step builders take any right-hand side f(x, t) -> x' that accepts CasADi (SX or MX)
arguments and return the state after a step h from (x, t):

- `midpoint`: x+ = x + h f(x + h/2 f(x, t), t + h/2) (2nd order);
- `rk4`: the classical Runge-Kutta method (4th order);
- `dormand_prince`: Dormand & Prince (1980) 5(4), the 5th-order solution and the embedded
  4th-order error estimate e, returned as max_i |e_i| / (tol (1 + |x_i|)): 1 is the largest
  accepted local error (absolute and relative tolerance `tol`).

`INTEGRATORS` names them for a scene: "adaptive" (Dormand-Prince with the step controlled by
`shrink` / `grow`, up to dt between events), "rk4" and "midpoint" at a fixed dt.
`locate` finds the step length at which an event function crosses zero (scipy's brentq).
"""

from __future__ import annotations

from collections.abc import Callable

import casadi as ca
import numpy as np

INTEGRATORS = ("adaptive", "rk4", "midpoint")
DEFAULT_INTEGRATOR = "adaptive"  # the one default of mechanics and scenes
TOLERANCE = 1e-8  # adaptive: largest local error per step, absolute and relative (m, m/s, J)
EVENT_TOLERANCE = 1e-15  # s: an event's time, located to this (and 4 eps relative)
# Dormand & Prince (1980) 5(4): nodes, stage coefficients, 5th- and 4th-order weights
DP_C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
DP_A = ((), (1 / 5,), (3 / 40, 9 / 40), (44 / 45, -56 / 15, 32 / 9),
        (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
        (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
        (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84))
DP_B5 = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0)
DP_B4 = (5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40)

Rhs = Callable[[ca.SX, ca.SX], ca.SX]


def midpoint(f: Rhs, x, t, h):
    """x(t + h) by the midpoint rule: x + h f(x + h/2 f(x, t), t + h/2)."""
    return x + h * f(x + h / 2 * f(x, t), t + h / 2)


def rk4(f: Rhs, x, t, h):
    """x(t + h) by the classical Runge-Kutta method: x + h/6 (k1 + 2 k2 + 2 k3 + k4)."""
    k1 = f(x, t)
    k2 = f(x + h / 2 * k1, t + h / 2)
    k3 = f(x + h / 2 * k2, t + h / 2)
    k4 = f(x + h * k3, t + h)
    return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def dormand_prince(f: Rhs, x, t, h, tol: float = TOLERANCE):
    """(x(t + h), error) by Dormand-Prince 5(4): x5 = x + h sum b5_i k_i, e = h sum (b5_i -
    b4_i) k_i, error = max_i |e_i| / (tol (1 + |x_i|)) (accept the step when error <= 1)."""
    k: list = []  # the stages k_i, as x
    for c, a in zip(DP_C, DP_A):
        k.append(f(x + h * sum((a_i * k_i for a_i, k_i in zip(a, k)), ca.SX.zeros(x.shape)),
                   t + c * h))
    x5 = x + h * sum((b * k_i for b, k_i in zip(DP_B5, k) if b), ca.SX.zeros(x.shape))
    e = h * sum((b5 - b4) * k_i for b5, b4, k_i in zip(DP_B5, DP_B4, k))
    return x5, ca.mmax(ca.fabs(e) / (tol * (1 + ca.fabs(x))))


def step(scheme: str, f: Rhs, x, t, h):
    """(x(t + h), error) by `scheme` (INTEGRATORS): the error estimate of "adaptive" in units
    of TOLERANCE, zero for the fixed-step schemes."""
    if scheme == "midpoint":
        return midpoint(f, x, t, h), 0
    if scheme == "rk4":
        return rk4(f, x, t, h), 0
    return dormand_prince(f, x, t, h)


def shrink(h: float, error: float) -> float:
    """The next try after a rejected adaptive step (error > 1): h max(0.1, 0.9 error^-1/5)."""
    return h * (max(0.1, 0.9 * error ** -0.2) if np.isfinite(error) else 0.1)


def grow(h: float, error: float) -> float:
    """The step after an accepted one: h min(5, 0.9 error^-1/5)."""
    return h * min(5.0, 0.9 * max(error, 1e-12) ** -0.2)


def locate(g: Callable[[float], float], h: float) -> float:
    """The step length s in [0, h] at which g (positive at 0, at most zero at h) reaches zero,
    by Brent's method to EVENT_TOLERANCE; 0 when g is not positive at 0 (already there)."""
    g_hi = g(h)
    if g_hi == 0.0:
        return h
    if not g(0.0) > 0.0:
        return 0.0
    from scipy.optimize import brentq  # here: scipy.optimize costs 0.3 s at every CLI start

    return brentq(g, 0.0, h, xtol=EVENT_TOLERANCE, rtol=4 * np.finfo(float).eps)
