"""Optimum maps (formopt sweep on a scene with [optimize]): warm-started chains agree with
cold solves, rows resume, the pool and Dask give the same map, the CLI draws it."""

import itertools

import numpy as np
import pytest
from helpers import SHIPPED

from formopt import load, solve
from formopt.cli import main
from formopt.studies import optimum_map, sweep

DEMO = SHIPPED / "demo_support.toml"  # the weighted optimum the map tests were written on
PARAMS = [("speed_mps", np.linspace(3.0, 4.0, 5)), ("friction", np.array([0.6, 0.8, 1.0]))]


def angles(rows):
    return np.array([[float(r[k]) for k in ("hip_deg", "knee_deg", "ankle_deg", "T_c")] for r in rows])


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return sweep.run(load(DEMO), PARAMS, tmp_path_factory.mktemp("map") / "map.csv", progress=False)


def test_the_serpentine_visits_every_point_next_to_the_one_before():
    params = [("a", np.arange(3.0)), ("b", np.arange(4.0)), ("c", np.arange(2.0))]
    walk = optimum_map.serpentine(params)
    assert len({tuple(p.values()) for p in walk}) == 24
    for p, q in itertools.pairwise(walk):
        assert sum(abs(p[k] - q[k]) for k in p) == 1.0


def test_warm_started_optima_are_the_cold_optima(serial):
    scene = load(DEMO)
    assert len(serial) == 15 and all(r["success"] == "True" for r in serial)
    assert sum(r["warm"] == "True" for r in serial) >= 13
    for r in serial[::4]:
        cold = solve(sweep.apply(scene, {"speed_mps": float(r["speed_mps"]),
                                         "friction": float(r["friction"])}))
        assert cold.success
        assert float(r["T_c"]) == pytest.approx(cold.impact.T_c, rel=1e-6)  # at the point's friction
        np.testing.assert_allclose([float(r[f"{v}_deg"]) for v in ("hip", "knee", "ankle")],
                                   np.degrees(cold.state[[1, 2, 3]]), atol=1e-5)


def test_a_second_run_resumes_and_the_pool_and_dask_agree(serial, tmp_path, dask_scheduler):
    scene = load(DEMO)
    again = sweep.run(scene, PARAMS, tmp_path / "pool.csv", progress=False, workers=2)
    np.testing.assert_allclose(angles(again), angles(serial), atol=1e-6)
    assert sweep.run(scene, PARAMS, tmp_path / "pool.csv", progress=False) == again  # resumed
    dask = sweep.run(scene, PARAMS, tmp_path / "dask.csv", progress=False, scheduler=dask_scheduler)
    np.testing.assert_allclose(angles(dask), angles(serial), atol=1e-6)


def test_cli_draws_the_map_and_refuses_a_decision_variable(tmp_path, capsys):
    out = tmp_path / "map.csv"
    assert main(["sweep", str(DEMO), "--param", "friction=0.5:1.0:3", "--out", str(out),
                 "--no-progress", "--workers", "1"]) == 0
    text = capsys.readouterr().out
    assert "3 optima" in text and "interior" in text and out.with_suffix(".png").exists()
    assert main(["sweep", str(DEMO), "--param", "knee_deg=0:10:3", "--out", str(out)]) == 2
    assert "decision variable" in capsys.readouterr().err


def test_a_slope_axis_reuses_one_problem(tmp_path, monkeypatch):
    """Slope is a parameter of a no-slip impact NLP: a map across it builds the problem once,
    and each row is the cold optimum of the scene built on that slope."""
    from pathlib import Path

    from formopt.io.scene import Scene
    built = []
    original = Scene.posture_problem
    monkeypatch.setattr(Scene, "posture_problem", lambda s, **k: built.append(s.slope) or original(s, **k))
    monkeypatch.setattr(optimum_map, "_PROBLEMS", {})
    scene = load(Path(__file__).parents[1] / "optim" / "bounded.toml")
    rows = sweep.run(scene, [("slope_deg", np.array([-4.0, 0.0, 4.0]))], tmp_path / "slope.csv",
                     progress=False)
    assert built == [scene.slope]
    header = (tmp_path / "slope.csv").read_text().splitlines()[0].split(",")
    assert header[:4] == ["slope_deg", "hip_deg", "knee_deg", "ankle_deg"]
    assert header[4:] == [c for c in optimum_map.COLUMNS if c != "slope_deg"]  # the swept one once
    assert all(float(r["friction"]) == scene.friction for r in rows)  # each row says its ground
    for r in rows:
        cold = solve(sweep.apply(scene, {"slope_deg": float(r["slope_deg"])}))
        assert r["success"] == "True" and cold.success
        assert float(r["T_c"]) == pytest.approx(cold.impact.T_c, rel=1e-6)
        assert r["verdict"] == cold.verdict


def test_the_problem_cache_follows_the_scene_content_not_its_path(tmp_path, monkeypatch):
    """Two scenes, then one scene edited in place (another objective) at the same path, in one
    process: each map row is the cold optimum of the scene as it is now (issue 25: the edited
    scene's map reported the first scene's optimum)."""
    monkeypatch.setattr(optimum_map, "_PROBLEMS", {})
    path = tmp_path / "scene.toml"
    text = DEMO.read_text().replace("starts = 8", "starts = 2")
    edited = text.replace("objective = { T_c = 1.0, support = 0.1 }", 'objective = "support"')
    assert edited != text
    bounded = SHIPPED.parent.parent / "tests" / "optim" / "bounded.toml"
    for source in (text, bounded.read_text(), edited):
        path.write_text(source)
        scene = load(path)
        (row,) = optimum_map.rows(scene, [{"friction": 0.8}])
        cold = solve(sweep.apply(scene, {"friction": 0.8}))
        assert row["success"] is True and cold.success
        assert row["objective"] == pytest.approx(cold.objective, rel=1e-6, abs=1e-9)
        assert row["T_c"] == pytest.approx(cold.impact.T_c, rel=1e-6)


def test_a_resumed_map_gives_the_rows_of_an_uninterrupted_run(tmp_path):
    """Whichever rows were written before an interruption, the resumed map on 2 workers is the
    uninterrupted one to the last digit, warm and iteration columns included (issue 25)."""
    scene = load(DEMO)
    whole = sweep.run(scene, PARAMS, tmp_path / "whole.csv", progress=False, workers=2)
    lines = (tmp_path / "whole.csv").read_text().splitlines()
    kept = [line for k, line in enumerate(lines) if k == 0 or k % 3 == 1]  # a chunk's first, middle rows
    (tmp_path / "resumed.csv").write_text("\n".join(kept) + "\n")
    resumed = sweep.run(scene, PARAMS, tmp_path / "resumed.csv", progress=False, workers=2)
    assert resumed == whole
