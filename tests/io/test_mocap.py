"""Motion capture on the real RBDS data (subject 001) and on damaged copies of it."""

import copy
import json
import math
import shutil

import numpy as np
import pytest

from formopt.io import mocap
from formopt.cli import main
from helpers import DATA

DATA = DATA / "rbds"
RUN35, STATIC = DATA / "RBDS001runT35.c3d", DATA / "RBDS001static.c3d"
RUN25, FORCES25 = DATA / "RBDS001runT25markers.txt", DATA / "RBDS001runT25forces.txt"


@pytest.fixture(scope="module")
def static():
    return mocap.read(STATIC)


@pytest.fixture(scope="module")
def cal(static):
    return mocap.calibrate(static)


@pytest.fixture(scope="module")
def run35():
    return mocap.read(RUN35)


@pytest.fixture(scope="module")
def run25():
    return mocap.read(RUN25, FORCES25)


@pytest.fixture(scope="module")
def steps(run35, run25, cal):
    out = {}
    for speed, trial in ((3.5, run35), (2.5, run25)):
        kin = mocap.kinematics(trial, cal)
        out[speed] = (kin, mocap.touchdowns(trial, kin, cal))
    return out


def test_files_read_with_their_units_and_rates(run35, run25, static):
    assert run35.rate == 150.0 and run35.force_rate == 300.0
    assert run25.rate == pytest.approx(150.0) and run25.force_rate == pytest.approx(300.0)
    # markers in metres: a pelvis marker about a metre above the floor, not a thousand
    assert 0.5 < np.nanmedian(run35.markers["R.ASIS"][:, 1]) < 1.5
    assert np.max(np.abs(run35.force)) > 1000.0  # N, from ezc3d's force-plate calibration


def test_lab_axes_are_found_and_agree_with_gravity(cal, run35, run25):
    """The floor plane of the standing trial gives 'up'; the ground reaction force, averaged
    over the runs (body weight), points the same way: an independent check."""
    for trial in (run35, run25):
        mean_force = trial.force.mean(axis=0)
        assert mean_force @ cal.axes.up / np.linalg.norm(mean_force) > 0.99
        assert 400 < mean_force @ cal.axes.up < 800  # about 62 kg * 9.81 N
    assert abs(cal.axes.forward @ cal.axes.up) < 1e-12
    assert "forward +X" in cal.axes.describe() and "up +Y" in cal.axes.describe()


def test_belt_speed_is_the_trial_speed(steps):
    assert steps[3.5][1].belt_speed == pytest.approx(3.5, abs=0.15)
    assert steps[2.5][1].belt_speed == pytest.approx(2.5, abs=0.15)


@pytest.mark.parametrize("speed", [2.5, 3.5])
def test_touchdowns_come_at_the_treadmill_cadence(steps, run35, run25, cal, speed):
    """Cadence from the touchdown events equals the vertical force's dominant frequency."""
    trial = run35 if speed == 3.5 else run25
    _, st = steps[speed]
    vertical = trial.force @ cal.axes.up
    spectrum = np.abs(np.fft.rfft(vertical - vertical.mean()))
    freqs = np.fft.rfftfreq(len(vertical), 1 / trial.force_rate)
    band = (freqs > 1.5) & (freqs < 4.0)
    step_hz = freqs[band][np.argmax(spectrum[band])]
    assert st.cadence_spm == pytest.approx(60 * step_hz, rel=0.02)
    sides = [td.side for td in st.touchdowns]
    assert all(a != b for a, b in zip(sides, sides[1:])), "touchdowns alternate right, left"


@pytest.mark.parametrize("speed", [2.5, 3.5])
def test_subject_001_is_not_a_rearfoot_striker(steps, speed):
    """RBDSinfo labels subject 001 a forefoot striker at 2.5 and 3.5 m/s. By the foot strike
    angle (Altman & Davis 2012) the right foot strikes forefoot every step; the left lands
    flatter (midfoot); no step is a rearfoot strike."""
    _, st = steps[speed]
    right = [td.strike for td in st.touchdowns if td.side == "R"]
    assert right.count("forefoot") == len(right)
    assert all(td.strike != "heel" for td in st.touchdowns)


@pytest.mark.parametrize("speed", [2.5, 3.5])
def test_angles_lie_in_physiological_ranges(steps, speed):
    _, st = steps[speed]
    for td in st.touchdowns:
        a = {k: math.degrees(v) for k, v in td.angles.items()}
        assert -10 < a["trunk"] < 30 and 0 < a["hip"] < 45
        assert 0 < a["knee"] < 40 and -35 < a["ankle"] < 20
        assert -25 < math.degrees(td.foot_strike_angle) < 25
        assert 0.8 < td.hip_height < 1.1
        assert td.hip_velocity[0] == pytest.approx(speed, abs=0.4) and -1.2 < td.hip_velocity[1] < 0


def test_kinematic_touchdowns_agree_with_the_force_plate(run25, cal, steps):
    trial = copy.copy(run25)
    trial.force, trial.force_rate = None, None
    kin = mocap.kinematics(trial, cal)
    kinematic = mocap.touchdowns(trial, kin, cal)
    assert kinematic.method == "kinematics"
    force_times = np.array([td.time for td in steps[2.5][1].touchdowns])
    for td in kinematic.touchdowns:
        assert np.min(np.abs(force_times - td.time)) < 0.03  # within 30 ms of the force's
    assert kinematic.cadence_spm == pytest.approx(steps[2.5][1].cadence_spm, rel=0.02)


