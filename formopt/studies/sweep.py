"""Parameter sweeps of the landing (or, for a scene with an [optimize] table, of its optimum:
studies.optimum_map): each result written as it finishes, resumable, parallel.

`--param ankle_deg=-20:20:41` sweeps the touchdown ankle angle from -20 to 20 deg in 41
points; several --param make a grid. Parameters: trunk_deg, hip_deg, knee_deg, ankle_deg
(touchdown angles), hip_vx, hip_vz (m/s), friction, slope_deg. Rows go to a CSV file as soon
as each landing is done; a second run with the same file skips the rows already there, so an
interruption loses nothing and repeats nothing. A sweep holds a lock on its file while it
runs (a second writer is refused), drops a torn last row (a killed run, a full disk) before
it resumes, and on Ctrl-C stops its workers and says how many rows are written.

The landings run in chunks on a local process pool (`workers`), or on a Dask distributed
cluster when given its scheduler's address; each worker builds its landing model once
(compiled functions come from the on-disk cache) and the rows are written as chunks return.

One runner for every kind of row (`Kind`, chosen by the scene): landings (here), posture
optima of a scene's [optimize] table (studies.optimum_map) and stride optima of a [stride]
scene (studies.stride_map); the last two are warm-started chains along a serpentine.
"""

from __future__ import annotations

import contextlib
import csv
import itertools
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path

import numpy as np

from ..io.files import OutputError, append_csv, append_rows, write_csv
from ..io.progress import bar as progress_bar
from ..io.stride_scene import StrideScene
from ..mechanics import limits
from ..mechanics.errors import InputError
from ..mechanics.landing import simulate_state
from ..mechanics.model import STATE, joint_angles
from . import optimum_map, stride_map
from .pool import local_pool, watched

PARAMETERS = {"speed_mps": "hip_vx", "trunk_deg": "trunk", "hip_deg": "hip", "knee_deg": "knee", "ankle_deg": "ankle",
              "hip_vx": "hip_vx", "hip_vz": "hip_vz", "friction": None, "slope_deg": None}
UNITS = {"speed_mps": "running speed (the hip's forward velocity), m/s",
         "trunk_deg": "touchdown trunk lean, deg", "hip_deg": "hip flexion, deg",
         "knee_deg": "knee flexion, deg", "ankle_deg": "ankle dorsiflexion, deg",
         "hip_vx": "m/s forward", "hip_vz": "m/s up", "friction": "coefficient",
         "slope_deg": "ground slope, deg uphill"}


@dataclass(frozen=True)
class LandingRow:
    """One landing of a sweep (SI unless the name says otherwise); None: not applicable (no
    second impact, no trunk) or not computed (`error` says why). Its CSV columns are its
    fields in order (COLUMNS), a swept ground parameter given once."""

    friction: float  # the ground's, of this landing
    slope_deg: float
    T_c_first: float | None = None  # J
    T_c_second: float | None = None  # J
    T_c_total: float | None = None  # J
    t_second_ms: float | None = None
    ankle_at_second_deg: float | None = None
    f_n_max_N: float | None = None
    dv_trunk_x: float | None = None  # m/s, summed over the impacts
    dv_trunk_z: float | None = None
    mu_c_max: float | None = None
    no_slip_held: bool | None = None
    releases: int | None = None
    energy_error: float | None = None
    ended: str | None = None
    valid: bool | None = None
    error: str = ""

    def to_dict(self) -> dict:
        """{column: CSV value} ("" where None)."""
        return {k: "" if v is None else v for k, v in asdict(self).items()}


COLUMNS = [f.name for f in fields(LandingRow)]
SPEED = limits.Range(-limits.SPEED_LIMIT, limits.SPEED_LIMIT, "m/s")
# What each parameter may take (mechanics.limits, with their sources); a value beyond is a
# typing error, not a runner, and is refused before any work.
RANGES = {"speed_mps": SPEED, "hip_vx": SPEED, "hip_vz": SPEED, "friction": limits.FRICTION,
          "slope_deg": limits.SLOPE_DEG, **{f"{k}_deg": limits.ANGLE_DEG
                                            for k in ("trunk", "hip", "knee", "ankle")}}
# The most points one sweep takes: a 1000 x 1000 grid, about 30 min of landings on two cores
# (benchmarks/sweep_scaling.py); a larger grid is refused before any work or memory is spent.
MAX_POINTS = 1_000_000


