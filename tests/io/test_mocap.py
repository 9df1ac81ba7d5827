"""Motion capture on the real trials: RBDS subject 001 (two speeds, C3D and text) and the
Running Injury Clinic runner (clusters only, no units, no force plate)."""

import copy
import importlib.util
import json
import math

import numpy as np
import pytest

from formopt.cli import main
from formopt.io import markerset, mocap
from helpers import DATA, PROBLEMS

RBDS, RIC = DATA / "rbds", DATA / "ric"
RUN35, STATIC = RBDS / "RBDS001runT35.c3d", RBDS / "RBDS001static.c3d"
RUN25, FORCES25 = RBDS / "RBDS001runT25markers.txt", RBDS / "RBDS001runT25forces.txt"
RIC_RUN, RIC_STATIC = RIC / "20160226T120637_run.c3d", RIC / "20160226T120637_static.c3d"
HEIGHT = 1.81


@pytest.fixture(scope="module")
def static():
    return mocap.read(STATIC)


@pytest.fixture(scope="module")
def run35():
    return mocap.read(RUN35)


@pytest.fixture(scope="module")
def run25():
    return mocap.read(RUN25, FORCES25)


@pytest.fixture(scope="module")
def measured(run35, run25, static):
    return {3.5: mocap.measure(run35, static, HEIGHT), 2.5: mocap.measure(run25, static, HEIGHT)}


@pytest.fixture(scope="module")
def ric():
    return mocap.measure(mocap.read(RIC_RUN), mocap.read(RIC_STATIC), 1.77)


def test_files_read_with_their_units_and_rates(run35, run25):
    assert run35.rate == 150.0 and run35.force_rate == 300.0
    assert run25.rate == pytest.approx(150.0) and run25.force_rate == pytest.approx(300.0)
    assert 0.5 < np.nanmedian(run35.markers["R.ASIS"][:, 1]) < 1.5  # metres, not millimetres
    assert np.max(np.abs(run35.force)) > 1000.0  # N, from ezc3d's force-plate calibration


def test_marker_maps_are_recognised(run35, static):
    assert markerset.recognise(run35.markers).name == "rbds"
    assert markerset.recognise(mocap.read(RIC_RUN).markers).name == "ric"
    assert markerset.recognise(mocap.read(RIC_STATIC).markers).name == "ric"
    for name in markerset.shipped():
        assert markerset.load(name).name == name


def test_lab_vertical_is_the_mean_force_and_the_mt_swap_is_undone(measured):
    """RBDS T35: up from the mean force (the lab's Y, not the standing feet's plane 4.8 deg
    off); R.MT1 and R.MT5 swapped in the run relative to the standing trial, swapped back."""
    for m in measured.values():
        axes = m.calibration.axes
        assert axes.up[1] > 0.9999 and axes.forward[0] > 0.9999 and not axes.mirrored
        assert any("R.MT1 and R.MT5 are swapped" in n for n in m.steps.notes)


def test_belt_speed_and_cadence(measured):
    for speed, m in measured.items():
        assert m.steps.belt_speed == pytest.approx(speed, abs=0.1)
        assert m.steps.speed == pytest.approx(speed, abs=0.12)
        sides = [td.side for td in m.steps.touchdowns]
        assert all(a != b for a, b in zip(sides, sides[1:])), "touchdowns alternate right, left"
    assert measured[3.5].steps.cadence_spm == pytest.approx(171.4, abs=0.2)
    assert measured[2.5].steps.cadence_spm == pytest.approx(156.5, abs=0.2)


@pytest.mark.parametrize("speed", [2.5, 3.5])
def test_angles_lie_in_physiological_ranges(measured, speed):
    for td in measured[speed].steps.touchdowns:
        a = {k: math.degrees(v) for k, v in td.angles.items()}
        assert -10 < a["trunk"] < 30 and 0 < a["hip"] < 45
        assert 0 < a["knee"] < 40 and -35 < a["ankle"] < 20
        assert -25 < math.degrees(td.foot_strike_angle) < 25
        assert 0.8 < td.hip_height < 1.1
        assert td.hip_velocity[0] == pytest.approx(speed, abs=0.4) and -1.2 < td.hip_velocity[1] < 0


