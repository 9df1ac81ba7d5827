"""`formopt bench`: what each model level and numerical choice costs, and what it gives up.

Over the fixed touchdown states of data/bench_states.csv and the scene data/full_body.toml
(package data beside this module, made by benchmarks/make_bench_states.py) (the paper's body, forefoot strike at 3.5 m/s), for each
ladder level and option: time per indicator evaluation, per landing and per optimisation, and
the error of T_c, mu_c, dv of the trunk and of the optimal posture against the finest setting
(the full planar body; SX, interpreted, exact Hessian; RK4 at the smallest step).
"""

from __future__ import annotations

import csv
import math
import statistics
import time
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import casadi as ca
import numpy as np

from ..io.scene import landing_scene, load
from ..mechanics.compiled import external
from ..mechanics.impact import Impact, impact_function, on_ground
from ..mechanics.landing import Diverged, LandingModel, simulate_state
from ..mechanics.model import STATE, build_model
from ..optim.posture import PostureProblem

LEVELS = ("effective-mass", "shank-foot", "leg", "leg-trunk", "full-body")
DATA = Path(__file__).resolve().parent / "data"


@dataclass
class Row:
    level: str
    option: str
    work: str  # "impact", "landing", "optimisation", "build"
    time_s: float  # median time of one unit of work
    error: float  # relative error of T_c (T_c_total for landings), or posture error (deg)
    error_mu_c: float = float("nan")  # largest absolute error of mu_c
    error_dv: float = float("nan")  # largest absolute error of dv_trunk (m/s)
    note: str = ""


@dataclass(frozen=True)
class Bench:
    """What `formopt bench` measured, and on which ground (the bench scene's)."""

    rows: list[Row]
    batch_states_per_s: float  # compiled, mapped indicators of the paper's leg, one core
    friction: float  # the ground's friction coefficient of every impact, landing and optimum
    slope: float  # rad, the ground's slope

    def to_dict(self) -> dict:
        """JSON-ready (non-finite numbers as null; the slope in degrees)."""
        def clean(v):
            return None if isinstance(v, float) and not math.isfinite(v) else v
        return {"rows": [{k: clean(v) for k, v in asdict(r).items()} for r in self.rows],
                "batch_states_per_s": self.batch_states_per_s, "friction": self.friction,
                "slope_deg": math.degrees(self.slope)}


