"""The local search (`[stride] search = "local"`): a stride's optimum from its starts, the generic
start and seeded perturbations of it (`optimum`), the best of the solves kept (`best_of`: `rank`),
under Coulomb after the touchdown's mode is decided (`touchdown_mode`). The global search
(search.py) builds on `generic_start` and `best_of`.
"""

from __future__ import annotations

import numpy as np

from .actuation import ACTIVATION_RATE_SMOOTHING
from .checks import impact_check
from .collocation import NX, StrideNLP
from .guess import ballistic, fitted, from_torques, perturbed, slide_guess
from .ipopt_options import CONTINUATION_IPOPT
from .layout import Solved
from .problem import RESERVE_CONTINUATION, RUNNER_TENDONS, SLIDING_PHASES
from .result import Stride, rank, summarise


def optimum(nlp: StrideNLP, speed: float, slope: float = 0.0, mu: float = 0.8,
            cadence: float | None = None, guess: dict | None = None, simulate: bool = True,
            starts: int = 1, seed: int = 0) -> Stride:
    """Solve the NLP from `guess` (default: the generic guess, or for Hermite-Simpson the
    trapezoid's optimum from it; a solution of another phase list or node count on this NLP's
    grading is `fitted` to its columns; one of another grading or transcription is fitted first,
    guess.fitted(nlp, blocks, source)) and, with `starts` > 1, from
    starts - 1 perturbations of it (guess.perturbed, seeded); summarise the best of the solves
    (`rank`: valid first, then converged, then the least objective), under Coulomb after its
    touchdown's mode is decided (`touchdown_mode`); where the forward check (`simulate`) makes
    it invalid, the next start in that order is summarised, and the best of those kept."""
    first = fitted(nlp, guess) if guess is not None else generic_start(nlp, speed, slope, mu, cadence)
    rng = np.random.default_rng(seed)
    solves = [nlp.solve(first if k == 0 else perturbed(first, rng), speed, slope, mu, cadence)
              for k in range(starts)]
    return best_of(nlp, solves, simulate)


def generic_start(nlp: StrideNLP, speed: float, slope: float = 0.0, mu: float = 0.8,
                  cadence: float | None = None) -> dict:
    """The start that knows nothing of the optimum (`optimum`'s default guess, and the global
    search's): the generic guess (guess.ballistic); with muscles the torque rung's optimum split
    among them and continued in the reserves' price (`muscle_start`); for Hermite-Simpson the
    trapezoid's optimum from the trapezoid's start."""
    if nlp.settings.transcription != "trapezoid":
        # Hermite-Simpson from the generic guess: converged at 20 intervals, not in 300
        # iterations at 40; from the trapezoid's optimum at 40, in 166 (heel, 3.5 m/s, 2026-11-25)
        base = nlp.variant(transcription="trapezoid")
        solved = base.solve(generic_start(base, speed, slope, mu, cadence), speed, slope, mu, cadence)
        return fitted(nlp, solved.blocks, base)
    if nlp.settings.muscles is not None:
        return muscle_start(nlp, speed, slope, mu, cadence)
    return ballistic(nlp, speed)


def best_of(nlp: StrideNLP, solves: list[Solved], simulate: bool = True) -> Stride:
    """The Stride of the best of `solves` (`rank`: valid first, then converged, then the least
    objective), under Coulomb after its touchdown's mode is decided (`touchdown_mode`); where
    the forward check (`simulate`) makes it invalid, the next solve in that order is
    summarised, and the best of those kept."""
    if len(solves) > 1:
        solves = sorted(solves, key=lambda solved: rank(summarise(nlp, solved, simulate=False)))
    best: Stride | None = None
    for solved in solves:  # the next start only where the forward check fails the best one
        kept_nlp, kept, tried = touchdown_mode(nlp, solved) if nlp.settings.law == "coulomb" else (nlp, solved, [])
        stride = summarise(kept_nlp, kept, simulate)
        if tried:
            stride.checks["touchdown_modes"] = tried
        best = stride if best is None or rank(stride) < rank(best) else best
        if best.valid or not best.success:
            break
    assert best is not None, "best_of: no solve"
    return best


