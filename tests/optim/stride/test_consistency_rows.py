"""StrideSettings.consistency_rows (the comment at the field says why): "exact", "trapezoid" or
"off", the rows the continuous stride meets by itself (the held contacts' work and energy budget,
a torque source's released f_n = 0 on the trapezoid, the released points' height at the next
phase's first column) imposed exactly, as the trapezoid meets them, or not at all. The setting's
error, the rows each form takes away or changes (the same NLP otherwise) and solved strides. The
paper's body. The trapezoid form's rows: test_derivatives.py."""

import numpy as np
import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.ocp import Release
from formopt.optim.stride.problem import CONSISTENCY_ROWS, RUNNER_TENDONS

SPEED = 3.5


@pytest.mark.parametrize("value", [True, False, 0, "no", None])
def test_consistency_rows_is_one_of_the_forms(value):
    with pytest.raises(InputError, match="consistency_rows"):
        StrideSettings(consistency_rows=value)


@pytest.mark.parametrize("other", [{"transcription": "hermite-simpson"}, {"moment_time": 0.04}])
def test_the_trapezoid_form_only_where_it_was_measured(other):
    """Its released-height bound is -RELEASE_DRIFT h^2 with h a trapezoid interval, measured on the
    torque rungs without moment dynamics: elsewhere the setting is refused, not guessed."""
    with pytest.raises(InputError, match="consistency_rows = 'trapezoid'"):
        StrideSettings(consistency_rows="trapezoid", **other)


@pytest.fixture(scope="module")
def nlps():
    """{form: its NLP}: a heel strike with springs on the trapezoid."""
    js = JointSpace(paper_body())
    return {form: StrideNLP(js, StrideSettings(strike="heel", nodes=20, tendons=RUNNER_TENDONS,
                                               consistency_rows=form)) for form in CONSISTENCY_ROWS}


def node_rows(nlp) -> int:
    return sum(len(lo) * c for (lo, _), c in zip(nlp.node_bounds, nlp.columns))


def test_the_rows_taken_away(nlps):
    """Off: the same variables; two rows fewer for the energy (the held contacts' work, the
    budget), one per release for its dropped normal force; at each release's next column the
    dropped point's height row free below, every other node row's bounds the same."""
    kept, loose = nlps["exact"], nlps["off"]
    assert kept.blocks.names == loose.blocks.names and kept.blocks.size == loose.blocks.size
    releases = [[t for t in nlp.ocp.transitions if isinstance(t, Release)] for nlp in (kept, loose)]
    assert [len(t.dropped) for t in releases[0]] == [1, 1] and all(not t.dropped for t in releases[1])
    assert len(kept.lbg) - len(loose.lbg) == 2 + 2
    nodes = node_rows(kept)
    freed = np.flatnonzero(kept.lbg[:nodes] != loose.lbg[:nodes])
    assert len(freed) == 2 and np.isinf(loose.lbg[freed]).all() and (kept.lbg[freed] == 0.0).all()
    np.testing.assert_array_equal(kept.ubg[:nodes], loose.ubg[:nodes])


def test_the_rows_as_the_trapezoid_meets_them(nlps):
    """Trapezoid: the node rows as off's; no f_n = 0 row at a release; a row per released point
    instead (its height plus RELEASE_DRIFT h^2, >= 0); the energy rows one-sided (the held
    contacts' work <= 0, the budget >= 0): as many rows as the exact form's."""
    exact, trapezoid, off = nlps["exact"], nlps["trapezoid"], nlps["off"]
    nodes = node_rows(off)
    np.testing.assert_array_equal(trapezoid.lbg[:nodes], off.lbg[:nodes])
    assert all(not t.dropped for t in trapezoid.ocp.transitions if isinstance(t, Release))
    assert len(trapezoid.lbg) == len(exact.lbg)
    np.testing.assert_array_equal(trapezoid.lbg[-2:], [-np.inf, 0.0])
    np.testing.assert_array_equal(trapezoid.ubg[-2:], [0.0, np.inf])
    np.testing.assert_array_equal(exact.lbg[-2:], [0.0, 0.0])


@pytest.mark.parametrize("form", ["off", "trapezoid"])
def test_a_stride_converges_and_lets_go_under_load(form):
    """From the generic start at 40 intervals: converged and valid under the forward check (off at
    20: its contact drift, 8.5 mm, and forward error, 0.106 rad, were over the checks' limits: what
    the exact rows held at coarse meshes); the forefoot leaves the ground still pushing (a torque
    source lets go by a jump of its moments)."""
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(strike="heel", nodes=40, tendons=RUNNER_TENDONS,
                                                              consistency_rows=form))
    stride = optimum(nlp, SPEED)
    assert stride.success, stride.solved.status
    assert stride.valid, stride.failed_checks
    assert stride.solved.blocks["F_forefoot"][:, -1].max() > 0.05
