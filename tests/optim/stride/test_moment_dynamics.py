"""Moment dynamics (StrideSettings.moment_time = T > 0): the torque rungs' joint moments are
states z (N m/kg), their rates the controls (z' = MOMENT_RATE_SCALE u), and the objective adds
T^2 times the effort's scale times int |tau'|^2 dt per distance. The setting's errors, the NLP's
blocks and rows, the rate term against its formula written here, and a solved stride whose
moments are continuous, and the bound report's name for the rate bound. The paper's body, 18
intervals (derivatives: test_derivatives.py's moment-dynamics case)."""

import itertools
import math

import casadi as ca
import numpy as np
import pytest
from helpers import SEED

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import GRAVITY, JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.actuation import MOMENT_RATE_LIMIT, MOMENT_RATE_SCALE
from formopt.optim.stride.bounds import held_by_bounds
from formopt.optim.stride.guess import ballistic
from formopt.optim.stride.ocp import Release
from formopt.optim.stride.problem import MOMENT_TIME, MOMENT_TIME_MAX, RUNNER_TENDONS

SPEED = 3.5


@pytest.mark.parametrize("value", [-0.01, math.nan, math.inf, 2 * MOMENT_TIME_MAX])
def test_moment_time_is_a_time_in_its_range(value):
    with pytest.raises(InputError, match="moment_time"):
        StrideSettings(moment_time=value)


def test_moment_time_is_for_the_torque_rungs():
    """The muscles' moments are their tendons' forces, states already."""
    with pytest.raises(InputError, match="moment_time"):
        StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", moment_time=MOMENT_TIME)


@pytest.fixture(scope="module")
def dynamic():
    """A heel strike with springs on Hermite-Simpson, moment dynamics at MOMENT_TIME."""
    return StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=18, tendons=RUNNER_TENDONS,
                                                              transcription="hermite-simpson",
                                                              moment_time=MOMENT_TIME))


def test_the_moments_are_states_and_their_rates_the_controls(dynamic):
    """Per phase a Z block of the six moments within the torque limit, U their scaled rates within
    MOMENT_RATE_LIMIT; every release keeps its f_n = 0 row (a moment that cannot jump can meet it)."""
    b, limit = dynamic.blocks, dynamic.settings.torque_limit
    lower, upper = (b.split(np.concatenate(v)) for v in (b.lower, b.upper))
    for phase in dynamic.phases:
        assert b.shapes[f"Z_{phase.name}"][0] == 6
        assert (lower[f"Z_{phase.name}"] == -limit).all() and (upper[f"Z_{phase.name}"] == limit).all()
        assert (upper[f"U_{phase.name}"] == MOMENT_RATE_LIMIT).all()
    releases = [t for t in dynamic.ocp.transitions if isinstance(t, Release)]
    assert len(releases) == 2 and all(t.dropped for t in releases)


def test_the_rate_term_is_the_written_formula(dynamic):
    """The NLP's moment-rate integral is Simpson's rule of |m MOMENT_RATE_SCALE u|^2 ((N m/s)^2)
    over each phase, at a guess with random rates; the objective adds it times T^2 100 / (m g)^2
    per distance."""
    rng = np.random.default_rng(SEED)
    guess = ballistic(dynamic, SPEED)
    for phase in dynamic.phases:
        guess[f"U_{phase.name}"] = rng.uniform(-1.0, 1.0, guess[f"U_{phase.name}"].shape)
    x, p = dynamic.blocks.join(guess), [SPEED, 0.0, 0.8]
    expected = 0.0
    for phase, n in zip(dynamic.phases, dynamic.split):
        h, tau_rate = guess[f"T_{phase.name}"] / n, dynamic.mass * MOMENT_RATE_SCALE * guess[f"U_{phase.name}"]
        w = np.r_[1.0, np.tile([4.0, 2.0], n)[:-1], 1.0] * h / 6  # Simpson: 1 4 2 4 ... 4 1
        expected += float(np.sum(tau_rate ** 2, axis=0) @ w)
    integral = ca.Function("I", [dynamic.blocks.vector(), dynamic.p], [dynamic.integral("moment_rates")])
    assert float(integral(x, p)) == pytest.approx(expected, rel=1e-12)
    term = [t for t in dynamic.ocp.cost_terms if t.integral == "moment_rates"]
    assert len(term) == 1 and term[0].weight == MOMENT_TIME ** 2
    assert term[0].scale == pytest.approx(100 / (dynamic.mass * GRAVITY) ** 2, rel=1e-12)


def test_a_stride_with_moment_dynamics_has_continuous_moments():
    """On the trapezoid from the generic start (Hermite-Simpson at 18 intervals did not converge
    in 1000 iterations, 2026-11-27): converged; the moments are continuous across the phases and
    periodic with the legs swapped; the dropped points' normal force is zero at their phase's
    end; a rate at MOMENT_RATE_LIMIT would be reported by name."""
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=18, tendons=RUNNER_TENDONS,
                                                             moment_time=MOMENT_TIME))
    stride = optimum(nlp, SPEED, simulate=False)
    assert stride.success, stride.solved.status
    b = stride.solved.blocks
    Z = [b[f"Z_{p.name}"] for p in nlp.phases]
    for before, after in itertools.pairwise(Z):
        np.testing.assert_allclose(after[:, 0], before[:, -1], atol=1e-8)
    np.testing.assert_allclose(np.r_[Z[-1][3:, -1], Z[-1][:3, -1]], Z[0][:, 0], atol=1e-8)
    for i, transition in enumerate(nlp.ocp.transitions):
        if isinstance(transition, Release):
            assert np.abs(b[f"F_{nlp.phases[i].name}"][list(transition.dropped), -1]).max() < 1e-6
    at_limit = {**b, "U_heel": np.full_like(b["U_heel"], MOMENT_RATE_LIMIT)}
    names = {h["variable"] for h in held_by_bounds(nlp, at_limit)}
    assert {"hip_R torque rate", "ankle_L torque rate"} <= names