def parse_param(text: str, scene=None) -> tuple[str, np.ndarray]:
    """'ankle_deg=-20:20:41' -> ('ankle_deg', 41 values from -20 to 20); the names and ranges
    of `scene`'s kind of sweep (a landing's when None, a stride's for a [stride] scene)."""
    names, ranges = (stride_map.PARAMETERS, stride_map.RANGES) if _is_stride(scene) else (PARAMETERS, RANGES)
    name, _, spec = text.partition("=")
    if name not in names:
        raise InputError(f"--param {name!r}: expected one of {', '.join(names)}")
    try:
        first, last, number = spec.split(":")
        start, stop, count = float(first), float(last), int(number)
    except ValueError:
        raise InputError(f"--param {text!r}: expected NAME=START:STOP:COUNT, e.g. ankle_deg=-20:20:41") from None
    if not 1 <= count <= MAX_POINTS or not (math.isfinite(start) and math.isfinite(stop)):
        # checked before linspace: no memory for a huge COUNT, no numpy warning for inf
        raise InputError(f"--param {text!r}: COUNT must be 1 to {MAX_POINTS} and the range finite")
    allowed = ranges[name]
    for value in (start, stop) if count > 1 else (start,):
        if value not in allowed:
            raise InputError(f"--param {text!r}: {name} = {value:g} is outside its range, "
                             f"{allowed.text()} (mechanics.limits)")
    return name, np.linspace(start, stop, count)


def check_grid(params: list[tuple[str, np.ndarray]]) -> None:
    """Refuse a grid that names one quantity twice (speed_mps and hip_vx are both the hip's
    forward velocity) or has more than MAX_POINTS points, before any work."""
    seen: dict[str, str] = {}
    for name, _ in params:
        quantity = PARAMETERS.get(name) or name
        if quantity in seen:
            raise InputError(f"--param {name}: sets the same quantity as --param {seen[quantity]}; "
                             "give each quantity once")
        seen[quantity] = name
    points = math.prod(len(v) for _, v in params)
    if points > MAX_POINTS:
        raise InputError(f"the grid has {points:.3g} points, more than the {MAX_POINTS} one sweep "
                         "takes: split it into several sweeps")


def apply(scene, values: dict):
    """The scene with parameter values set (degrees where the name says so)."""
    state = scene.state.copy()
    friction, slope = scene.friction, scene.slope
    for name, value in values.items():
        if name == "friction":
            friction = value
        elif name == "slope_deg":
            slope = math.radians(value)
        else:
            k = STATE.index(PARAMETERS[name])
            state[k] = math.radians(value) if name.endswith("_deg") else value
    return replace(scene, state=state, friction=friction, slope=slope)


CHUNK = 8  # landings per task: enough to pay for a worker's model, small enough to balance


# A chained map (stride, optimum) is cut into CHAINS chains of at least CHAIN_MIN points, whatever
# the workers: each chain starts from its own first point's solve and warm-starts the rest, so
# its rows depend on where it starts. Cut by the workers, a stride map's rows did (2 workers:
# 4 of 12 points 9-36 % costlier than with 1, issue 37). Eight chains keep a pool of up to eight
# workers busy on a large map; a small one stays one chain of up to 16 points, since a chain's
# first point costs about 15-20 warm ones (stride_map.CHUNK).
CHAINS = 8
CHAIN_MIN = 16


@dataclass(frozen=True)
class Kind:
    """What a sweep computes at each grid point: `work(scene, chunk)` -> one row ({column:
    CSV value}) per point, `chunk` points per task; `chained`: the points of a chunk are
    warm-started one from the next, so the grid is walked as a serpentine; `ticks`:
    `work(scene, chunk, tick)` calls tick() after each point, so that a chunk run in this
    process moves the progress bar point by point (a stride map's chain of up to 120 strides
    would otherwise show nothing, and no remaining time, until it ends)."""

    unit: str  # what a row is, for the progress bar
    columns: list[str]
    work: Callable
    chunk: int
    chained: bool
    ticks: bool = False


def kind_of(scene, params, landings: bool = False) -> Kind:
    """The sweep a scene asks for (its grid checked, InputError naming a parameter it cannot
    take): a stride map for a [stride] scene, an optimum map for an [optimize] table (unless
    `landings`), else landings."""
    if _is_stride(scene):
        stride_map.check(scene, params)
        return Kind("stride", stride_map.COLUMNS, stride_map.rows, stride_map.CHUNK, True, ticks=True)
    if scene.problem is not None and not landings:
        optimum_map.check(scene, params)
        return Kind("optimum", optimum_map.columns(scene), optimum_map.rows, optimum_map.CHUNK, True)
    return Kind("landing", COLUMNS, landing_rows, CHUNK, False)


def chunk_size(kind: Kind, points: int, workers: int = 1, scheduler: str | None = None) -> int:
    """Points per chunk: a chained map's the same whatever the workers (CHAINS chains of at
    least CHAIN_MIN points, at most kind.chunk: a chain's rows depend on its start); a landing
    sweep's a fair share of a pool's or a cluster's workers, so that every one is busy."""
    if kind.chained:
        return max(min(kind.chunk, CHAIN_MIN), min(kind.chunk, math.ceil(points / CHAINS)))
    if workers > 1 or scheduler:
        return max(1, min(kind.chunk, math.ceil(points / (4 * (workers if not scheduler else 8)))))
    return kind.chunk


