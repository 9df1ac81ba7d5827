"""StrideSettings.activation_rate_smoothing, the muscles' activation rates' scale in the
transcription's smoothing: collocation.build keeps one NLP per scale (its key is the settings)
and the NLP's smoothing reads it; refine.refined tries a muscle stride directly (IPOPT stopped at
a restoration) and, where that fails, solves it without the smoothing first, then with it from
there (refine.continued). The paper's body, flat strike, 14 nodes (the least muscle mesh): NLPs
built, no IPOPT run (refined's solves recorded, not run)."""

from dataclasses import replace
from types import SimpleNamespace

import casadi as ca
import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.optim.stride import refine
from formopt.optim.stride.actuation import ACTIVATION_RATE_SMOOTHING
from formopt.optim.stride.collocation import build
from formopt.optim.stride.layout import Solved
from formopt.optim.stride.problem import RUNNER_TENDONS, StrideSettings

BODY = paper_body()
SETTINGS = StrideSettings(strike="flat", nodes=14, objective="metabolic", muscles=body_muscles(BODY))
PARAMETERS = {"speed": 3.5, "slope": 0.0, "mu": 0.8, "cadence": None}


def smoothing(nlp, x: np.ndarray) -> float:
    """The NLP's smoothing integral (collocation's "smoothing" term) at the decision vector x."""
    term = ca.Function("smoothing", [nlp.blocks.vector(), nlp.p], [nlp.integral("smoothing")])
    return float(term(x, [3.5, 0.0, 0.8]))


def test_build_keeps_one_nlp_per_scale_and_its_smoothing_reads_it():
    """Two settings differing only in the scale build two NLPs (each kept: built again, the same
    one); their smoothing at one decision vector (durations > 0) is S_A + s^2 S_a' (the accelerations' part and
    the activation rates' scaled by s): (S(10) - S(0)) / (S(3) - S(0)) = 100 / 9."""
    nlps = {s: build(BODY, replace(SETTINGS, activation_rate_smoothing=s)) for s in (ACTIVATION_RATE_SMOOTHING, 0.0, 3.0)}
    assert len({id(nlp) for nlp in nlps.values()}) == 3
    assert build(BODY, SETTINGS) is nlps[ACTIVATION_RATE_SMOOTHING]
    x = np.random.default_rng(1).uniform(0.05, 1.0, nlps[0.0].blocks.vector().numel())
    S = {s: smoothing(nlp, x) for s, nlp in nlps.items()}
    assert S[ACTIVATION_RATE_SMOOTHING] - S[0.0] == pytest.approx(100.0 / 9.0 * (S[3.0] - S[0.0]), rel=1e-9)
    assert S[3.0] > S[0.0] > 0.0


def solved(blocks: dict, success: bool = True, iterations: int = 0) -> Solved:
    """A stand-in solve of `blocks` at PARAMETERS."""
    return Solved(blocks=blocks, success=success, status="status", iterations=iterations, solve_s=0.0,
                  objective=1.0, x=np.zeros(1), lam_g=np.zeros(1), parameters=dict(PARAMETERS))


def recorded(monkeypatch, direct_success: bool = True, unsmoothed_success: bool = True, options: list | None = None) -> list:
    """refine's solves recorded, not run, as (what, the NLP's scale, whether IPOPT stops at a
    restoration, the guess): StrideNLP.solve (the direct try, where IPOPT stops at a restoration:
    the blocks {"direct": 1}, converged with `direct_success`, in 5 iterations; `continued`'s
    unsmoothed solve: {"unsmoothed": 1}, converged with `unsmoothed_success`, in 7), local.best_of
    (a converged direct try summarised; its guess the solve's blocks) and each `optimum` (a
    stand-in stride, converged); guess.fitted as {"fitted": blocks}; `options`: each NLP's IPOPT
    options appended."""
    seen: list = []

    def stops(nlp) -> bool:
        (options if options is not None else []).append(dict(nlp.ipopt or {}))
        return (nlp.ipopt or {}).get("max_resto_iter") == 0

    def solve(nlp, guess, speed, slope, mu, cadence):
        stop = stops(nlp)
        seen.append(("solve", nlp.settings.activation_rate_smoothing, stop, guess))
        return solved({"direct": 1}, direct_success, 5) if stop else solved({"unsmoothed": 1}, unsmoothed_success, 7)

    def best_of(nlp, solves, simulate):
        seen.append(("best_of", nlp.settings.activation_rate_smoothing, stops(nlp), solves[0].blocks))
        return SimpleNamespace(checks={}, success=solves[0].success)

    def optimum(nlp, speed, slope, mu, cadence, guess, simulate):
        seen.append(("optimum", nlp.settings.activation_rate_smoothing, stops(nlp), guess))
        return SimpleNamespace(checks={}, success=True, iterations=9, status="status")

    monkeypatch.setattr(type(build(BODY, SETTINGS)), "solve", solve)
    monkeypatch.setattr(refine, "best_of", best_of)
    monkeypatch.setattr(refine, "optimum", optimum)
    monkeypatch.setattr(refine, "fitted", lambda nlp, blocks, source: {"fitted": blocks})
    return seen


