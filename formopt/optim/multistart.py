"""The multi-start: IPOPT from the reference posture and from seeded random postures, at
any parameters p (one home: PostureProblem.solve and the optimum maps both run it).

Only a start that IPOPT reports as converged, that satisfies every constraint record (the
gait's equalities to 1e-9 m), whose impact passes the checked impact map and, for a landing,
whose event-driven simulation agrees, can be the optimum; the best of those is. When none
converges the best last iterate is returned with success False and the statuses explained.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..mechanics import contact
from ..mechanics.impact import ImpactResult
from .solution import Local, Optimum, Start, distinct, explain

DRAWS = 50  # random draws per wanted start of a landing problem


def starts(pp) -> list[np.ndarray]:
    """The reference posture first, then seeded uniform starts in the bounds.

    For a landing problem a start must land: its simulated landing brings the other foot
    point down (otherwise the event constraint has no solution near it); up to DRAWS draws
    per start are tried.
    """
    rng = np.random.default_rng(pp.problem.seed)
    first = pp.start(pp.reference)
    n = pp.posture.size
    if not pp.landing:
        return [first] + [rng.uniform(0.0, 1.0, n) for _ in range(pp.problem.starts - 1)]
    found = [first]
    for _ in range(DRAWS * pp.problem.starts):
        if len(found) == pp.problem.starts:
            break
        u = rng.uniform(0.0, 1.0, n)
        t_e = pp.second_impact(pp.to_state(u))
        if t_e is not None:
            found.append(np.append(u, t_e / pp.duration))
    return found


@dataclass(frozen=True)
class Run:
    """One start's IPOPT run at parameters p, accepted or not (PostureProblem.accept)."""

    sol: dict  # IPOPT's solution (x, f, g, lam_x, lam_g)
    stats: dict  # IPOPT's statistics
    w: np.ndarray  # the decision vector it ended at
    x: np.ndarray  # its touchdown state (STATE, SI)
    impact: ImpactResult  # checked at x
    start: Start  # where it began, how it ended, its objective
    elapsed: float  # s


def runs(pp, p, progress=None) -> list[Run]:
    """Every start of posture problem `pp` (starts(pp)) at parameters p; `progress(k, n,
    start)` after each."""
    out = []
    for k, w0 in enumerate(starts(pp)):
        sol, stats, elapsed = pp.solve_from(w0, p)
        w, x, impact, why = pp.accept(sol, stats, p)
        start = Start(k + 1, pp.posture.degrees(pp.to_state(w0, p)), stats["return_status"],
                      why == "", float(pp.objective_function(w, p)), pp.posture.degrees(x),
                      int(stats["iter_count"]), why or "")
        out.append(Run(sol, stats, w, x, impact, start, elapsed))
        if progress:
            progress(k + 1, pp.problem.starts, start)
    return out


def best(found: list[Run]) -> Run:
    """The accepted run with the least objective; when none is accepted, the least of all."""
    return min([r for r in found if r.start.converged] or found, key=lambda r: r.start.objective)


def solve(pp, progress=None) -> Optimum:
    """The multi-start of posture problem `pp` at its own parameters, as an Optimum;
    `progress(k, n, start)` after each start."""
    p = pp.p0
    found = runs(pp, p, progress)
    chosen = best(found)
    converged = [r for r in found if r.start.converged]
    notes = []
    if not converged:
        statuses = sorted({(r.start.rejected and f"{r.start.status}, rejected: {r.start.rejected}")
                           or f"{r.start.status}: {explain(r.start.status)}" for r in found})
        notes.append(f"no start converged: {'; '.join(statuses)}. "
                     "The state shown is the best last iterate, not an optimum")
    if pp.mode is not None:
        mode, direction = pp.mode
        notes.append(f"Coulomb mode fixed for every start from the reference touchdown: "
                     f"{contact.MODES[mode]}, sliding {'forward' if direction > 0 else 'backward'}"
                     f" at first; the impact at the state shown ends in {chosen.impact.mode}")
    active, sensitivity = (), {}
    if converged:
        active = pp.active(chosen.w, p, chosen.sol)
        sensitivity = pp.sensitivity(chosen.w, p, chosen.sol["lam_x"], chosen.sol["lam_g"])

    def terms(w):
        return dict(zip(pp.term_names, map(float, np.asarray(pp.terms_function(w, p)).ravel())))
    first = pp.start(pp.reference)
    return Optimum(success=bool(converged), status=chosen.start.status,
                   objective=chosen.start.objective, state=chosen.x, impact=chosen.impact,
                   reference=pp.checked(pp.reference, p), active=active,
                   sensitivity=sensitivity, starts=tuple(r.start for r in found),
                   local_optima=distinct([r.x[pp.index] for r in converged]),
                   seed=pp.problem.seed, solve_time=float(np.median([r.elapsed for r in found])),
                   build_time=pp.build_time, terms=terms(chosen.w), weights=dict(pp.problem.objective),
                   reference_objective=float(pp.objective_function(first, p)),
                   reference_terms=terms(first),
                   cadence_spm=pp.problem.gait.cadence_spm if pp.problem.gait else None,
                   local=(Local(math.degrees(pp.problem.radius), pp.marginal(pp.reference))
                          if converged and pp.problem.radius else None),
                   notes=tuple(notes))
