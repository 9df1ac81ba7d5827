"""optim.stride.search: the global search is deterministic, states what it spent and the optima
it met, is never worse than the one-start optimum, and its grid is nested in the spend."""

import pytest

from formopt.mechanics.body import scaled_body
from formopt.mechanics.errors import InputError
from formopt.optim.stride import search
from formopt.optim.stride.collocation import build
from formopt.optim.stride.local import optimum
from formopt.optim.stride.problem import RUNNER_TENDONS, StrideSettings
from formopt.optim.stride.result import rank

SPEED = 3.5


@pytest.fixture(scope="module")
def searched():
    """A small search (flat strike, 14 nodes, two grid cadences, one released: six solves), run twice (the
    second with the grid forward-checked), and the one-start optimum of the same NLP."""
    mp = pytest.MonkeyPatch()
    mp.setattr(search, "GRID_POINTS", 1)
    mp.setattr(search, "RELEASED", 1)
    mp.setattr(search, "GRID_SPM", (150.0, 190.0))
    nlp = build(scaled_body(62.0, 1.81), StrideSettings(strike="flat", nodes=14, tendons=dict(RUNNER_TENDONS)))
    runs = [search.global_optimum(nlp, SPEED, simulate=False, check_grid=check) for check in (False, True)]
    planned = search.solves_planned(SPEED)
    mp.undo()
    return runs, optimum(nlp, SPEED, simulate=False), planned


def test_the_search_is_deterministic(searched):
    (first, second), _, _ = searched
    assert first.success
    assert second.objective_value == first.objective_value and second.cadence_spm == first.cadence_spm
    assert second.search["optima"] == first.search["optima"]


def test_the_search_states_its_spend_and_the_optima_it_met(searched):
    (stride, _), _, planned = searched
    record = stride.search
    assert record["spend"] == 1 and record["procedure"] == "free cadence"
    assert record["solves"] == planned == 6
    assert record["iterations"] >= record["solves"] and record["seconds"] > 0
    assert record["grid_spm"] == [150.0, 190.0] and len(record["grid_objective"]) == 2
    optima = record["optima"]
    assert optima and sum(o["reached"] for o in optima) <= 2  # the free solves that converged
    answer = [o for o in optima if o["answer"]]
    assert len(answer) == 1 and answer[0]["objective"] == pytest.approx(stride.objective_value)
    assert all(o["valid"] == (not o["failed"]) for o in optima)
    assert record["spread_pct"] >= 0.0
    assert "search" in stride.to_dict()


def test_the_grid_is_forward_checked_when_asked(searched):
    """check_grid: each grid cadence's least costly stride summarised with the forward check, its
    validity and failed checks beside its objective (None where no solve converged)."""
    (plain, checked), _, _ = searched
    assert "grid_valid" not in plain.search
    record = checked.search
    assert record["grid_objective"] == plain.search["grid_objective"]
    assert len(record["grid_valid"]) == len(record["grid_failed"]) == len(record["grid_spm"])
    for objective, valid, failed in zip(record["grid_objective"], record["grid_valid"], record["grid_failed"]):
        assert (valid is None) == (objective is None) and (valid is not False) == (not failed)


def test_the_search_is_no_worse_than_one_start(searched):
    (stride, _), one, _ = searched
    assert rank(stride) <= rank(one)


def test_the_grid_is_nested_in_the_spend_and_holds_an_imposed_cadence():
    one, two = search.grid(3.5, 1), search.grid(3.5, 2)
    assert one[0] == search.GRID_SPM[0] and one[-1] == search.GRID_SPM[1]
    assert len(one) == search.GRID_POINTS + 1 and set(one) <= set(two) and len(two) == 2 * search.GRID_POINTS + 1
    assert 171.4 in search.grid(3.5, 1, 171.4)
    assert all(60.0 * 8.0 / c <= 2.7 for c in search.grid(8.0, 1))  # steps a runner can take at 8 m/s
    assert search.solves_planned(3.5, 1, 171.4) == 3 * 6 - 2  # no free solves at an imposed cadence
    with pytest.raises(InputError, match="spend = 0"):
        search.grid(3.5, 0)
    with pytest.raises(InputError, match="speed_mps"):  # no cadence of the grid runnable: refused, not skipped
        search.solves_planned(0.5)
    with pytest.raises(InputError, match="cadence_spm = 60"):
        search.grid(3.5, 1, 60.0)


def test_the_answer_is_among_the_optima_when_the_touchdown_re_solved_it():
    """Under Coulomb the answer may be the sliding variant's re-solve (local.touchdown_mode),
    whose objective no free solve reached: it is listed, as the answer, beside them."""
    from types import SimpleNamespace

    def met(cadence, objective, valid=True):
        return SimpleNamespace(cadence_spm=cadence, objective_value=objective, success=True, valid=valid,
                               failed_checks=[] if valid else ["forward"], solved=None)

    sticking, other, sliding = met(160.0, 0.30), met(130.0, 0.28, valid=False), met(158.0, 0.29)
    optima = search.distinct(None, [sticking, other, sticking], sliding, simulate=False)
    assert [(o["cadence_spm"], o["answer"], o["reached"]) for o in optima] == [(158.0, True, 1), (160.0, False, 2),
                                                                            (130.0, False, 1)]
    assert [o["answer"] for o in search.distinct(None, [sticking], sticking, simulate=False)] == [True]


def test_an_imposed_cadence_keeps_the_best_stride_met_there():
    """With a cadence imposed: the grid holds it, no free solve runs (solves_planned's count),
    and the answer and every optimum listed are at that cadence."""
    mp = pytest.MonkeyPatch()
    mp.setattr(search, "GRID_POINTS", 1)
    mp.setattr(search, "GRID_SPM", (150.0, 190.0))
    try:
        nlp = build(scaled_body(62.0, 1.81), StrideSettings(strike="flat", nodes=14, tendons=dict(RUNNER_TENDONS)))
        stride = search.global_optimum(nlp, SPEED, cadence=171.4, simulate=False)
        planned = search.solves_planned(SPEED, 1, 171.4)
    finally:
        mp.undo()
    record = stride.search
    assert record["procedure"] == "imposed cadence" and record["grid_spm"] == [150.0, 171.4, 190.0]
    assert record["solves"] == planned == 7
    assert stride.success and stride.cadence_spm == pytest.approx(171.4, rel=1e-6)
    assert record["optima"] and all(o["cadence_spm"] == pytest.approx(171.4, rel=1e-6) for o in record["optima"])
    assert sum(o["answer"] for o in record["optima"]) == 1
