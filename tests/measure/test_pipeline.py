"""The whole measurement on the real trials: RBDS subject 001 (two speeds, C3D and text) and
the Running Injury Clinic runner (clusters only, no units, no force plate)."""

import importlib.util
import itertools
import math

import numpy as np
import pytest
from helpers import PROBLEMS
from trials import HEIGHT, RIC_HEIGHT, RIC_RUN, RIC_STATIC

from formopt.io import mocap
from formopt.measure import measure


@pytest.fixture(scope="module")
def ric():
    return measure(mocap.read(RIC_RUN), mocap.read(RIC_STATIC), RIC_HEIGHT)


def test_lab_vertical_is_the_mean_force_and_the_mt_swap_is_undone(measured):
    """RBDS T35: up from the mean force (the lab's Y, not the standing feet's plane 4.8 deg
    off); R.MT1 and R.MT5 swapped in the run relative to the standing trial, swapped back."""
    for m in measured.values():
        axes = m.calibration.axes
        assert axes.up[1] > 0.9999 and axes.forward[0] > 0.9999 and not axes.mirrored
        assert any("R.MT1 and R.MT5 are swapped" in n for n in m.steps.notes)


def test_belt_speed_and_cadence(measured):
    """Belt and running speed near the nominal 2.5 and 3.5 m/s; cadence as the data set's own
    processing gives it (RBDS001processed.txt: 156.5 and 171.4 steps/min; design.md 6)."""
    for speed, m in measured.items():
        assert m.steps.belt_speed == pytest.approx(speed, abs=0.1)
        assert m.steps.speed == pytest.approx(speed, abs=0.12)
        sides = [td.side for td in m.steps.touchdowns]
        assert all(a != b for a, b in itertools.pairwise(sides)), "touchdowns alternate right, left"
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
    again = measure(text, static, HEIGHT).steps
    assert [td.time for td in again.touchdowns] == pytest.approx([td.time for td in measured[3.5].steps.touchdowns])


def test_the_trials_given_are_left_as_read(run35, static, measured):
    """measure works on copies: the trials as read keep their raw samples, the Measurement
    holds the cleaned run."""
    assert not run35.suspect and not static.suspect
    assert measured[3.5].trial is not run35 and measured[3.5].trial.rate == run35.rate


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
    pig = measure(pig_run, pig_static, HEIGHT)
    assert pig.calibration.markerset.name == "plugin_gait" and len(pig.steps.valid) == len(m.steps.valid)

    def mean(mm):
        return np.degrees([[td.angles[k] for k in ("hip", "knee", "ankle")]
                           for td in mm.steps.valid if td.side == "R"]).mean(axis=0)
    assert np.abs(mean(pig) - mean(m))[:2] == pytest.approx([0, 0], abs=0.5)
    assert abs(mean(pig)[2] - mean(m)[2]) < 4.0
