"""Stride maps (formopt sweep on a [stride] scene): warm-started rows are no worse than fresh
solves, a finished map repeats nothing, the objectives' values agree with the NLP's own graph,
bad parameters are refused in one line. Cheap: 24 nodes, 1 start, a 2 x 2 grid."""

import dataclasses
from itertools import pairwise
from types import SimpleNamespace

import casadi as ca
import numpy as np
import pytest
from helpers import SHIPPED

from formopt import load
from formopt.cli import main
from formopt.mechanics.errors import InputError
from formopt.optim.stride import summarise
from formopt.optim.stride.guess import ballistic
from formopt.report.stride_sweep import stride_sweep_figures
from formopt.studies import stride_map, sweep
from formopt.studies.pool import Background

PARAMS = [("speed_mps", np.array([3.0, 3.5])), ("cadence_spm", np.array([165.0, 185.0]))]


@pytest.fixture(scope="module")
def scene():
    """The shipped stride scene on the trapezoid without its tendons, its impacts' charge and its
    moment dynamics (the scene before 2026-11-28, less its tendons): with tendons, a chain's warm
    start can stay in a costlier local optimum than the generic guess reaches (0.493 against 0.397
    at 3.0 m/s and 185 steps/min, 24 nodes, 2026-11-23), so "no worse than a fresh solve" holds
    only for the rigid-leg landscape; the rows say how each was started (`start`)."""
    shipped = stride_map.for_nodes(load(SHIPPED / "stride.toml"), 24, starts=1)
    rigid = dataclasses.replace(shipped.settings, tendons={}, transcription="trapezoid", impact_weight=0.0,
                                approach_speed=0.0, moment_time=0.0)
    return dataclasses.replace(shipped, settings=rigid)


@pytest.fixture(scope="module")
def grid(scene, tmp_path_factory):
    path = tmp_path_factory.mktemp("stride-map") / "map.csv"
    return path, sweep.run(scene, PARAMS, path, progress=False)


@pytest.fixture(scope="module")
def fresh(scene, grid):
    """Each row's point solved fresh, from the generic guess (the NLP the map solved)."""
    _, rows = grid
    nlp = scene.nlp()
    return [nlp.solve(ballistic(nlp, float(r["speed_mps"])), float(r["speed_mps"]), 0.0, scene.friction,
                      float(r["cadence_spm"])) for r in rows]


@pytest.fixture(scope="module")
def free_optimum(scene):
    """The free optimum at 3.5 m/s: the cadence curve's start and the first sweep's (one solve
    for both tests; cadence_curve's `start` is such an optimum found before)."""
    return stride_map.free(scene, 3.5, 0.0, scene.friction)


def test_rows_are_no_worse_than_a_fresh_solve(grid, fresh):
    _, rows = grid
    assert [r["start"] for r in rows].count("neighbour") == 3  # one chain, its first from the free optimum
    for r, solved in zip(rows, fresh):
        assert r["success"] == "True" and r["valid"] == "True"
        speed, cadence = float(r["speed_mps"]), float(r["cadence_spm"])
        assert solved.success
        # the warm start may find a better local optimum than the generic guess, never a worse
        # one; the same optimum to 1e-5: IPOPT stops at its tolerance (1e-6 on the scaled KKT
        # error), and the warm start's monotone barrier stops on another side of it (measured
        # 1.7e-6 above at 3.5 m/s, 185 steps/min)
        assert float(r["objective_value"]) <= solved.objective * (1 + 1e-5)
        assert 60.0 / cadence == pytest.approx(float(r["step_length_m"]) / speed, rel=1e-9)  # imposed


def test_the_objectives_and_impact_loss_are_the_nlps(scene, grid, fresh):
    """effort_value by numpy on the nodes against the NLP's CasADi graph of the same integral;
    the impact loss is the impacts' T_c times the step rate; the work objective is W+/(m g d)."""
    _, rows = grid
    nlp = scene.nlp()
    speed = float(rows[0]["speed_mps"])
    stride = summarise(nlp, fresh[0], False)
    graph = ca.Function("effort", [nlp.blocks.vector(), nlp.p], [nlp.integral("effort")])
    effort = float(graph(stride.solved.x, [speed, 0.0, scene.friction]))
    values = stride_map.objective_values(nlp, stride)
    assert values["effort_value"] == pytest.approx(
        effort / stride.step_length_m * 100 / (nlp.mass * 9.81) ** 2, rel=1e-9)
    assert values["work_value"] == pytest.approx(stride.cost_of_transport, rel=1e-12)
    for row in rows:
        assert float(row["impact_loss_W"]) == pytest.approx(
            float(row["impacts_J"]) * float(row["cadence_spm"]) / 60.0, rel=1e-9)