def _is_stride(scene) -> bool:
    return isinstance(scene, StrideScene)


def run(scene, params: list[tuple[str, np.ndarray]], path, progress: bool = True,
        workers: int = 1, scheduler: str | None = None, note=None,
        landings: bool = False) -> list[dict]:
    """Sweep `scene` over the grid of `params` (its landing, or the optimum of its [optimize]
    table unless `landings`, or its stride: `kind_of`), appending rows to `path` (CSV).

    workers > 1: a local process pool; scheduler: a Dask distributed scheduler's address;
    note(text): told of a repaired file. Ctrl-C raises KeyboardInterrupt("N rows written ...").
    """
    path = Path(path)
    check_grid(params)
    if scheduler is not None and not scheduler.strip():  # not "no scheduler": a missing address
        raise InputError("--scheduler '': give the Dask scheduler's address (e.g. tcp://10.0.0.5:8786), "
                         "or leave the option out to run on local processes")
    names = [n for n, _ in params]
    kind = kind_of(scene, params, landings)
    work = kind.work
    grid = optimum_map.serpentine(params) if kind.chained else \
        [dict(zip(names, combo)) for combo in itertools.product(*[v for _, v in params])]
    header = names + [c for c in kind.columns if c not in names]  # a swept ground column once
    fh, existing, torn = append_csv(path, header)
    with fh:
        if torn and note:
            note(f"{path}: dropped a torn last row (an interrupted write); it is computed again")
        done = _done(path, existing, names, {_key(g, names) for g in grid})
        todo = [g for g in grid if _key(g, names) not in done]
        size = chunk_size(kind, len(grid), workers, scheduler)
        # chunks cut from the whole grid, not from what is left: a resumed optimum map's chains
        # start where an uninterrupted run's do (a partly done chunk runs whole again, its
        # missing rows kept), so its rows are that run's (optimum_map's docstring)
        chunks = [c for c in (grid[k:k + size] for k in range(0, len(grid), size))
                  if any(_key(g, names) not in done for g in c)]
        bar = progress_bar(len(grid), "sweep", kind.unit, initial=len(grid) - len(todo)) if progress else None
        meter = _Meter(bar, [sum(_key(g, names) not in done for g in c) for c in chunks])
        written = len(grid) - len(todo)
        try:
            # closing: an error in this loop (a full disk) ends the pool now, not when the
            # traceback that holds the generator goes
            tick = meter.tick if bar and kind.ticks else None
            with contextlib.closing(_results(work, scene, chunks, workers, scheduler, tick)) as results:
                for chunk, rows in results:
                    new = [(values, row) for values, row in zip(chunk, rows)
                           if _key(values, names) not in done]
                    append_rows(fh, path, ([{**row, **values}[c] for c in header] for values, row in new))
                    written += len(new)
                    meter.chunk_done(len(new))
        except KeyboardInterrupt:
            raise KeyboardInterrupt(f"{written} of {len(grid)} rows written to {path}; the same "
                                    "command resumes") from None
        finally:
            if bar:
                bar.close()
        _sort(path, header, names, grid)
    return read(path)


def _sort(path: Path, header, names, grid) -> None:
    """Rewrite the finished sweep in parameter order (rows arrive in completion order)."""
    order = {_key(g, names): k for k, g in enumerate(sorted(grid, key=lambda g: _key(g, names)))}
    rows = read(path)
    rows.sort(key=lambda r: order.get(_key({n: float(r[n]) for n in names}, names), len(order)))
    write_csv(path, [header] + [[r[c] for c in header] for r in rows])


def valid(row: dict) -> bool:
    """A computed landing that holds its own assumptions (Landing.valid); for an optimum map,
    a converged optimum whose impact is valid; for a stride map, a converged stride whose
    impacts are valid."""
    return not row["error"] and row["valid"] == "True"


class _Meter:
    """A sweep's progress bar (None: no bar): rows as each chunk is written, and, for a chunk run
    in this process by a `ticks` kind, its points as they are computed (`fresh[k]`: chunk k's
    points not yet in the file, the most its ticks move the bar; in-process chunks run in order)."""

    def __init__(self, bar, fresh: list[int]):
        self.bar, self.fresh, self.chunk, self.ticked = bar, fresh, 0, 0

    def tick(self) -> None:
        if self.bar is not None and self.ticked < self.fresh[self.chunk]:
            self.ticked += 1
            self.bar.update(1)

    def chunk_done(self, new: int) -> None:
        if self.bar is not None:
            self.bar.update(new - self.ticked)
        self.chunk, self.ticked = self.chunk + 1, 0