def torque_start(nlp: StrideNLP) -> StrideNLP:
    """The torque+springs NLP a muscle NLP starts from (`muscle_start`): its mesh and strike,
    effort, problem.RUNNER_TENDONS, trapezoid, without the muscles' settings."""
    return nlp.variant(muscles=None, objective="effort", tendons=RUNNER_TENDONS, transcription="trapezoid",
                       force_rate_power=2, force_rate_weight=None, activation_rate_smoothing=ACTIVATION_RATE_SMOOTHING)


def muscle_start(nlp: StrideNLP, speed: float, slope: float, mu: float, cadence: float | None) -> dict:
    """The muscles' start: the torque+springs rung's optimum (effort, problem.RUNNER_TENDONS,
    trapezoid) of the same strike and mesh from the generic guess, its net moments split among
    the muscles (guess.from_torques), then the muscles' optimum at each reserve weight of
    problem.RESERVE_CONTINUATION below the setting's, each from the one before (IPOPT's barrier
    from ipopt_options.CONTINUATION_IPOPT's unless the NLP's own options set it; a cold solve at
    the default 10000 ends in a costlier optimum: problem.RESERVE_WEIGHT). From the generic
    guess itself the muscle NLP did not converge in 600 iterations (RBDS001, heel, 40 nodes,
    3.5 m/s, 2026-11-25)."""
    base = torque_start(nlp)
    start = from_torques(nlp, base, base.solve(ballistic(base, speed), speed, slope, mu, cadence))
    for weight in (w for w in RESERVE_CONTINUATION if w < nlp.settings.reserve_weight):
        step = nlp.variant({**CONTINUATION_IPOPT, **(nlp.ipopt or {})}, reserve_weight=weight)
        solved = step.solve(start, speed, slope, mu, cadence)
        start = solved.blocks if solved.success else start  # a failed step's iterate is no start
    return start


def touchdown_mode(nlp: StrideNLP, stick: Solved) -> tuple[StrideNLP, Solved, list]:
    """The Coulomb touchdown's mode, as the landing decides it: the sticking solve `stick`
    is checked with formopt's Coulomb map at its touchdown state; where the map says it does
    not stick, or the impulse sits on the friction cone's edge (the sticking mode's boundary),
    the sliding variant (problem.SLIDING_PHASES) is solved, warm-started from it, with the
    slip's sign s from the map (or against the tangential impulse); the better valid result
    is kept (`rank`). Returns the kept NLP and
    solve, and each mode tried (`checks["touchdown_modes"]`: objective, success, validity,
    cost of transport, cadence; empty when only the sticking one was)."""
    first = summarise(nlp, stick, simulate=False)
    touchdown = first.impacts[-1]
    if nlp.settings.strike not in SLIDING_PHASES or not (touchdown["coulomb_mode"] != "stick"
                                                         or touchdown["on_cone_edge"]):
        return nlp, stick, []
    par = stick.parameters
    sliding = nlp.variant(touchdown="slide", slip=_slip_sign(nlp, stick))
    solved = sliding.solve(slide_guess(sliding, stick.blocks, par["mu"]), par["speed"],
                           par["slope"], par["mu"], par["cadence"])
    candidates = [(first, nlp, stick), (summarise(sliding, solved, simulate=False), sliding, solved)]
    tried = [{"mode": s.impacts[-1]["mode"], "objective": s.objective_value, "success": s.success,
              "valid": s.valid, "cost_of_transport": s.cost_of_transport,
              "cadence_spm": s.cadence_spm} for s, _, _ in candidates]
    _, kept_nlp, kept = min(candidates, key=lambda c: rank(c[0]))
    return kept_nlp, kept, tried


def _slip_sign(nlp: StrideNLP, stick: Solved) -> int:
    """s (+1 or -1): the sign of the touchdown point's slip after formopt's Coulomb impact at the
    sticking solution's touchdown state, or (where that does not slide) against its tangential
    impulse, the side of the cone it leans on."""
    b, par = stick.blocks, stick.parameters
    end = b[f"X_{nlp.phases[-1].name}"][:, -1]
    check = impact_check(nlp.js, nlp.touchdown_rows, end[:NX], end[NX:], par["slope"], par["mu"])
    slip = check["coulomb_slip_mps"] if check["coulomb_mode"] != "stick" else -check["impulse_t"]
    return 1 if slip >= 0 else -1
