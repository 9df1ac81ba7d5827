"""The multi-start: IPOPT from the reference posture and from seeded random postures.

Only a start that IPOPT reports as converged, that satisfies every constraint record (the
gait's equalities to 1e-9 m), whose impact passes the checked impact map and, for a landing,
whose event-driven simulation agrees, can be the optimum; the best of those is. When none
converges the best last iterate is returned with success False and the statuses explained.
"""

from __future__ import annotations

import math

import numpy as np

from ..mechanics import contact
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


def solve(pp, progress=None) -> Optimum:
    """Run every start of posture problem `pp`; `progress(k, n, start)` after each."""
    results, runs = [], []
    for k, w0 in enumerate(starts(pp)):
        sol, stats, elapsed = pp.solve_from(w0)
        w, x, impact, converged = pp.accept(sol, stats)
        status = stats["return_status"]
        objective = float(pp.objective_function(w, pp.p0))
        start = Start(k + 1, pp.posture.degrees(pp.to_state(w0)), status, converged, objective,
                      pp.posture.degrees(x), int(stats["iter_count"]))
        runs.append(start)
        results.append((sol, w, x, start, elapsed, impact))
        if progress:
            progress(k + 1, pp.problem.starts, start)
    converged = [r for r in results if r[3].converged]
    sol, w, x, best, _, impact = min(converged or results, key=lambda r: r[3].objective)
    notes = []
    if not converged:
        statuses = sorted({r[3].status for r in results})
        notes.append(f"no start converged: {'; '.join(f'{s}: {explain(s)}' for s in statuses)}. "
                     "The state shown is the best last iterate, not an optimum")
    if pp.mode is not None:
        mode, direction = pp.mode
        notes.append(f"Coulomb mode fixed for every start from the reference touchdown: "
                     f"{contact.MODES[mode]}, sliding {'forward' if direction > 0 else 'backward'}"
                     f" at first; the impact at the state shown ends in {impact.mode}")
    active, sensitivity = (), {}
    if converged:
        active = pp.active(w, pp.p0, sol)
        sensitivity = pp.sensitivity(w, pp.p0, sol["lam_x"], sol["lam_g"])
    def terms(w):
        return dict(zip(pp.term_names, map(float, np.asarray(pp.terms_function(w, pp.p0)).ravel())))
    first = pp.start(pp.reference)
    return Optimum(success=bool(converged), status=best.status, objective=best.objective,
                   state=x, impact=impact, reference=pp.impact(pp.reference), active=active,
                   sensitivity=sensitivity, starts=tuple(runs),
                   local_optima=distinct([r[2][pp.index] for r in converged]),
                   seed=pp.problem.seed, solve_time=float(np.median([r[4] for r in results])),
                   build_time=pp.build_time, terms=terms(w),
                   reference_objective=float(pp.objective_function(first, pp.p0)),
                   reference_terms=terms(first),
                   cadence_spm=pp.problem.gait.cadence_spm if pp.problem.gait else None,
                   local=(Local(math.degrees(pp.problem.radius), pp.marginal(pp.reference))
                          if converged and pp.problem.radius else None),
                   notes=tuple(notes))