def test_c3d_and_text_paths_agree(run35, cal, steps, tmp_path):
    """The 3.5 m/s C3D trial written in the RBDS text layout reads back to the same data and
    the same touchdowns."""
    mocap.write_text(run35, tmp_path / "m.txt", tmp_path / "f.txt")
    text = mocap.read(tmp_path / "m.txt", tmp_path / "f.txt")
    assert text.rate == pytest.approx(run35.rate) and text.force_rate == pytest.approx(run35.force_rate)
    for name, xyz in run35.markers.items():
        assert np.allclose(text.markers[name], xyz, atol=1e-9)
    kin = mocap.kinematics(text, cal)
    again = mocap.touchdowns(text, kin, cal)
    assert [td.time for td in again.touchdowns] == pytest.approx([td.time for td in steps[3.5][1].touchdowns])


def test_missing_markers_are_named(run35, cal):
    trial = copy.copy(run35)
    trial.markers = {k: v for k, v in run35.markers.items() if k not in ("R.MT5", "L.ASIS")}
    with pytest.raises(mocap.MocapError, match="missing: L.ASIS, R.MT5"):
        mocap.kinematics(trial, cal)


def test_short_gaps_are_filled_and_long_ones_leave_their_steps_out(cal, steps):
    markers = {k: v.copy() for k, v in mocap.read(RUN35).markers.items()}
    frame = steps[3.5][1].touchdowns[10].frame
    markers["R.Heel.Top"][100:103] = np.nan  # 3 frames: interpolated
    side = steps[3.5][1].touchdowns[10].side
    markers[f"{side}.MT1"][frame - 20:frame + 20] = np.nan  # 40 frames around a touchdown
    trial = mocap.fill_gaps(mocap.Trial(markers, 150.0, mocap.read(RUN35).force, 300.0, "damaged"))
    assert np.all(np.isfinite(trial.markers["R.Heel.Top"]))
    assert "R.Heel.Top" not in trial.gaps and f"{side}.MT1" in trial.gaps
    kin = mocap.kinematics(trial, cal)
    st = mocap.touchdowns(trial, kin, cal)
    assert any(f"{side}.MT1" in why for why in st.left_out)
    assert len(st.touchdowns) == len(steps[3.5][1].touchdowns) - len(st.left_out)


def test_empty_force_plate_falls_back_to_kinematics(tmp_path, run25):
    markers = tmp_path / "m.txt"
    shutil.copy(RUN25, markers)
    forces = tmp_path / "f.txt"
    forces.write_text("Time\tFx\tFy\tFz\n" + "".join(f"{k}\t0\t0\t0\n" for k in range(1, 9001)))
    trial = mocap.read(markers, forces)
    assert trial.force is None and any("force plate is empty" in n for n in trial.notes)


@pytest.mark.parametrize("damage,needle", [
    ("truncate", "truncated: the file declares 4500 frames"),
    ("empty", "not a readable C3D"),
])
def test_damaged_c3d_files_are_refused(tmp_path, damage, needle):
    path = tmp_path / "run.c3d"
    data = RUN35.read_bytes()
    path.write_bytes(data[:len(data) // 3] if damage == "truncate" else b"")
    with pytest.raises(mocap.MocapError, match=needle):
        mocap.read(path)


def test_cli_compare_json_and_bad_input(tmp_path, capsys):
    code = main(["compare", "--trial", str(RUN35), "--static", str(STATIC), "--mass", "62",
                 "--height", "1.81", "--json", "--out", str(tmp_path)])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    for key in ("cadence_spm", "touchdowns", "optimum"):
        assert key in data
    td = data["touchdowns"][0]
    assert {"time", "side", "strike", "angles_deg", "foot_angle_deg", "hip_velocity", "T_c"} <= set(td)
    assert set(td["angles_deg"]) == {"trunk", "hip", "knee", "ankle"}
    assert {"touchdown", "T_c"} <= set(data["optimum"]) and data["optimum"]["success"]
    assert (tmp_path / "comparison.png").stat().st_size > 0
    assert len((tmp_path / "touchdowns.csv").read_text().splitlines()) == len(data["touchdowns"]) + 1
    assert main(["compare", "--trial", str(tmp_path / "none.c3d"), "--static", str(STATIC),
                 "--mass", "62", "--height", "1.81"]) == 2
    assert "no such file" in capsys.readouterr().err


def test_cli_bad_motion_capture_exits_2_with_one_line(tmp_path, run35, capsys):
    trial = copy.copy(run35)
    trial.markers = {k: v for k, v in run35.markers.items() if k != "L.Shank.Top.Medial"}
    mocap.write_text(trial, tmp_path / "m.txt", tmp_path / "f.txt")
    args = ["--static", str(STATIC), "--mass", "62", "--height", "1.81", "--out", str(tmp_path)]
    assert main(["compare", "--trial", str(tmp_path / "m.txt"), "--forces", str(tmp_path / "f.txt"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "L.Shank.Top.Medial" in err[0]
    data = RUN35.read_bytes()
    (tmp_path / "cut.c3d").write_bytes(data[: len(data) // 2])
    assert main(["compare", "--trial", str(tmp_path / "cut.c3d"), *args]) == 2
    assert "truncated" in capsys.readouterr().err