COARSE = SimpleNamespace(solved=solved({"coarse": 1}))  # a stand-in Stride on a coarser mesh
FITTED = {"fitted": {"coarse": 1}}
FINE = replace(SETTINGS, nodes=16)
SCALE = ACTIVATION_RATE_SMOOTHING


def test_refined_keeps_a_muscle_strides_direct_try_where_it_converges(monkeypatch):
    """A muscle stride on a finer mesh: one solve from the coarser stride (fitted), IPOPT
    stopped at a restoration (refine.DIRECT_TRY), kept where it converged: summarised on the
    NLP without DIRECT_TRY (its touchdown's mode decided under Coulomb by a solve to its end)."""
    seen = recorded(monkeypatch)
    fine = refine.refined(build(BODY, FINE), COARSE)
    assert seen == [("solve", SCALE, True, FITTED), ("best_of", SCALE, False, {"direct": 1})]
    assert "continuation" not in fine.checks


@pytest.mark.parametrize("unsmoothed_success", [True, False])
def test_refined_continues_a_muscle_stride_where_its_direct_try_fails(monkeypatch, unsmoothed_success):
    """The direct try failed: solved at scale 0 from the coarser stride, then at the settings'
    scale (restorations allowed) from that solve where it converged (else from the coarser
    stride); the tries' iterations recorded on the stride."""
    seen = recorded(monkeypatch, direct_success=False, unsmoothed_success=unsmoothed_success)
    fine = refine.refined(build(BODY, FINE), COARSE)
    assert seen == [("solve", SCALE, True, FITTED), ("solve", 0.0, False, FITTED),
                    ("optimum", SCALE, False, {"unsmoothed": 1} if unsmoothed_success else FITTED)]
    assert fine.checks["continuation"] == {"direct_iterations": 5, "direct_status": "status",
                                           "unsmoothed_iterations": 7, "unsmoothed_status": "status"}


def test_refined_solves_a_torque_stride_or_a_direct_one_once(monkeypatch):
    """The torque rungs, and `continuation=False`: one solve to its end, from the fitted stride."""
    seen = recorded(monkeypatch, direct_success=False)
    torque = replace(FINE, muscles=None, objective="effort", tendons=RUNNER_TENDONS)
    assert "continuation" not in refine.refined(build(BODY, torque), COARSE).checks
    assert "continuation" not in refine.refined(build(BODY, FINE), COARSE, continuation=False).checks
    assert seen == [("optimum", SCALE, False, FITTED)] * 2


def test_refined_keeps_the_callers_ipopt_options_in_every_solve(monkeypatch):
    """The caller's options (here a barrier and a CPU cap, as problems/muscle_mesh.py's) in the
    direct try, the unsmoothed solve and the last one; DIRECT_TRY in the direct try alone."""
    options: list = []
    recorded(monkeypatch, direct_success=False, options=options)
    caller = {"mu_init": 1e-2, "max_cpu_time": 600}
    refine.refined(build(BODY, FINE).variant(caller), COARSE)
    assert [o.get("max_resto_iter") for o in options] == [0, None, None]
    assert all(o.items() >= caller.items() for o in options)