def test_subject_001_lands_midfoot_not_on_the_heel(measured):
    """With the lab vertical and the MT swap undone the right foot strike angle at 3.5 m/s is
    about +1 deg: midfoot (Altman & Davis), where the swapped labels made it -9.8 (forefoot)."""
    right = [td for td in measured[3.5].steps.valid if td.side == "R"]
    fsa = np.degrees([td.foot_strike_angle for td in right])
    assert -1.6 < fsa.mean() < 3 and all(td.strike != "heel" for td in measured[3.5].steps.touchdowns)


def test_a_second_method_agrees(measured):
    """Segment angles as standing angle + the cluster's sagittal pitch, the lab's Y as up and
    touchdowns from the foot's speed (problems/rbds_angles.py): within 2 deg of formopt's."""
    spec = importlib.util.spec_from_file_location("rbds_angles", PROBLEMS / "rbds_angles.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    m = measured[3.5]
    right = [td for td in m.steps.valid if td.side == "R"]
    ours = np.degrees([[td.angles[k] for k in ("hip", "knee", "ankle")] for td in right]).mean(axis=0)
    assert np.all(np.abs(module.second_method(m) - ours) < 2.0)


def test_kinematic_touchdowns_agree_with_the_force_plate(run25, static, measured):
    """The foot's speed over the ground (half the running speed) gives the force plate's
    touchdowns to a frame or two: also with a cluster-only map (no heel or toe markers)."""
    trial = copy.copy(run25)
    trial.force, trial.force_rate = None, None
    kinematic = mocap.measure(trial, static, HEIGHT).steps
    assert kinematic.method == "kinematics"
    force_times = np.array([td.time for td in measured[2.5].steps.touchdowns])
    gaps = [td.time - force_times[np.argmin(np.abs(force_times - td.time))] for td in kinematic.touchdowns]
    assert abs(np.median(gaps)) < 0.005 and np.percentile(np.abs(gaps), 90) < 0.015
    assert kinematic.cadence_spm == pytest.approx(measured[2.5].steps.cadence_spm, rel=0.02)


def test_ric_runner(ric):
    """Clusters only, POINT:UNITS empty, a one-frame static, no force plate: millimetres
    inferred, Y up and -Z forward found, about 3.4 m/s (the repository says 3.43), 164
    steps/min, rearfoot strikes with the knee near 10 deg."""
    s = ric.steps
    assert s.method == "kinematics" and any("no units in the file: millimetres" in n for n in s.notes)
    axes = ric.calibration.axes
    assert axes.up[1] > 0.999 and axes.forward[2] < -0.999
    assert s.speed == pytest.approx(3.43, abs=0.15) and s.cadence_spm == pytest.approx(164, abs=2)
    assert len(s.valid) > 60 and all(td.strike == "heel" for td in s.valid)
    knee = np.degrees([td.angles["knee"] for td in s.valid])
    assert 3 < knee.mean() < 20 and 10 < np.degrees(np.mean([td.foot_strike_angle for td in s.valid])) < 25


def test_c3d_and_text_paths_agree(run35, static, measured, tmp_path):
    mocap.write_text(run35, tmp_path / "m.txt", tmp_path / "f.txt")
    text = mocap.read(tmp_path / "m.txt", tmp_path / "f.txt")
    assert text.rate == pytest.approx(run35.rate) and text.force_rate == pytest.approx(run35.force_rate)
    again = mocap.measure(text, static, HEIGHT).steps
    assert [td.time for td in again.touchdowns] == pytest.approx([td.time for td in measured[3.5].steps.touchdowns])


def test_cli_compare_json_exports_and_bad_input(tmp_path, capsys):
    code = main(["compare", "--trial", str(RUN35), "--static", str(STATIC), "--mass", "62",
                 "--height", "1.81", "--json", "--out", str(tmp_path)])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    td = data["touchdowns"][0]
    assert {"segment_angles_deg", "foot_strike_angle_deg", "angles_deg", "rates_dps",
            "hip_velocity_mps", "method", "strike_point", "valid_data", "contact_laws"} <= set(td)
    assert set(td["segment_angles_deg"]) == {"trunk", "thigh", "shank", "foot"}
    assert set(data["settings"]) >= {"cutoff_hz", "force_threshold_n", "contact", "friction",
                                     "bounds_deg", "body", "markers"}
    assert data["optimum"]["success"] and data["per_step"]["converged"] >= 80
    assert len((tmp_path / "touchdowns.csv").read_text().splitlines()) == len(data["touchdowns"]) + 1
    trc = (tmp_path / "markers.trc").read_text().splitlines()
    assert trc[0].startswith("PathFileType\t4") and trc[2].split("\t")[2] == "4500"
    mot = (tmp_path / "angles.mot").read_text().splitlines()
    assert "endheader" in mot and mot[mot.index("endheader") + 1].startswith("time\tpelvis_tilt")
    assert main(["compare", "--trial", str(tmp_path / "none.c3d"), "--static", str(STATIC),
                 "--mass", "62", "--height", "1.81"]) == 2
    assert "no such file" in capsys.readouterr().err


def test_scene_file_gives_one_table_across_trials(tmp_path, capsys):
    scene = tmp_path / "runners.toml"
    scene.write_text(f'[compare]\nmass = 62\nheight = 1.81\nstatic = "{STATIC}"\nper_step = false\n'
                     f'bounds = {{ knee = [0, 90] }}\n[[trial]]\ntrial = "{RUN35}"\n'
                     f'[[trial]]\ntrial = "{RUN25}"\nforces = "{FORCES25}"\n')
    assert main(["compare", "--scene", str(scene), "--out", str(tmp_path / "out"), "--starts", "1"]) == 0
    rows = (tmp_path / "out" / "trials.csv").read_text().splitlines()
    assert len(rows) == 1 + 4 and "RBDS001runT25markers.txt" in rows[-1]
    bad = tmp_path / "bad.toml"
    bad.write_text('[compare]\nmas = 62\n')
    assert main(["compare", "--scene", str(bad)]) == 2
    assert "unknown key 'mas'" in capsys.readouterr().err


def test_plugin_gait_map_on_a_relabelled_run(measured, static):
    """RBDS001 T35 relabelled as Plug-in Gait (one wand marker per segment; KNE and ANK at the
    knee and ankle centres, TOE at MT1): recognised, and the hip and knee of formopt's own map
    again; the ankle differs by the foot line (heel to MT1, not to the MT midpoint)."""
    m = measured[3.5]
    names = {"ASI": "ASIS", "PSI": "PSIS", "THI": "Thigh.Top.Lateral", "TIB": "Shank.Top.Lateral",
             "HEE": "Heel.Bottom", "TOE": "MT1"}

    def relabel(markers, knee, ankle):
        out = {}
        for s in "RL":
            out.update({s + k: markers[f"{s}.{v}"] for k, v in names.items()})
            out[s + "KNE"], out[s + "ANK"] = knee(s), ankle(s)
        return out
    sm = static.markers
    pig_static = mocap.Trial(relabel(sm, lambda s: (sm[f"{s}.Knee"] + sm[f"{s}.Knee.Medial"]) / 2,
                                     lambda s: (sm[f"{s}.Ankle"] + sm[f"{s}.Ankle.Medial"]) / 2),
                             static.rate, source="pig_static")
    km = m.kinematics.markers
    pig_run = mocap.Trial(relabel(m.trial.markers, lambda s: km[f"{s}.knee"], lambda s: km[f"{s}.ankle"]),
                          m.trial.rate, m.trial.force, m.trial.force_rate, source="pig_run")
    pig = mocap.measure(pig_run, pig_static, HEIGHT)
    assert pig.calibration.markerset.name == "plugin_gait" and len(pig.steps.valid) == len(m.steps.valid)

    def mean(mm):
        return np.degrees([[td.angles[k] for k in ("hip", "knee", "ankle")]
                           for td in mm.steps.valid if td.side == "R"]).mean(axis=0)
    assert np.abs(mean(pig) - mean(m))[:2] == pytest.approx([0, 0], abs=0.5)
    assert abs(mean(pig)[2] - mean(m)[2]) < 4.0
