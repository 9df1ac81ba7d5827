"""StrideSettings.grading: each phase's mesh graded toward both of its ends (transcription.fractions).
The setting's error; grading 0 the uniform mesh exactly; the graded schemes exact on the
polynomials they integrate and at their order on a smooth function; the NLP's objective the
quadrature on its own node times; a graded stride that solves with its checks closed; a guess
fitted between a uniform and a graded mesh at the right times; the trapezoid form's height bound
(StrideSettings.consistency_rows) on the held phase's last interval. The paper's body. No new
expression IPOPT sees beyond the schemes' constant weights: nothing for test_derivatives.py."""

import itertools
import math

import casadi as ca
import numpy as np
import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import GRAVITY, JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.contact import height
from formopt.optim.stride.guess import ballistic, fitted
from formopt.optim.stride.problem import RELEASE_DRIFT, RUNNER_TENDONS, SMOOTHING
from formopt.optim.stride.transcription import HermiteSimpson, Trapezoid, fractions, steps, times

SPEED = 3.5
GRADING = 0.9


@pytest.mark.parametrize("value", [-0.1, 1.5, math.nan, "0.5"])
def test_grading_is_between_0_and_1(value):
    with pytest.raises(InputError, match="grading"):
        StrideSettings(grading=value)


@pytest.mark.parametrize("scheme", [Trapezoid, HermiteSimpson])
def test_grading_0_is_the_uniform_mesh_exactly(scheme):
    """Ones for the steps and np.linspace for the times, bit for bit: the NLP of every shipped figure."""
    for n in (4, 7, 13):
        assert (steps(n, 0.0) == 1.0).all()
        assert (times(scheme, 0.37, n, 0.0) == np.linspace(0.0, 0.37, scheme.columns(n))).all()
        w = np.asarray(scheme.weights(0.37 / n, steps(n, 0.0)), float).ravel()
        classic = np.r_[0.5, np.ones(n - 1), 0.5] if scheme is Trapezoid else np.r_[1.0, np.tile([4.0, 2.0], n)[:-1], 1.0]
        before = 0.37 / n * ca.DM(classic).T if scheme is Trapezoid else 0.37 / n / 6 * ca.DM(classic).T  # main's
        assert (w == np.asarray(before, float).ravel()).all()