def test_a_finished_map_repeats_nothing_and_a_torn_one_resumes_to_the_same_rows(scene, grid, monkeypatch):
    path, rows = grid
    calls = []
    monkeypatch.setattr(stride_map, "rows", lambda s, chunk: calls.append(chunk) or [])
    assert sweep.run(scene, PARAMS, path, progress=False) == rows and calls == []
    monkeypatch.undo()
    text = path.read_text().splitlines(keepends=True)
    torn = path.with_name("torn.csv")
    torn.write_text("".join(text[:-1]))  # the last row lost: its chain runs again, whole
    again = sweep.run(scene, PARAMS, torn, progress=False)
    assert len(again) == len(rows)
    for a, b in zip(again, rows):
        assert {k: v for k, v in a.items() if k != "solve_s"} == {k: v for k, v in b.items() if k != "solve_s"}


def test_bad_parameters_are_refused_in_one_line_naming_them(scene):
    for text, name in (("cadence_spm=40:200:3", "cadence_spm"), ("ankle_deg=-5:5:3", "ankle_deg"),
                       ("step_length_m=0.1:1:3", "step_length_m"), ("speed_mps=2:9:3", "speed_mps")):
        with pytest.raises(InputError, match=name) as err:
            sweep.parse_param(text, scene)
        assert "\n" not in str(err.value)
    three = [sweep.parse_param(t, scene) for t in
             ("speed_mps=3:4:2", "cadence_spm=160:180:2", "step_length_m=1:1.2:2")]
    with pytest.raises(InputError, match="step_length_m"):
        sweep.run(scene, three, "unused.csv", progress=False)
    best = dataclasses.replace(scene, strike="best")
    with pytest.raises(InputError, match=r"stride\.strike"):
        sweep.run(best, PARAMS, "unused.csv", progress=False)


def test_a_step_length_imposes_its_cadence(scene):
    """A step is a half stride: L = v T, cadence 60 / T = 60 v / L."""
    assert stride_map.point(scene, {"speed_mps": 3.0, "step_length_m": 1.2})[3] == pytest.approx(150.0)
    assert stride_map.point(scene, {"cadence_spm": 150.0, "step_length_m": 1.2})[0] == pytest.approx(3.0)


def test_the_cadence_curve_is_the_least_costly_optimum_its_neighbours_reach(scene, free_optimum):
    """Each cadence's stride lies above the free optimum, is the least costly of the optima
    its starts reached (CadenceCurve.tried), and no neighbour (the free optimum among them)
    leads a warm start to a cheaper one: the polish's fixed point (warm as the polish solves, so
    that the check is of the polish and not of which start finds which local optimum)."""
    cadences = [160.0, 190.0]
    curve = stride_map.cadence_curve(scene, 3.5, cadences, start=free_optimum)
    assert curve.free.success and set(curve.starts) <= {"free", "neighbour"}
    for cadence, stride, tried in zip(cadences, curve.strides, curve.tried):
        assert stride.success and stride.cadence_spm == pytest.approx(cadence, rel=1e-9)
        assert stride.objective_value >= curve.free.objective_value * (1 - 1e-6)
        assert stride.objective_value == pytest.approx(min(tried), rel=1e-6)
    nlp = scene.nlp()
    order = sorted([(c, s) for c, s in zip(cadences, curve.strides)] + [(curve.free.cadence_spm, curve.free)],
                   key=lambda cs: cs[0])
    for (c0, s0), (c1, s1) in pairwise(order):
        for cadence, kept, source in ((c1, s1, s0), (c0, s0, s1)):
            if kept is curve.free:
                continue
            again = stride_map.warm(nlp, source, 3.5, 0.0, scene.friction, cadence)
            assert not again.success or again.objective >= kept.objective_value * (1 - 1e-6)


