"""Shared helpers of the tests and benchmarks: seeded random touchdown states, the reference
touchdown, the paper's leg in other natural coordinates, a landing with another step."""

from dataclasses import replace
from pathlib import Path

import casadi as ca
import numpy as np

import formopt
from formopt.mechanics.model import STATE, Model, Point, PointMass, RigidBody
from formopt.optim.stride import forward_checked

SEED = 20261122
ROOT = Path(__file__).resolve().parent.parent  # the repository
PROBLEMS = ROOT / "problems"  # the scripts
SHIPPED = ROOT / "formopt" / "scenes"  # the shipped scenes (package data)
DATA = ROOT / "data"  # the real trials shipped with the repository (data/README.md)
DEG = np.pi / 180


def random_states(n, seed=SEED, strike="forefoot", slope=0.0):
    """Touchdown states spanning running (angles in rad, velocities in m/s and rad/s)."""
    rng = np.random.default_rng(seed)
    x = np.zeros((n, len(STATE)))
    lo = np.array([-10, 0, 2, -30, 1.0, -1.5, -100, -400, -200, -200]) * 1.0
    hi = np.array([20, 40, 60, 20, 7.0, -0.2, 100, 100, 400, 300]) * 1.0
    x[:] = rng.uniform(lo, hi, size=(n, len(STATE)))
    angles = [0, 1, 2, 3, 6, 7, 8, 9]
    x[:, angles] *= DEG
    if strike == "flat":  # sole parallel to the ground: hip - trunk - knee + ankle = slope
        x[:, 3] = x[:, 0] - x[:, 1] + x[:, 2] + slope
    return x


def touchdown(trunk=0.0, hip=22.0, knee=18.0, ankle=-12.0, v=(3.5, -0.6), w=(0.0, -150.0, 120.0, 40.0)):
    """The reference touchdown of issue 2 (degrees and deg/s in, SI out)."""
    return np.array([trunk * DEG, hip * DEG, knee * DEG, ankle * DEG, v[0], v[1],
                     *(np.array(w) * DEG)])


def split_leg(body) -> Model:
    """The paper's leg in other natural coordinates: knee points per segment joined by a
    coincidence constraint, the thigh based knee->hip, the foot based forefoot->heel with the
    ankle fixed in it (12 coordinates, 7 constraints)."""
    points = [Point("hip", "hip"), Point("knee_t", "knee"), Point("knee_s", "knee"),
              Point("ankle", "ankle"), Point("heel", "heel"), Point("forefoot", "forefoot")]
    bodies = [RigidBody("thigh", ("knee_t", "hip")), RigidBody("shank", ("knee_s", "ankle")),
              RigidBody("foot", ("forefoot", "heel"), ("ankle",))]
    return Model(body, points, bodies, [PointMass("trunk", "hip"), PointMass("swing_leg", "hip")],
                 coincident=[("knee_t", "knee_s")], trunk="trunk")


def land(scene, dt=None):
    """The scene's landing (formopt.simulate), with another integration step if given (s)."""
    if dt is not None:
        scene = replace(scene, integration=replace(scene.integration, dt=dt))
    return formopt.simulate(scene)


def assert_nlp_derivatives(problem, points, h=1e-5, hessian=True):
    """The posture NLP's gradient, constraint Jacobian (and Hessian of the objective) match
    central differences at each scaled point u."""
    nlp = ca.Function("nlp", [problem.nlp["x"], problem.nlp["p"]],
                      [problem.nlp["f"], problem.nlp["g"]])
    u = ca.SX.sym("u", len(problem.index))
    f, g = nlp(u, problem.p0)
    jac = ca.Function("jacobians", [u], [ca.gradient(f, u), ca.jacobian(g, u), ca.hessian(f, u)[0]])
    for u0 in points:
        grad, J, H = (np.asarray(a, float) for a in jac(u0))
        for k in range(u0.size):
            e = np.zeros_like(u0)
            e[k] = h
            fp, gp = (np.asarray(a, float).ravel() for a in nlp(u0 + e, problem.p0))
            fm, gm = (np.asarray(a, float).ravel() for a in nlp(u0 - e, problem.p0))
            assert abs((fp[0] - fm[0]) / (2 * h) - grad[k, 0]) < 1e-6 * max(1, abs(grad[k, 0]))
            np.testing.assert_allclose((gp - gm) / (2 * h), J[:, k], rtol=1e-5, atol=1e-6)
            if hessian:
                gradp = np.asarray(jac(u0 + e)[0], float).ravel()
                gradm = np.asarray(jac(u0 - e)[0], float).ravel()
                np.testing.assert_allclose((gradp - gradm) / (2 * h), H[:, k], rtol=1e-5, atol=1e-5)


def central_difference(f, x, h=1e-4):
    """Fourth-order central differences: truncation O(h^4), rounding O(eps / h)."""
    cols = []
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        cols.append((-f(x + 2 * e) + 8 * f(x + e) - 8 * f(x - e) + f(x - 2 * e)) / (12 * h))
    return np.column_stack(cols)


def forward_check_again(nlp, stride):
    """The stride's forward check taken off and added again by optim.stride.forward_checked
    (compare's free optima): the stride with it, and the keys taken off."""
    forward = [k for k in stride.checks if k.startswith(("forward_", "open_loop_"))]
    bare = replace(stride, checks={k: v for k, v in stride.checks.items() if k not in forward})
    return forward_checked(nlp, bare), forward