def test_the_map_grades_both_ends():
    """The fractions run from 0 to 1, symmetric, the end intervals (1 - g) + g n (1 - cos(pi/n)) / 2
    times a uniform one's and the middle ones longer; the steps sum to n."""
    n = 10
    tau, s = fractions(n, GRADING), steps(n, GRADING)
    assert tau[0] == 0.0 and tau[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.allclose(tau + tau[::-1], 1.0) and (np.diff(tau) > 0).all()
    assert s[0] == pytest.approx((1 - GRADING) + GRADING * n * (1 - math.cos(math.pi / n)) / 2)
    assert s[0] == pytest.approx(0.32, abs=0.01) and s[n // 2] > 1.3 and s.sum() == pytest.approx(n)


@pytest.mark.parametrize("scheme, power", [(Trapezoid, 2), (HermiteSimpson, 3)])
def test_graded_schemes_are_exact_on_their_polynomials(scheme, power):
    """On the graded mesh (the columns at `times`), a state x = t^power and its rate leave no
    defect and the quadrature integrates the rate exactly (the trapezoid: linear rates; Simpson's
    rule and Hermite's midpoint: cubic states); a power higher leaves defects (the mesh's own times
    in use, the midpoints at their intervals' middles)."""
    T, n = 0.3, 7
    t = times(scheme, T, n, GRADING)
    h, s = T / n, steps(n, GRADING)

    def defects(p):
        X, D = ca.DM(t ** p).T, ca.DM(p * t ** (p - 1)).T
        return np.abs(np.asarray(scheme.defects(X, D, h, s), float)).max()

    integral = float(np.asarray(scheme.weights(h, s), float).ravel() @ (power * t ** (power - 1)))
    assert defects(power) < 1e-15 and integral == pytest.approx(T ** power, abs=1e-15)
    assert defects(power + 1) > 1e-9


@pytest.mark.parametrize("scheme, order", [(Trapezoid, 2), (HermiteSimpson, 4)])
def test_graded_quadrature_converges_at_its_order(scheme, order):
    """int_0^T cos(t / tau) dt on graded meshes of n and 2n intervals: the error falls by 2^order."""
    T, tau = 0.3, 0.05
    errors = []
    for n in (8, 16, 32):
        t = times(scheme, T, n, GRADING)
        w = np.asarray(scheme.weights(T / n, steps(n, GRADING)), float).ravel()
        errors.append(abs(w @ np.cos(t / tau) - tau * math.sin(T / tau)))
    observed = [math.log2(a / b) for a, b in itertools.pairwise(errors)]
    assert all(abs(p - order) < 0.3 for p in observed), observed


@pytest.fixture(scope="module")
def graded():
    """A heel strike with springs on a graded trapezoid of 30 intervals, and the uniform one (at
    20 graded intervals its drift was 9 mm: the middle intervals 1.4 times a uniform one's)."""
    js = JointSpace(paper_body())
    return tuple(StrideNLP(js, StrideSettings(strike="heel", nodes=30, tendons=RUNNER_TENDONS, grading=g))
                 for g in (GRADING, 0.0))


def test_the_objective_is_the_quadrature_on_the_graded_times(graded):
    """At the generic guess the NLP's objective (torque+springs, effort) equals the trapezoid on
    the columns' own times, sum (t_k+1 - t_k) (f_k + f_k+1) / 2 of the squared moments, and the
    smoothing sum (t_k+1 - t_k) |A_k+1 - A_k|^2, per step length (100 / (m g)^2 and SMOOTHING)."""
    nlp = graded[0]
    guess = ballistic(nlp, SPEED)
    f = ca.Function("f", [nlp.problem["x"], nlp.problem["p"]], [nlp.problem["f"]])
    value = float(f(nlp.blocks.join(nlp._with_power_split(guess)), [SPEED, 0.0, 0.8]))
    effort = smooth = 0.0
    for i, phase in enumerate(nlp.phases):
        t = nlp.times(i, guess[f"T_{phase.name}"])
        dt = np.diff(t)
        assert dt[0] < 0.5 * dt[len(dt) // 2], "not graded"
        squares = np.sum(nlp.moments(guess, i)[0] ** 2, axis=0)  # the active moments' (N m)
        effort += dt @ (squares[:-1] + squares[1:]) / 2
        A = guess[f"A_{phase.name}"]
        smooth += dt @ np.sum(np.diff(A, axis=1) ** 2, axis=0)
    d = SPEED * sum(guess[f"T_{p.name}"] for p in nlp.phases)
    expected = 100 * effort / (nlp.mass * GRAVITY) ** 2 / d + SMOOTHING * smooth / d
    assert value == pytest.approx(expected, rel=1e-12)


def test_a_graded_stride_solves_with_its_checks_closed(graded):
    """The graded stride converges, its forward check within its tolerance, its energy budget
    closed and its histories' times the graded columns'."""
    nlp = graded[0]
    stride = optimum(nlp, SPEED)
    assert stride.success and stride.valid, stride.failed_checks
    assert stride.checks["balance_relative"] < 1e-3
    T = stride.phases[0][1]
    assert np.allclose(stride.t[:nlp.columns[0]], nlp.times(0, T))


def test_a_guess_fitted_between_meshes_keeps_its_times(graded):
    """Node histories linear in each phase's time, fitted from the uniform mesh onto the graded
    one (and back, and onto a mesh twice as fine): the same lines at the new columns' times."""
    fine = StrideNLP(graded[0].js, StrideSettings(strike="heel", nodes=60, tendons=RUNNER_TENDONS, grading=GRADING))

    def lines(nlp):
        return {f"X_{p.name}": np.vstack([1.0 + 2.0 * nlp.times(i, 0.1), -3.0 * nlp.times(i, 0.1)])
                for i, p in enumerate(nlp.phases)}

    for target, source in ((graded[0], graded[1]), (graded[1], graded[0]), (fine, graded[0])):
        got = fitted(target, lines(source), source)
        for name, value in lines(target).items():
            assert np.allclose(got[name], value, atol=1e-14), (target.settings.grading, name)
    own = lines(graded[0])
    for name, value in fitted(graded[0], own).items():  # its own mesh by default: unchanged
        assert (value == own[name]).all(), name


def test_a_trapezoid_guess_fits_a_hermite_simpson_nlp_without_its_source():
    """A trapezoid's node histories (phases of 5 and 6 intervals: an even column count no
    Hermite-Simpson phase has) fitted onto Hermite-Simpson's columns without naming their NLP
    (local.optimum's guess): the same lines, as main's resampling did (it raised here)."""
    js = JointSpace(paper_body())
    nlps = [StrideNLP(js, StrideSettings(strike="heel", nodes=20, transcription=t)) for t in ("trapezoid", "hermite-simpson")]

    def lines(nlp):
        return {f"X_{p.name}": np.vstack([1.0 + 2.0 * nlp.times(i, 0.1), -3.0 * nlp.times(i, 0.1)])
                for i, p in enumerate(nlp.phases)}

    assert any(c % 2 == 0 for c in nlps[0].columns)
    got = fitted(nlps[1], lines(nlps[0]))
    for name, value in lines(nlps[1]).items():
        assert np.allclose(got[name], value, atol=1e-14), name


def test_the_trapezoid_forms_height_bound_is_on_the_held_phases_last_interval():
    """consistency_rows "trapezoid" on a graded mesh: each released point's row at the next
    phase's first column is its height + RELEASE_DRIFT h^2 with h the held phase's last interval,
    T (1 - tau_n-1) (0.53 of the uniform T / n at g 0.9 and n 5), not T / n."""
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=20, tendons=RUNNER_TENDONS,
                                                             consistency_rows="trapezoid", grading=GRADING))
    guess = ballistic(nlp, SPEED)
    g = ca.Function("g", [nlp.problem["x"], nlp.problem["p"]], [nlp.problem["g"]])
    values = np.asarray(g(nlp.blocks.join(nlp._with_power_split(guess)), [SPEED, 0.0, 0.8]), float).ravel()
    bounded = values[(nlp.lbg == 0.0) & np.isinf(nlp.ubg)]
    released = 0
    for i, (before, after) in enumerate(itertools.pairwise(nlp.phases), 1):
        if nlp.impact_before(i):
            continue
        T, n = guess[f"T_{before.name}"], nlp.split[i - 1]
        last = T * (1 - fractions(n, GRADING)[-2])
        assert last < 0.6 * T / n
        theta = ca.DM(guess[f"X_{after.name}"][:len(guess["V_touchdown"]), 0])
        for point in set(before.points) - set(after.points):
            y = float(height(nlp.js, point, theta, 0.0))
            assert np.isclose(bounded, y + RELEASE_DRIFT * last ** 2, rtol=0, atol=1e-12).sum() == 1, point
            assert not np.isclose(bounded, y + RELEASE_DRIFT * (T / n) ** 2, rtol=0, atol=1e-12).any(), point
            released += 1
    assert released == 2