def _results(work, scene, chunks, workers, scheduler, tick=None):
    """(chunk, rows) as each chunk finishes, wherever it ran; work(scene, chunk) -> rows
    (work(scene, chunk, tick) in this process when `tick` is given: Kind.ticks)."""
    if scheduler:
        from dask.distributed import Client, as_completed

        with _client(Client, scheduler) as client:
            futures = {client.submit(work, scene, chunk, pure=False): chunk for chunk in chunks}
            for future in as_completed(futures):
                yield futures[future], future.result()
    elif workers > 1 and len(chunks) > 1:
        with local_pool(workers) as pool:
            got = pool.imap_unordered(_chunk_rows, [(work, scene, chunk) for chunk in chunks])
            for _ in chunks:
                yield watched(pool, got.next)
    else:
        for chunk in chunks:
            yield chunk, work(scene, chunk, tick) if tick else work(scene, chunk)


def _client(Client, address: str):
    """A Dask client of the scheduler at `address`; OutputError in one line when the address is
    malformed or nobody answers within 10 s."""
    try:
        return Client(address, timeout="10s")
    except (OSError, ValueError, TypeError) as err:  # dask's TimeoutError is an OSError
        raise OutputError(f"--scheduler {address!r}: no Dask scheduler there "
                          f"({type(err).__name__}: {str(err).splitlines()[0][:120] if str(err) else ''})") from None


def _chunk_rows(task):
    work, scene, chunk = task
    return chunk, work(scene, chunk)


_MODELS: dict = {}  # per process: landing models by scene and slope, built once


def landing_rows(scene, chunk) -> list[dict]:
    """The rows ({column: CSV value}, LandingRow) of a chunk of parameter values."""
    return [_landing_row(scene, values, _MODELS) for values in chunk]


def read(path) -> list[dict]:
    with Path(path).open(newline="") as fh:
        return list(csv.DictReader(fh))


def _landing_row(scene, values, models) -> dict:
    ground = {"friction": values.get("friction", scene.friction),
              "slope_deg": values.get("slope_deg", math.degrees(scene.slope))}
    try:
        s = apply(scene, values)
        key = repr((s.kind, s.body, s.swing, s.joints, s.slope, s.numerics, s.contact))  # what the model holds
        if key not in models:
            models[key] = s.landing(many=True)
        lm = models[key]
        L = simulate_state(lm, s.strike, s.state, s.friction, s.integration.dt,
                           s.integration.duration)
        second = L.impacts[1] if len(L.impacts) > 1 else None
        ankle = None
        if second:
            k = int(np.searchsorted(L.t, second.time))
            q_e = L.q[min(k, len(L.t) - 1)]
            ankle = math.degrees(joint_angles({k: lm.model.segment_angle(q_e, k)
                                                for k in ("shank", "foot")})["ankle"])
        normal = L.force[:, 1]
        f_max = float(np.nanmax(normal)) if np.any(np.isfinite(normal)) else None
        dv = np.sum([e.dv_trunk for e in L.impacts if e.dv_trunk], axis=0) if lm.model.trunk else (None, None)
        row = LandingRow(**ground, T_c_first=L.impacts[0].T_c, T_c_second=second.T_c if second else None,
                         T_c_total=L.T_c_total, t_second_ms=second.time * 1e3 if second else None,
                         ankle_at_second_deg=ankle, f_n_max_N=f_max, dv_trunk_x=dv[0], dv_trunk_z=dv[1],
                         mu_c_max=L.mu_c_max, no_slip_held=L.no_slip_held, releases=len(L.releases),
                         energy_error=L.energy_error, ended=L.ended, valid=L.valid)
    except (InputError, RuntimeError) as err:  # a point the model cannot take: say so, go on
        row = LandingRow(**ground, error=str(err).replace("\n", " "))
    return row.to_dict()


def _key(values: dict, names) -> tuple:
    return tuple(round(float(values[n]), 9) for n in names)


def _done(path: Path, rows: list[dict], names, grid: set) -> set:
    """The grid points already in the sweep's rows; OutputError if a row is not a number where
    a parameter should be, or belongs to another grid (the same parameters, other values)."""
    done = set()
    for k, r in enumerate(rows):
        try:
            key = _key({n: float(r[n]) for n in names}, names)
        except ValueError:
            raise OutputError(f"{path}: row {k + 1} holds {[r[n] for n in names]} where numbers "
                              "should be; mend or remove the file") from None
        if key not in grid:
            raise OutputError(f"{path}: holds points of another grid ({dict(zip(names, key))}); "
                              "give another --out or remove it")
        done.add(key)
    return done