def read_states(path=None) -> np.ndarray:
    """The bench states (data/bench_states.csv) as model.STATE vectors (SI)."""
    with Path(path or DATA / "bench_states.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    deg = math.radians
    return np.array([[deg(float(r["trunk_deg"])), deg(float(r["hip_deg"])), deg(float(r["knee_deg"])),
                      deg(float(r["ankle_deg"])), float(r["hip_vx"]), float(r["hip_vz"]), 0.0,
                      deg(float(r["omega_thigh_dps"])), deg(float(r["omega_shank_dps"])),
                      deg(float(r["omega_foot_dps"]))] for r in rows])


def _median_time(f, args, repeats=1):
    times = []
    for a in args:
        for _ in range(repeats):
            t = time.perf_counter()
            f(a)
            times.append(time.perf_counter() - t)
    return statistics.median(times)


def run(quick: bool = False, progress=None) -> Bench:
    """All rows (impacts, landings, optimisations, in the order of the table), the compiled
    batch throughput of the paper's leg (states/s) and the ground."""
    say = progress or (lambda text: None)
    scene = landing_scene(load(DATA / "full_body.toml"), "formopt bench")
    states = read_states()[: 20 if quick else 200]
    models = {level: build_model(scene.body, level, scene.strike, scene.swing) for level in LEVELS}
    rows = _impact_rows(scene, models, states, say)
    batch_states_per_s = _batch(models["leg"], scene.strike, states, scene.friction, scene.slope)
    rows += _landing_rows(scene, models, states[: 5 if quick else 20], quick, say)
    rows += _optimisation_rows(scene, models, quick, say)
    return Bench(rows, batch_states_per_s, scene.friction, scene.slope)


def _impact_rows(scene, models, states, say) -> list[Row]:
    """Build and evaluation per level against the full body, then SX/MX and compilation for the
    paper's leg against its interpreted SX values."""
    rows: list[Row] = []
    results = {}
    for level in LEVELS:
        say(f"impact: {level}")
        t = time.perf_counter()
        impact = Impact(models[level], scene.strike, scene.slope, scene.friction)
        build = time.perf_counter() - t
        results[level] = [impact(x) for x in states]
        rows.append(Row(level, "SX interpreted", "build", build, 0.0,
                        note=f"{impact.function.n_instructions()} instructions, {models[level].n} coordinates"))
        rows.append(Row(level, "ladder, SX interpreted", "impact", _median_time(impact.evaluate, states), 0.0))
    finest = results["full-body"]
    for level in LEVELS:
        errors = [abs(r.T_c - f.T_c) / f.T_c for r, f in zip(results[level], finest)]
        mu = [abs(r.mu_c - f.mu_c) for r, f in zip(results[level], finest)
              if r.mu_c is not None and f.mu_c is not None]
        dv = [np.hypot(*np.subtract(r.dv_trunk, f.dv_trunk)) for r, f in zip(results[level], finest)
              if r.dv_trunk is not None and f.dv_trunk is not None]
        row = next(r for r in rows if r.level == level and r.work == "impact" and r.option.startswith("ladder"))
        row.error = float(np.max(errors))
        row.error_mu_c = float(np.max(mu)) if mu else float("nan")
        row.error_dv = float(np.max(dv)) if dv else float("nan")
        row.note = f"median relative T_c error {np.median(errors):.2e}"
    reference = np.array([r.T_c for r in results["leg"]])
    for graph in ("SX", "MX"):
        for compiled in (False, True):
            say(f"impact: leg, {graph}, {'compiled' if compiled else 'interpreted'}")
            impact = Impact(models["leg"], scene.strike, scene.slope, scene.friction, compiled=compiled,
                            graph=graph)
            values = np.array([float(np.ravel(impact.evaluate(x)["T_c"])[0]) for x in states])
            rows.append(Row("leg", f"{graph} {'compiled' if compiled else 'interpreted'}", "impact",
                            _median_time(impact.evaluate, states),
                            float(np.max(np.abs(values - reference) / reference)),
                            note=f"{impact.function.n_instructions()} instructions"))
    return rows


def _landing_rows(scene, models, states, quick, say) -> list[Row]:
    """Step and integrator for the paper's leg against a fine RK4 reference, then the ladder
    (RK4, 0.5 ms) against the full body. A diverged landing is counted in its row's note.
    Compiled step functions; `quick` runs them interpreted (no compiler run: the quick bench
    is a check that every row runs, its landing times are not the compiled ones)."""
    steps = (1e-3, 5e-4) if quick else (2e-3, 1e-3, 5e-4, 2.5e-4)
    reference_dt = 1e-4 if quick else 6.25e-5
    lm = {integ: LandingModel(models["leg"], scene.joints, scene.slope, not quick, integrator=integ)
          for integ in ("rk4", "midpoint")}

    def land(model, x, dt):
        """T_c_total (J) of one landing; NaN when it diverges (a row says so, the bench goes on)."""
        try:
            return simulate_state(model, scene.strike, x, scene.friction, dt, 0.2).T_c_total
        except Diverged:
            return math.nan

    say("landing: reference")
    rows: list[Row] = []
    ref_total = [land(lm["rk4"], x, reference_dt) for x in states]
    for integ in ("rk4", "midpoint"):
        for dt in steps:
            say(f"landing: leg, {integ}, dt {dt * 1e3:g} ms")
            totals = np.array([land(lm[integ], x, dt) for x in states])
            error, note = _landing_errors(totals, ref_total)
            rows.append(Row("leg", f"{integ} dt {dt * 1e3:g} ms", "landing",
                            _median_time(lambda x, m=lm[integ], h=dt: land(m, x, h), states),
                            error, note=note))
    ladder: dict[str, Row] = {}
    level_totals: dict[str, list[float]] = {}
    for level in LEVELS[1:]:
        say(f"landing: {level}")
        model = LandingModel(models[level], scene.joints, scene.slope, not quick, integrator="rk4")
        level_totals[level] = [land(model, x, 5e-4) for x in states]
        ladder[level] = Row(level, "ladder, rk4 dt 0.5 ms", "landing",
                            _median_time(lambda x, m=model: land(m, x, 5e-4), states), 0.0)
        rows.append(ladder[level])
    for level, row in ladder.items():
        row.error, row.note = _landing_errors(np.array(level_totals[level]), level_totals["full-body"])
    for row in rows if quick else []:
        row.note += "; step functions interpreted (--quick)"
    return rows


def _optimisation_rows(scene, models, quick, say) -> list[Row]:
    """The ladder with an exact Hessian against the full body's optimum, then the Hessian and
    compilation for the paper's leg against its exact optimum (posture errors in deg)."""
    assert scene.problem is not None  # the bench's scene has an [optimize] table
    problem = replace(scene.problem, starts=1)
    rows: list[Row] = []
    optima = {}
    repeats = 3 if quick else 10
    for level in LEVELS:
        say(f"optimisation: {level}")
        pp = PostureProblem(models[level], scene.strike, scene.state, problem, scene.slope, scene.friction)
        sol, stats, _ = pp.solve_from(pp.to_unit(scene.state))
        optima[level] = np.degrees(pp.to_state(np.asarray(sol["x"], float).ravel())[pp.index])
        rows.append(Row(level, "ladder, exact Hessian", "optimisation",
                        _median_time(pp.solve_from, [pp.to_unit(scene.state)], repeats),
                        0.0, note=stats["return_status"]))
    for row in rows:
        row.error = float(np.max(np.abs(optima[row.level] - optima["full-body"])))
        row.note += "; posture error against the full body's optimum, deg"
    for hessian, compiled in (("limited-memory", False), ("exact", True)):
        say(f"optimisation: leg, {hessian}, {'compiled' if compiled else 'interpreted'}")
        pp = PostureProblem(models["leg"], scene.strike, scene.state, problem, scene.slope, scene.friction,
                            compiled=compiled, hessian=hessian)
        sol, stats, _ = pp.solve_from(pp.to_unit(scene.state))
        posture = np.degrees(pp.to_state(np.asarray(sol["x"], float).ravel())[pp.index])
        rows.append(Row("leg", f"{hessian} Hessian{', compiled' if compiled else ''}", "optimisation",
                        _median_time(pp.solve_from, [pp.to_unit(scene.state)], repeats),
                        float(np.max(np.abs(posture - optima["leg"]))),
                        note=f"{stats['return_status']}; posture error against the leg's exact optimum, deg"))
    return rows


def _landing_errors(totals: np.ndarray, reference) -> tuple[float, str]:
    """(largest relative error of T_c_total, note with the median and the diverged count); a
    diverged landing (NaN) counts in the note, not in the error; all diverged: error NaN."""
    errors = np.abs(totals - np.asarray(reference)) / np.abs(reference)
    good = errors[np.isfinite(errors)]
    diverged = int(np.sum(~np.isfinite(totals)))
    note = f"median {np.median(good):.1e}" if good.size else "no landing converged"
    if diverged:
        note += f"; {diverged} of {len(totals)} landings DIVERGED (the step is too long)"
    return (float(np.max(good)) if good.size else math.nan), note


def _batch(model, strike, states, friction, slope, n=10000):
    """Compiled, mapped indicators of the paper's leg on the scene's ground (friction, slope
    rad): states per second on one core."""
    f = on_ground(impact_function(model, strike, outputs=["T", "T_c", "T_a", "impulse", "mu_signed",
                                                          "dv_trunk", "dv_com"]), friction, slope)
    batch = external(f.map(n, "serial"))
    X = ca.DM(np.resize(states, (n, len(STATE))).T)
    batch(X)
    return n / _median_time(lambda _: batch(X), range(7))
