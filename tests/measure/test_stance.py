"""The foot-at-rest rule and the resting feet's level paths (formopt/measure/stance.py), the
cluster's angular velocity (rigid.py), and the vertical they give without a force plate."""

import copy
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from trials import HEIGHT, RIC_HEIGHT, RIC_RUN, RIC_STATIC

from formopt.io import mocap
from formopt.measure import Options, measure
from formopt.measure.filters import CUTOFF_HZ
from formopt.measure.rigid import angular_velocity
from formopt.measure.stance import at_rest, stance_paths


def test_angular_velocity_against_scipy():
    """A rotation turning at a known, changing rate about a tilted axis: the central
    difference of R against scipy's rotation vector of R[k+1] R[k-1]^T."""
    rate, t = 200.0, np.arange(100) / 200.0
    axis = np.array([0.2, 0.9, 0.3]) / np.linalg.norm([0.2, 0.9, 0.3])
    R = Rotation.from_rotvec(np.outer(3.0 * t + 4.0 * t ** 2, axis)).as_matrix()
    found = angular_velocity(R, rate)
    expected = (Rotation.from_matrix(R[2:]) * Rotation.from_matrix(R[:-2]).inv()).as_rotvec() * rate / 2
    assert found[1:-1] == pytest.approx(expected, abs=1e-9)
    assert found[50] @ axis == pytest.approx(3.0 + 8.0 * t[50], rel=1e-3)


def _foot(cadence_spm: float, rate: float = 200.0, seconds: float = 6.0):
    """A foot's height (m), pitch rate (rad/s) and vertical speed (m/s): at rest 35 % of each
    stride, swinging (a raised cosine) otherwise; a 0.1 mm, 0.01 rad/s noise."""
    t = np.arange(int(seconds * rate)) / rate
    phase = (t * cadence_spm / 120.0) % 1.0
    swing = np.clip((phase - 0.35) / 0.65, 0.0, 1.0)
    height = 0.02 + 0.1 * (1 - np.cos(2 * np.pi * swing)) / 2
    noise = np.random.default_rng(0).normal(0, 1, (2, len(t)))
    return height + 1e-4 * noise[0], np.gradient(height, 1 / rate) * 60 + 0.01 * noise[1], \
        np.gradient(height, 1 / rate), phase


def test_the_rest_rule_finds_each_stance_at_any_cadence():
    """The same stride played at 150 and 230 steps/min: rest found in every stride, only
    where the foot is within 5 mm of the ground."""
    for cadence in (150.0, 230.0):
        height, omega, v_up, phase = _foot(cadence)
        rest = at_rest(height, omega, v_up)
        assert np.all(height[rest] < 0.025)
        strides = np.floor(np.arange(len(phase)) / 200.0 * cadence / 120.0).astype(int)
        assert set(strides[rest]) == set(strides[:-1])


def test_stance_paths_find_a_tilted_belt():
    """Feet resting on a belt that runs 1.5 deg downhill along x (z up): the paths' direction,
    with 1 mm marker noise, within 0.1 deg; the bootstrap spread small and both sides alike."""
    rate, rng = 150.0, np.random.default_rng(2)
    belt = np.array([-math.cos(math.radians(1.5)), 0.0, -math.sin(math.radians(1.5))]) * 3.0
    markers, rest = {}, {}
    for s, y in (("R", -0.1), ("L", 0.1)):
        shape = rng.normal(0, 0.04, (4, 3)) + [0.0, y, 0.05]
        t = np.arange(1500) / rate
        M = shape[None] + np.outer(t % 0.7, belt)[:, None, :] + rng.normal(0, 0.001, (1500, 4, 3))
        markers[s], rest[s] = M, (t % 0.7 > 0.05) & (t % 0.7 < 0.2)
    paths = stance_paths(markers, rest, rate)
    assert paths is not None and len(paths.sides) == 2 * 15
    up = np.array([0.0, 0.0, 1.0])
    assert math.degrees(math.asin(paths.direction @ up)) == pytest.approx(-1.5, abs=0.1)
    assert math.degrees(paths.spread(up)) < 0.1
    assert all(math.degrees(e) == pytest.approx(-1.5, abs=0.1) for e in paths.side_elevations(up).values())


@pytest.fixture(scope="module")
def without_plate(measured, static, run35, run25):
    """RBDS001 T35 and T25 measured again with their forces dropped, by speed."""
    out = {}
    for speed, run in ((3.5, run35), (2.5, run25)):
        trial = copy.copy(run)
        trial.force, trial.force_rate = None, None
        out[speed] = measure(trial, static, HEIGHT)
    return out


def test_the_vertical_without_a_plate_is_within_a_degree_of_the_plates(measured, without_plate):
    """The standing body pitched to the resting feet's level paths: 0.28 deg (T35) and 0.25
    deg (T25) from the plate's mean force when written (2.0 and 1.0 deg with the stance
    foot's median velocity); the goal of issue 24 is 1 deg."""
    for speed, m in without_plate.items():
        up, lab = m.calibration.axes.up, measured[speed].calibration.axes.up
        assert "level paths" in m.calibration.axes.vertical
        assert math.degrees(math.acos(min(1.0, float(up @ lab)))) < 0.5


@pytest.mark.parametrize("factor", [1.3])
def test_a_run_played_faster_rests_and_lands_in_the_same_frames(factor):
    """The RIC runner (a heel striker, 164 steps/min at 200 Hz) declared at 1.3 times its rate
    runs 214 steps/min; with the markers' cut-off scaled alike (the rest of the pipeline is
    then the same in frames) every touchdown falls in the same frame, and the belt runs 1.3
    times faster. A rate 10 times too high is still refused, naming the rate."""
    run, static = mocap.read(RIC_RUN), mocap.read(RIC_STATIC)
    run.markers = {k: v[:2000] for k, v in run.markers.items()}  # the first 10 s
    base = measure(run, static, RIC_HEIGHT).steps
    fast = copy.deepcopy(run)
    fast.rate *= factor
    steps = measure(fast, static, RIC_HEIGHT, Options(cutoff_hz=CUTOFF_HZ * factor)).steps
    assert steps.cadence_spm == pytest.approx(base.cadence_spm * factor, rel=1e-6) and steps.cadence_spm > 210
    assert [(td.frame, td.side) for td in steps.touchdowns] == [(td.frame, td.side) for td in base.touchdowns]
    assert steps.belt_speed == pytest.approx(base.belt_speed * factor, rel=1e-3)
    fast.rate = run.rate * 10
    with pytest.raises(mocap.MocapError, match=r"is the rate, 2000 Hz, right\?"):
        measure(fast, static, RIC_HEIGHT)
