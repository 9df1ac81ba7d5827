"""The stance leg's tendons (optim.stride.problem.TENDON_JOINTS): springs engaged unloaded at
the touchdown and let go at toe-off. One coarse solve (24 nodes, 1 start), checked against
the energy budget (the tendons' loss, `spring_J`, closes it), the forward simulation with the
springs in the equations of motion, and the NLP without tendons (zero stiffness is today's
NLP)."""

import casadi as ca
import numpy as np
import pytest

from formopt.io.stride_scene import parse
from formopt.mechanics.body import scaled_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.guess import ballistic

NODES = 24
TENDONS = {"knee": 2.5, "ankle": 4.0}  # problem.RUNNER_TENDONS


@pytest.fixture(scope="module")
def js():
    return JointSpace(scaled_body(62.0, 1.81))


@pytest.fixture(scope="module")
def stride(js):
    nlp = StrideNLP(js, StrideSettings(nodes=NODES, tendons=TENDONS))
    return optimum(nlp, 3.5, starts=1)


def test_the_budget_closes_with_the_tendons_loss(stride):
    """W+ = W- + impacts + friction + passive + spring: with tendons the NLP imposes it (and
    that the held contacts do no work), so it closes to IPOPT's tolerance."""
    b = stride.budget
    assert stride.success, stride.status
    assert b["spring_J"] >= -1e-6  # a tendon let go loaded only loses energy
    assert abs(b["balance_J"]) < 1e-4 * b["positive_work_J"] + 1e-6
    assert abs(b["friction_J"]) < 1e-4 * b["positive_work_J"] + 1e-6
    assert stride.budget["impacts_J"] < 20.0  # measured 1-12 J; 40-110 J without tendons


def test_forward_simulation_with_the_springs_reproduces_each_phase(stride):
    assert stride.checks["forward_theta"] < 0.25


def test_zero_stiffness_is_the_nlp_without_tendons(js):
    """The same objective and constraints at the same point: tendons of zero stiffness add
    nothing."""
    plain = StrideNLP(js, StrideSettings(nodes=NODES))
    zero = StrideNLP(js, StrideSettings(nodes=NODES, tendons={"knee": 0.0, "ankle": 0.0}))
    x = plain.blocks.join(ballistic(plain, 3.5))
    p = [3.5, 0.0, 0.8]
    a, b = (ca.Function("fg", [n.problem["x"], n.problem["p"]], [n.problem["f"], n.problem["g"]])
            for n in (plain, zero))
    for left, right in zip(a(x, p), b(x, p)):
        np.testing.assert_array_equal(np.asarray(left), np.asarray(right))


@pytest.mark.parametrize("tendons, key", [({"toe": 1.0}, "tendons.toe"), ({"knee": -1.0}, "tendons.knee"),
                                          ({"ankle": 50.0}, "tendons.ankle")])
def test_bad_tendons_name_their_key(tendons, key):
    with pytest.raises(InputError, match=key):
        StrideSettings(tendons=tendons)


def test_scene_key(tmp_path):
    scene = parse({"scene": {"name": "t"}, "ground": {"friction": 0.8},
                   "stride": {"speed_mps": 3.5, "tendons": {"knee": 5, "ankle": 8}}})
    assert scene.settings.tendons == {"knee": 5.0, "ankle": 8.0}
