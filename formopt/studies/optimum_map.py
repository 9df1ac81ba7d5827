"""Optimum maps: the posture optimum of a scene's [optimize] table across a parameter grid.

`formopt sweep SCENE --param speed_mps=2:6:41 --param friction=0.4:1.0:7` on a scene with an
[optimize] table solves the posture problem at every grid point. The grid is walked as a
serpentine (each point next to the one before) and cut into chunks along that path; in a
chunk every point starts from the solved point before it (its posture and IPOPT's multipliers,
with IPOPT's warm-start options), so a point costs a few iterations. The first point of a
chunk, and any point whose warm start does not converge, runs the scene's multi-start.

Speed, friction and slope are parameters of the NLP: one problem serves the whole grid (a
landing problem's slope is built into its landing model and a Coulomb problem's into its
fixed mode, so there the problem is built for each slope). Any other parameter (touchdown
angles, hip_vz) builds the problem for its value (once per value per worker). Each row says
the friction and slope it was solved on. Rows are written as chunks finish, resumable and on
a process pool or on Dask, exactly as landing sweeps (studies.sweep).

A row depends on its chunk (a chunk's first point is cold, the others warm): the chunks are
cut from the whole serpentine (studies.sweep.CHAINS of them, at least CHAIN_MIN and at most
CHUNK points, whatever the workers), never from what a resumed run has left, and a partly
written chunk runs whole again. So a resumed map's rows are those of an uninterrupted run, to
the last digit, warm and iteration columns included, on any number of workers.
"""

from __future__ import annotations

import hashlib
import itertools
import math
import pickle
from dataclasses import asdict, dataclass, field, fields, replace

import numpy as np

from ..mechanics.errors import InputError
from ..optim import multistart
from ..optim.solution import verdict_of

# sweep parameter -> PostureProblem.parameters keyword, and its value's conversion to SI
NLP_PARAMETERS = {"speed_mps": ("speed", float), "hip_vx": ("speed", float),
                  "friction": ("friction", float), "slope_deg": ("slope", math.radians)}
CHUNK = 40  # points per warm-started chain


@dataclass(frozen=True)
class OptimumRow:
    """One point of an optimum map; None: not computed (`error` says why). Its CSV columns:
    the decision variables in deg (deg/s), then the fields in order (COLUMNS)."""

    friction: float  # the ground's, of this point
    slope_deg: float
    posture_deg: dict[str, float] = field(default_factory=dict)  # variable -> deg (deg/s)
    status: str | None = None  # IPOPT's return status
    success: bool | None = None  # an accepted optimum (PostureProblem.accept)
    verdict: str | None = None  # interior, HELD BY ..., or NO OPTIMUM
    objective: float | None = None
    T_c: float | None = None  # J, the checked impact's at the optimum
    iterations: int | None = None
    warm: bool | None = None  # warm-started from the point before
    valid: bool | None = None  # success and a valid checked impact
    error: str = ""

    def to_dict(self, variables) -> dict:
        """{column: CSV value} ("" where None), the posture under `variables`' columns."""
        out = {f"{v}_deg": self.posture_deg.get(v, "") for v in variables}
        out.update({k: "" if v is None else v for k, v in asdict(self).items() if k != "posture_deg"})
        return out


COLUMNS = [f.name for f in fields(OptimumRow) if f.name != "posture_deg"]
WARM = {"ipopt.warm_start_init_point": "yes", "ipopt.warm_start_bound_push": 1e-9,
        "ipopt.warm_start_mult_bound_push": 1e-9, "ipopt.mu_init": 1e-6}


def columns(scene) -> list[str]:
    """The result columns of an optimum map of `scene`."""
    return [f"{v}_deg" for v in scene.problem.variables] + COLUMNS


def serpentine(params) -> list[dict]:
    """The grid points in an order where each is a neighbour of the one before."""
    names = [n for n, _ in params]
    order = []  # a reflected walk: an axis runs backwards when the indices before it sum to odd
    for combo in itertools.product(*[range(len(v)) for _, v in params]):
        flipped, parity = [], 0
        for k, i in enumerate(combo):
            n = len(params[k][1])
            flipped.append(n - 1 - i if parity % 2 else i)
            parity += flipped[-1]
        order.append(tuple(flipped))
    return [{n: float(params[k][1][i]) for k, (n, i) in enumerate(zip(names, combo))} for combo in order]


