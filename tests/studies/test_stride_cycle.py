"""studies.stride's comparison with a measured mean cycle: the angles' RMS, their offset and
the offset-removed RMS, on a synthetic half stride whose whole cycle is known in closed form."""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from formopt.studies.stride import CYCLE_JOINTS, compare_cycle, cycle_angles, measured_cycle

RBDS = Path(__file__).resolve().parents[2] / "data" / "rbds" / "RBDS001processed.txt"
OFFSET = {"hip": -15.0, "knee": 4.0, "ankle": 10.0}  # deg


def half_stride(nodes: int = 41) -> SimpleNamespace:
    """A half stride of T = 0.35 s whose right leg's angles over the whole cycle p (%) are
    a_j(p) = A_j sin(2 pi p / 100) (deg): R over the first half, L (the R of the second) after."""
    T = 0.35
    t = np.linspace(0.0, T, nodes)
    theta = np.zeros((nodes, 9))
    for k, amplitude in enumerate((30.0, 40.0, 20.0)):
        theta[:, 3 + k] = np.radians(amplitude * np.sin(np.pi * t / T))
        theta[:, 6 + k] = -theta[:, 3 + k]
    return SimpleNamespace(t=t, half_period_s=T, mass_kg=62.0, theta=theta, thetad=np.zeros((nodes, 9)),
                           tau=np.zeros((nodes, 6)), tau_spring=None, force=np.zeros((nodes, 2, 2)),
                           duty_factor=0.35)


def test_the_offset_and_the_shape_split_the_rms():
    stride = half_stride()
    percent = np.linspace(0.0, 100.0, 101)
    truth = cycle_angles(stride, percent)
    shape = {"hip": 3.0 * np.cos(2 * np.pi * percent / 100), "knee": np.zeros(101), "ankle": np.zeros(101)}
    measured = {"percent": percent, "vertical": np.zeros(101),
                "angles": {j: truth[j] - OFFSET[j] - shape[j] for j in CYCLE_JOINTS}}
    c = compare_cycle(stride, measured)
    for j in CYCLE_JOINTS:
        assert c["angle_offset_deg"][j] == pytest.approx(OFFSET[j] + np.mean(shape[j]), abs=1e-9)
        assert c["angle_rms_deg"][j] ** 2 == pytest.approx(c["angle_offset_deg"][j] ** 2
                                                           + c["angle_rms_shape_deg"][j] ** 2)
    assert c["angle_rms_shape_deg"]["knee"] == pytest.approx(0.0, abs=1e-9)
    assert c["angle_rms_shape_deg"]["hip"] == pytest.approx(np.std(shape["hip"]))


def test_the_cycle_is_the_right_leg_then_the_left():
    stride = half_stride()
    stride.theta[:, 2] = np.radians(8.0)  # the trunk leaning forward
    angles = cycle_angles(stride, np.array([25.0, 50.0, 75.0]))
    assert angles["knee"] == pytest.approx([40.0, 0.0, -40.0], abs=0.05)  # sin at 25 / 50 / 75 % (41 nodes)
    assert angles["thigh"] == pytest.approx(angles["hip"] - 8.0)  # thigh = hip - trunk


def test_the_measured_cycle_starts_at_right_touchdown():
    """RBDS001's mean cycle: row 0 is the right foot's touchdown (the vertical force rising
    from zero), its stance about 35 % of the cycle at 3.5 m/s, knee flexion positive (its
    swing peak near 100 deg) and ankle dorsiflexion positive (its peak in midstance)."""
    m = measured_cycle(RBDS, 3.5)
    vertical = m["vertical"]
    assert vertical[0] < 1.0 < vertical[2] and vertical[-2] < 0.5
    assert np.mean(vertical[:-1] > 0.5) == pytest.approx(0.35, abs=0.01)
    assert 60 < np.argmax(m["angles"]["knee"]) < 75 and np.max(m["angles"]["knee"]) > 90
    assert 10 < np.argmax(m["angles"]["ankle"]) < 30
