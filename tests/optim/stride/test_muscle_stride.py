"""A solved muscle-driven stride (the paper's body, flat strike, 14 nodes, 3.5 m/s, the default
settings: the reserves' weight reached by local.muscle_start's continuation) and its forward
check (checks.forward), which replays the excitations through the muscles: within its tolerance
for the optimum, beyond it when the stance leg's muscles are switched off. The cheapest muscle
stride there is (14 nodes, the flat strike's least mesh, is the least of any strike): the file
takes about 20 s of CPU, against 31 s with the heel strike at its least mesh (18 nodes)."""

import dataclasses

import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.checks import forward
from formopt.optim.stride.result import TOLERANCES
from formopt.report.stride import rate_text


@pytest.fixture(scope="module")
def muscle_stride():
    body = paper_body()
    nlp = StrideNLP(JointSpace(body), StrideSettings(strike="flat", nodes=14, objective="metabolic",
                                                     muscles=body_muscles(body)))
    return nlp, optimum(nlp, 3.5)


def test_the_muscles_make_the_stride_without_their_reserves(muscle_stride):
    """Valid: the reserves within their tolerance (0.1 N m/kg) and the excitations replayed
    within the forward check's; the net moments' replay reported beside them."""
    _, stride = muscle_stride
    assert stride.valid, stride.failed_checks
    assert stride.checks["reserve_nm_per_kg"] <= TOLERANCES["reserve_nm_per_kg"]
    assert stride.checks["forward_theta"] <= TOLERANCES["forward_theta"]
    assert np.isfinite(stride.checks["forward_moments_reset_theta"])
    assert len(stride.checks["forward_moments_reset_per_phase"]) == len(stride.phases)


def test_the_stance_leg_switched_off_does_not_make_the_stride(muscle_stride):
    """The stance leg's (R) excitations zero at every node: the replay leaves the path by more
    than the tolerance (0.57 rad here, halved excitations 0.25 rad, against 0.039 for the
    optimum; each phase starts from the NLP's activations, which decay over tens of
    milliseconds), while the unchanged moments' replay cannot see it."""
    nlp, stride = muscle_stride
    n = nlp.ocp.models[0].actuation.n
    blocks = {k: v.copy() for k, v in stride.solved.blocks.items()}
    for phase in nlp.phases:
        blocks[f"U_{phase.name}"][:n] = 0.0
    perturbed = forward(nlp, blocks, stride.solved.parameters)
    assert perturbed["reset_theta"] > TOLERANCES["forward_theta"]
    assert perturbed["moments_reset_theta"] == pytest.approx(stride.checks["forward_moments_reset_theta"])


def test_the_muscles_warm_start_reaches_the_neighbouring_speed(muscle_stride):
    """StrideNLP.resolve from the optimum's primal and dual values (WARM_START with
    MUSCLE_WARM_START's barrier) converges at 3.6 m/s in few iterations (28 at 40 nodes on RBDS001)."""
    nlp, stride = muscle_stride
    warm = nlp.resolve(stride.solved, 3.6)
    assert warm.success and warm.iterations < 100


def test_the_stride_records_its_force_rate_term(muscle_stride):
    """The muscles' record names the objective's force-rate power and weight (the JSON's
    `muscles.force_rate_term`); the report's muscles line says them only off the default."""
    _, stride = muscle_stride
    assert stride.muscles["force_rate_term"] == {"power": 2, "weight": 80.0}
    assert rate_text(stride) == ""
    other = dataclasses.replace(stride, muscles={**stride.muscles, "force_rate_term": {"power": 1, "weight": 12.0}})
    assert rate_text(other) == "; its force-rate term |F'| at weight 12"