_PROBLEMS: dict = {}  # per process: the posture problem of the last scene content built


def content_key(scene) -> str:
    """A digest of everything a scene's posture problem is built from: its pickled fields
    (state, body, ground, [optimize], joints, numerics ...), not its path, so that a scene
    edited in place, or another scene at the same path, builds its own problem. The name,
    path and notes do not change the NLP and are left out."""
    return hashlib.sha256(pickle.dumps(replace(scene, name="", path="", notes=()))).hexdigest()


def rows(scene, chunk) -> list[dict]:
    """The rows ({column: CSV value}, OptimumRow) of a chain of neighbouring points."""
    from .sweep import apply

    out, previous = [], None
    for values in chunk:
        try:
            built = NLP_PARAMETERS if not _slope_built_in(scene) else {
                k: v for k, v in NLP_PARAMETERS.items() if k != "slope_deg"}
            other = {k: v for k, v in values.items() if k not in built}
            built_scene = apply(scene, other)
            key = content_key(built_scene)
            if key not in _PROBLEMS:
                _PROBLEMS.clear()  # one problem at a time: a grid moves through them in order
                _PROBLEMS[key] = built_scene.posture_problem()
            pp = _PROBLEMS[key]
            p = pp.parameters(**{built[k][0]: built[k][1](v) for k, v in values.items() if k in built})
            row, previous = _solve(pp, p, previous if previous and previous[0] is pp else None)
        except (InputError, RuntimeError) as err:
            row, previous = OptimumRow(*_ground(scene, values), error=str(err).replace("\n", " ")), None
        out.append(row.to_dict(scene.problem.variables))
    return out


def _ground(scene, values) -> tuple[float, float]:
    """(friction, slope deg) of a grid point: swept, or the scene's."""
    return values.get("friction", scene.friction), values.get("slope_deg", math.degrees(scene.slope))


def _slope_built_in(scene) -> bool:
    """Whether the scene's problem is built for its slope: a landing (its landing model) or
    Coulomb (its mode, fixed from the reference touchdown on the problem's ground)."""
    return scene.problem.landing or scene.contact == "coulomb"


def _solve(pp, p, previous):
    """One point: warm-started from `previous` (pp, w, lam_x, lam_g) when given, else (or
    when that fails) the multi-start at these parameters. (row, what the next point starts from)."""
    warm = previous is not None
    if warm:
        _, w0, lam_x, lam_g = previous
        sol, stats, _ = pp.solve_from(w0, p, lam_x, lam_g, options=WARM)
        w, x, impact, why = pp.accept(sol, stats, p)
    if not warm or why != "":
        warm = False
        run = multistart.best(multistart.runs(pp, p))
        sol, stats, w, x, impact = run.sol, run.stats, run.w, run.x, run.impact
        why = "" if run.start.converged else run.start.rejected or None
    ok = why == ""
    verdict = verdict_of(pp.active(w, p, sol)) if ok else \
        f"NO OPTIMUM ({f'IPOPT converged, but {why}' if why else stats['return_status']})"
    row = OptimumRow(impact.friction, math.degrees(impact.slope),
                     dict(zip(pp.problem.variables, map(float, np.degrees(x[pp.index])))),
                     stats["return_status"], ok, verdict, float(pp.objective_function(w, p)),
                     impact.T_c, int(stats["iter_count"]), warm, ok and impact.valid)
    return row, ((pp, w, sol["lam_x"], sol["lam_g"]) if ok else None)


def check(scene, params) -> None:
    """Refuse parameters an optimum map cannot take, naming them."""
    for name, _ in params:
        if name in scene.problem.variables or name.removesuffix("_deg") in scene.problem.variables:
            raise InputError(f"--param {name}: {name.removesuffix('_deg')!r} is a decision variable of "
                             "the scene's [optimize] table; sweep what the optimum depends on")