def test_the_first_sweep_on_a_pool_is_the_same_solves(scene, free_optimum):
    """stride_map.first_sweep: each cadence solved from the free optimum on a pool's workers
    (the farthest first) gives the strides solved here, bit for bit, in the cadences' order."""
    base = free_optimum
    cadences = [175.0, 160.0, 190.0]
    here = stride_map.first_sweep(scene, base, 3.5, 0.0, scene.friction, cadences, None)
    with Background(2) as pool:
        there = stride_map.first_sweep(scene, base, 3.5, 0.0, scene.friction, cadences, pool)
    assert [s.cadence_spm for s in there] == pytest.approx(cadences, rel=1e-9)
    assert [s.objective_value for s in there] == [s.objective_value for s in here]
    assert all(np.array_equal(a.solved.x, b.solved.x) for a, b in zip(here, there))


def test_the_polish_sweeps_from_neighbours_past_the_free_optimum():
    """stride_map._polish (cadence_curve's step 2): each cadence re-solved from its neighbour,
    both ways once, the free optimum's cadence (165) neither re-solved nor a source (step 1 solved
    every cadence from it): its neighbours from the cadence beyond it; no change ends it."""
    kept = {c: (SimpleNamespace(success=True, cadence=c), "free") for c in (150.0, 160.0, 170.0, 180.0)}
    tried = []

    def attempt(target, source, how):
        tried.append((target, source.cadence))
        return False

    stride_map._polish([150.0, 160.0, 165.0, 170.0, 180.0], 165.0, kept, attempt)
    assert tried == [(170.0, 180.0), (160.0, 170.0), (150.0, 160.0),  # falling
                     (160.0, 150.0), (170.0, 160.0), (180.0, 170.0)]  # rising, then nothing changed


def test_figures_and_cli(scene, grid, tmp_path, capsys):
    _, rows = grid
    assert set(stride_sweep_figures(rows, [n for n, _ in PARAMS])) == {"cadence", "speed", "map"}
    assert main(["sweep", str(SHIPPED / "stride.toml"), "--param", "speed_mps=3:3:1",
                 "--param", "cadence_spm=40:50:2", "--out", str(tmp_path / "x.csv")]) == 2
    assert "cadence_spm" in capsys.readouterr().err


def test_chains_do_not_depend_on_the_workers(scene):
    """A stride map's chains (and so its rows) are cut the same on 1, 2 or 8 workers or a
    cluster: 861 points in 8 chains of 108, 200 in 8 of 25, 40 in 3 of 16 (issue 37: cut by the
    workers, 4 of 12 points came out 9-36 % costlier on 2 workers than on 1)."""
    kind = sweep.kind_of(scene, PARAMS)
    for points, size in ((861, 108), (200, 25), (40, 16), (4, 16)):
        sizes = {sweep.chunk_size(kind, points, w, s) for w, s in ((1, None), (2, None), (8, None), (1, "tcp://x"))}
        assert sizes == {size}


def test_a_chain_in_this_process_moves_the_bar_point_by_point(scene, tmp_path, monkeypatch):
    """Issue 36 item 7: a stride map's chain (up to 120 strides) moved the bar only when it
    ended, with no remaining time before; each stride now moves it, and a resumed chain's
    points already written do not."""
    moves = []

    class Bar:
        def update(self, n):
            moves.append(n)

        def close(self):
            pass

    def rows(s, chunk, tick=None):
        out = []
        for values in chunk:
            speed, _, mu, cadence = stride_map.point(s, values)
            out.append(stride_map.StrideRow(speed, 0.0, mu, cadence, error="not solved here").to_dict())
            tick()
        return out

    monkeypatch.setattr(sweep, "progress_bar", lambda total, desc, unit, initial: Bar())
    monkeypatch.setattr(stride_map, "rows", rows)
    path = tmp_path / "map.csv"
    sweep.run(scene, PARAMS, path)
    assert moves == [1, 1, 1, 1, 0]  # one chain of 4: a tick per stride, nothing left at its end
    lines = path.read_text().splitlines(keepends=True)
    path.write_text("".join(lines[:-1]))  # one row lost: the chain runs again, one row new
    moves.clear()
    sweep.run(scene, PARAMS, path)
    assert moves == [1, 0]
