"""optim.stride.ranges: one home for the [stride] ranges; derived speed, cadence and step length
refused before any solve, at every entry point (scene, API, map grid)."""

import dataclasses

import numpy as np
import pytest
from helpers import SHIPPED

import formopt
from formopt.io.scene import SceneError
from formopt.mechanics.errors import InputError
from formopt.optim.stride import ranges
from formopt.studies import stride_map


@pytest.fixture(scope="module")
def scene():
    return formopt.load(SHIPPED / "stride.toml")


@pytest.mark.parametrize("speed, cadence, step, words", [
    (0.0, None, None, "speed_mps"), (-3.5, None, None, "speed_mps"), (np.nan, None, None, "speed_mps"),
    (3.5, 60.0, None, "step_length_m = 3.5"), (3.5, 1000.0, None, "cadence_spm"),
    (1.0, None, 0.2, "step_length_m"), (8.0, None, 0.3, "cadence_spm = 1600"),
    (3.5, 170.0, 1.2, "impose one of them")])
def test_a_point_outside_the_ranges_is_refused(speed, cadence, step, words):
    with pytest.raises(InputError, match=words):
        ranges.point(speed, cadence, step)


def test_a_runners_point_passes():
    assert ranges.point(3.5, None, 1.2) == (3.5, pytest.approx(175.0))
    assert ranges.point(3.5, 171.4) == (3.5, 171.4)


@pytest.mark.parametrize("speed", [0.0, -3.5, float("nan"), 9.0])
def test_the_api_refuses_what_the_command_line_refuses(scene, speed):
    """formopt.stride(scene, speed=0.0) is refused, not replaced by the scene's speed."""
    with pytest.raises(InputError, match="speed_mps"):
        formopt.stride(scene, speed=speed)


def test_a_scene_whose_cadence_gives_no_run_is_refused():
    data = {"scene": {"name": "s"}, "ground": {"friction": 0.8},
            "stride": {"speed_mps": 3.5, "cadence_spm": 60.0}}
    with pytest.raises(SceneError, match=r"stride\.cadence_spm.*step_length_m = 3\.5"):
        formopt.io.scene.parse(data)


@pytest.mark.parametrize("params, words", [
    ([("speed_mps", np.array([3.0, 3.5])), ("step_length_m", np.array([0.2, 1.0]))], "step_length_m"),
    ([("cadence_spm", np.array([60.0, 170.0])), ("step_length_m", np.array([0.3, 1.0]))], "speed of 0.3"),
    ([("friction", np.array([-1.0, 0.8]))], "friction"),
    ([("slope_deg", np.array([45.0]))], "slope_deg")])
def test_a_map_grid_is_checked_before_any_solve(scene, params, words):
    """Every point of the grid, its derived values too, before the first solve."""
    shallow = dataclasses.replace(scene, strike="heel")
    with pytest.raises(InputError, match=words):
        stride_map.check(shallow, params)


def test_settings_use_the_same_ranges():
    from formopt.optim.stride import StrideSettings

    for bad, key in (({"nodes": 401}, "nodes"), ({"impact_weight": -1.0}, "impact_weight"),
                     ({"tendons": {"ankle": 30.0}}, "tendons.ankle"),
                     ({"duration": {"flight": (0.0, 0.3)}}, "duration flight"),
                     ({"duration": {"heell": (0.01, 0.1)}}, "duration heell: expected a phase")):
        with pytest.raises(InputError, match=key):
            StrideSettings(**bad)


def test_a_mesh_study_may_pass_the_scenes_nodes_never_go_below_them(monkeypatch):
    monkeypatch.setitem(ranges.RANGES, "nodes", ranges.RANGES["nodes"])  # restored after the test
    ranges.allow_nodes(160)
    assert 160 in ranges.RANGES["nodes"] and 161 not in ranges.RANGES["nodes"]
    ranges.allow_nodes(80)
    assert ranges.RANGES["nodes"].high == 120 and ranges.RANGES["nodes"].low == 14
