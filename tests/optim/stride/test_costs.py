"""optim.stride.costs: the torque rungs' joint-level metabolic cost (Minetti & Alexander's muscle
at each joint) by hand, on a known trajectory through the NLP, its constants against gait2d's
muscles, its refusal with muscles and its scene key."""

import casadi as ca
import numpy as np
import pytest
from helpers import SEED

from formopt.io.muscle_table import body_muscles, gait2d_muscles
from formopt.io.scene import SceneError
from formopt.io.stride_scene import parse
from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JointSpace
from formopt.mechanics.muscles import JOINTS as LEG_JOINTS
from formopt.mechanics.muscles import force_velocity
from formopt.optim.stride import StrideNLP, StrideSettings, costs
from formopt.optim.stride.actuation import JOINT_MAX_RATE
from formopt.optim.stride.guess import ballistic, perturbed
from formopt.optim.stride.ocp import INTEGRANDS, NX
from formopt.optim.stride.problem import RUNNER_TENDONS


def phi(v):
    """Minetti & Alexander 1997's phi, written out."""
    return (0.054 + 0.506 * v + 2.46 * v ** 2) / (1 - 1.13 * v + 12.8 * v ** 2 - 1.64 * v ** 3)


def cost_per_moment(v):
    """phi(v) over De Groote's f_V at the shortening velocity v, capped smoothly at 0.9."""
    v = v - 0.02 * np.log1p(np.exp((v - 0.9) / 0.02))
    return phi(v) / np.asarray(force_velocity(-v), float).ravel()


def test_minetti_alexander_at_hand_values():
    assert float(costs.minetti_alexander(0.0)) == pytest.approx(0.054)
    assert float(costs.minetti_alexander(1.0)) == pytest.approx(3.02 / 11.03)
    assert float(costs.minetti_alexander(-1.0)) == pytest.approx(2.008 / 16.57)


def test_a_plantarflexing_ankle_by_hand():
    """150 N m at the right ankle while it plantarflexes at 5 rad/s (positive work, 750 W),
    every other joint free (they cost nothing), a 62 kg body: eps = 12.4 N m."""
    tau, rate = np.zeros(6), np.zeros(6)
    tau[2], rate[2] = 150.0, -5.0
    size = np.hypot(150.0, 12.4)
    v = 750.0 / (12.7 * size)  # 0.392 of omega_max
    expected = (size - 12.4) * 12.7 * phi(v) / float(force_velocity(-v))
    got = float(costs.joint_metabolic_rate(ca.DM(tau), ca.DM(rate), 62.0))
    assert got == pytest.approx(expected, rel=1e-12)
    # held (isometric) it costs less, braking (negative work) less still
    costs_at = {}
    for speed in (0.0, 2.0, 5.0):
        rate[2] = speed
        costs_at[speed] = float(costs.joint_metabolic_rate(ca.DM(tau), ca.DM(rate), 62.0))
    assert costs_at[2.0] < costs_at[5.0] < costs_at[0.0] < got


def test_max_rates_are_gait2d_muscles():
    """omega_max = sum F_max v_max / sum F_max |r| over the muscles crossing each joint, the same
    for two bodies (lengths scale with height, forces cancel)."""
    for mass, height in ((62.0, 1.81), (90.0, 1.6)):
        m = gait2d_muscles(mass, height)
        for k, joint in enumerate(LEG_JOINTS):
            r = np.abs(m.moment_arms[:, k])
            rate = np.sum((m.max_force * m.max_velocity)[r > 0]) / np.sum(m.max_force * r)
            assert JOINT_MAX_RATE[joint] == pytest.approx(rate, abs=0.05)


@pytest.fixture(scope="module")
def nlp():
    return StrideNLP(JointSpace(paper_body()), StrideSettings(nodes=18, objective="joint-metabolic",
                                                              tendons=RUNNER_TENDONS))


def test_its_terms_and_no_power_split(nlp):
    assert [t.integral for t in nlp.ocp.cost_terms] == ["joint_metabolic", "smoothing"]
    assert nlp.ocp.cost_terms[0].scale == pytest.approx(1.0 / (nlp.ocp.mass * 9.81), rel=1e-3)
    assert not any(name.startswith("S_") for name in nlp.blocks.offsets)


def test_the_integral_on_a_known_trajectory(nlp):
    """The NLP's integral of the joint metabolic power on a perturbed guess against the rate
    computed here from its active moments and joint rates, with the trapezoid's weights."""
    rng = np.random.default_rng(SEED)
    guess = perturbed(ballistic(nlp, 3.5), rng)
    for phase in nlp.phases:  # moments of up to 2 N m/kg (the guess has none)
        guess[f"U_{phase.name}"] = rng.uniform(-2.0, 2.0, np.shape(guess[f"U_{phase.name}"]))
    x = nlp.blocks.join(guess)
    blocks, p = nlp.blocks.split(x), [3.5, 0.0, 0.8]
    got = float(ca.Function("I", [nlp.problem["x"], nlp.problem["p"]], [nlp.integral("joint_metabolic")])(x, p))
    eps = 0.2 * nlp.ocp.mass
    w = np.array([22.4, 23.7, 12.7] * 2)[:, None]
    expected = 0.0
    for i, (phase, (L, weights)) in enumerate(zip(nlp.phases, nlp.integrands(blocks, dict(speed=3.5, slope=0.0, mu=0.8)))):
        tau, _ = nlp.moments(blocks, i)
        rate = blocks[f"X_{phase.name}"][NX + 3:]
        size = np.sqrt(tau ** 2 + eps ** 2)
        v = -tau * rate / (w * size)
        rates = np.sum((size - eps) * w * cost_per_moment(v.ravel()).reshape(v.shape), axis=0)
        np.testing.assert_allclose(L[INTEGRANDS.index("joint_metabolic")], rates, rtol=1e-12)
        expected += float(rates @ weights)
    assert got == pytest.approx(expected, rel=1e-12)
    assert expected > 10.0  # J


def test_refused_with_muscles():
    with pytest.raises(InputError, match="actuation 'muscles': expected objective metabolic or activation"):
        StrideSettings(objective="joint-metabolic", muscles=body_muscles(paper_body()))


def test_the_scene_key():
    scene = parse({"scene": {"name": "t"}, "ground": {"friction": 0.8},
                   "stride": {"speed_mps": 3.5, "actuation": "torque+springs", "objective": "joint-metabolic"}})
    assert scene.settings.objective == "joint-metabolic"
    with pytest.raises(SceneError, match="stride"):
        parse({"scene": {"name": "t"}, "ground": {"friction": 0.8},
               "stride": {"speed_mps": 3.5, "actuation": "muscles", "objective": "joint-metabolic"}})
