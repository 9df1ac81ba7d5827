"""StrideSettings.consistency_rows = False (the comment at the field says why): the NLP without the
held contacts' work and energy budget rows, without a torque source's released f_n = 0 row on
the trapezoid and without the released points' height row at the next phase's first column. The
setting's error, the rows it takes away (the same NLP otherwise) and a solved stride. The
paper's body. No new expression: nothing for test_derivatives.py."""

import numpy as np
import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.ocp import Release
from formopt.optim.stride.problem import RUNNER_TENDONS

SPEED = 3.5


@pytest.mark.parametrize("value", [0, 1, "no", None])
def test_consistency_rows_is_true_or_false(value):
    with pytest.raises(InputError, match="consistency_rows"):
        StrideSettings(consistency_rows=value)


@pytest.fixture(scope="module")
def pair():
    """(with, without) the consistency rows: a heel strike with springs on the trapezoid."""
    js = JointSpace(paper_body())
    return tuple(StrideNLP(js, StrideSettings(strike="heel", nodes=20, tendons=RUNNER_TENDONS,
                                              consistency_rows=kept)) for kept in (True, False))


def test_the_rows_taken_away(pair):
    """The same variables; two rows fewer for the energy (the held contacts' work, the budget), one
    per release for its dropped normal force; at each release's next column the dropped point's
    height row free below, every other node row's bounds the same."""
    kept, loose = pair
    assert kept.blocks.names == loose.blocks.names and kept.blocks.size == loose.blocks.size
    releases = [[t for t in nlp.ocp.transitions if isinstance(t, Release)] for nlp in pair]
    assert [len(t.dropped) for t in releases[0]] == [1, 1] and all(not t.dropped for t in releases[1])
    assert len(kept.lbg) - len(loose.lbg) == 2 + 2
    nodes = sum(len(lo) * c for (lo, _), c in zip(kept.node_bounds, kept.columns))
    freed = np.flatnonzero(kept.lbg[:nodes] != loose.lbg[:nodes])
    assert len(freed) == 2 and np.isinf(loose.lbg[freed]).all() and (kept.lbg[freed] == 0.0).all()
    np.testing.assert_array_equal(kept.ubg[:nodes], loose.ubg[:nodes])


def test_a_stride_without_them_converges_and_lets_go_under_load():
    """From the generic start at 40 intervals: converged and valid under the forward check (at
    20 its contact drift, 8.5 mm, and forward error, 0.106 rad, were over the checks' limits: what
    the rows held at coarse meshes); the forefoot leaves the ground still pushing (a torque source
    lets go by a jump of its moments)."""
    loose = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=40, tendons=RUNNER_TENDONS,
                                                               consistency_rows=False))
    stride = optimum(loose, SPEED)
    assert stride.success, stride.solved.status
    assert stride.valid, stride.failed_checks
    assert stride.solved.blocks["F_forefoot"][:, -1].max() > 0.05
