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
from formopt.measure.clean import measured_frames
from formopt.measure.filters import CUTOFF_HZ
from formopt.measure.rigid import angular_velocity
from formopt.measure.stance import at_rest, stance_paths
from formopt.measure.touchdowns import STEP_WINDOW


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


FOOT = [f"R_foot_{i}" for i in range(1, 5)]
REPLAY = 1.28  # the RIC runner's 164 steps/min played at 210


@pytest.fixture(scope="module")
def fast_ric():
    """The RIC runner's first 10 s with 0.7 mm of noise (a 200 Hz system's), declared at 1.28
    times its rate (210 steps/min), and its measurement; the rest of the pipeline in frames
    as at the real rate (the markers' cut-off scaled alike)."""
    run, static = mocap.read(RIC_RUN), mocap.read(RIC_STATIC)
    rng = np.random.default_rng(0)
    run.markers = {k: v[:2000] + rng.normal(0.0, 0.7, (2000, 3)) for k, v in run.markers.items()}  # mm
    run.rate *= REPLAY
    return run, static, _measure(run, static)


def _measure(run, static):
    return measure(run, static, RIC_HEIGHT, Options(cutoff_hz=CUTOFF_HZ * REPLAY))


def _corrupted(run, kind: str, a: int = 600, b: int = 1400):
    """`run` with the right foot cluster frozen, lost, turned 20 deg toe-up about its centre
    (about the lab's x, RIC's lateral) or dropping a marker 30 of every 100 frames, over frames
    a to b (4 s at the real rate, 3.1 s replayed)."""
    bad = copy.deepcopy(run)
    M = np.stack([bad.markers[n][a:b] for n in FOOT], axis=1)
    if kind == "frozen":
        M[:] = M[0]
    elif kind == "lost":
        M[:] = np.nan
    elif kind == "turned":
        centre = M.mean(axis=1, keepdims=True)
        M = (M - centre) @ Rotation.from_euler("x", 20, degrees=True).as_matrix().T + centre
    for i, n in enumerate(FOOT):
        bad.markers[n][a:b] = M[:, i]
    if kind == "drop-outs":
        for j in range(a, b, 100):
            bad.markers[FOOT[0]][j:j + 30] = np.nan
    return bad


@pytest.mark.parametrize("kind, needle", [
    ("frozen", "touchdowns not found; the foot's markers not measured in 9"),
    ("lost", "touchdowns not found; the foot's markers not measured in 9"),
    ("turned", "from its side's"),
    ("drop-outs", "missing or spiked samples in R_foot_1"),
])
def test_a_fast_runner_with_one_bad_foot_cluster_keeps_the_other(fast_ric, kind, needle):
    """Issue 35: at 210 steps/min with the right foot's cluster corrupted for a third of the
    trial, the left foot's touchdowns are all found and sound, the right foot's outside the
    stretch are kept, those inside (but for a step between two drop-outs) are listed and left
    out with their reason, and the axes
    and belt stay within 0.5 deg and 1 % of the clean run's."""
    run, static, clean = fast_ric
    m = _measure(_corrupted(run, kind), static)
    steps, sound = m.steps, clean.steps
    assert [td.frame for td in steps.touchdowns if td.side == "L" and td.valid_data] == \
        [td.frame for td in sound.touchdowns if td.side == "L"]
    inside = [td for td in steps.touchdowns if td.side == "R" and 600 <= td.frame < 1400]
    measured = measured_frames(m.trial, FOOT)
    window = round(STEP_WINDOW * run.rate)
    # kept inside the stretch: only a step between two drop-outs, its markers measured
    assert all(kind == "drop-outs" and measured[td.frame - window:td.frame + window + 1].all()
               for td in inside if td.valid_data)
    outside = [td.frame for td in steps.touchdowns if td.side == "R" and td.valid_data]
    assert len(outside) >= sum(td.side == "R" and not 590 <= td.frame < 1410 for td in sound.touchdowns) - 1
    assert any(needle in why for why in steps.left_out)
    assert math.degrees(math.acos(min(1.0, float(m.calibration.axes.up @ clean.calibration.axes.up)))) < 0.5
    assert steps.belt_speed == pytest.approx(sound.belt_speed, rel=0.01)


def test_neither_foot_found_is_refused_naming_each_foot_s_tests(fast_ric):
    """Both foot clusters lost for all but 40 frames each (never the same ones): no stance
    of either foot; the refusal names each foot and the share of frames each test passed."""
    run, static, _ = fast_ric
    bad = copy.deepcopy(run)
    for side, keep in (("R", slice(100, 140)), ("L", slice(1000, 1040))):
        for n in (f"{side}_foot_{i}" for i in range(1, 5)):
            kept = bad.markers[n][keep].copy()
            bad.markers[n][:] = np.nan
            bad.markers[n][keep] = kept
    with pytest.raises(mocap.MocapError, match=r"neither foot rests.*right: measured 2 %.*left: measured 2 %"):
        _measure(bad, static)


def test_segment_angles_without_a_plate_are_the_plate_s(measured, without_plate):
    """Issue 35 item 4: RBDS001's touchdowns found again without the plate (by the foot's
    speed) and measured on the vertical of the resting feet's paths: each side's mean thigh and
    shank angle within 0.5 deg of the plate's (0.23-0.24 deg when written, the verticals'
    difference); nine steps in ten within 1.5 deg (a touchdown one marker frame off: the shank
    turns up to 2.6 deg in a frame at 150 Hz)."""
    for speed, m in without_plate.items():
        plate = measured[speed].steps.touchdowns
        for side in ("R", "L"):
            for seg in ("thigh", "shank"):
                pairs = [(td, min(m.steps.touchdowns, key=lambda o: abs(o.time - td.time) + 9 * (o.side != side)))
                         for td in plate if td.side == side]
                diff = np.degrees([o.segments[seg] - td.segments[seg] for td, o in pairs])
                assert abs(np.mean(diff)) < 0.5
                assert np.percentile(np.abs(diff), 90) < 1.5
