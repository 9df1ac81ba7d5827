"""Joint centres in RBDS001's standing trial: Harrington's hip regression applied by hand
(pelvis frame built another way, the centre read back in it), the calibrated points, and the
segment lengths against the stature."""

import copy
import math

import numpy as np
import pytest
from trials import HEIGHT, STATIC

from formopt.io import markerset
from formopt.io.mocap import MocapError
from formopt.measure.clean import clean
from formopt.measure.joints import LENGTH_PER_HEIGHT, calibrate, harrington_hip

UP = np.array([0.0, 1.0, 0.0])  # RBDS's lab Y (test_pipeline: the force's mean is along it)


@pytest.fixture(scope="module")
def ref(static):
    return clean(copy.deepcopy(static)).mean_positions()


def by_hand(ref, side):
    """Harrington et al. (2007) eq.: in the pelvis frame (origin mid-ASIS; z to the right ASIS,
    y up normal to the ASIS-PSIS plane, x = y cross z forward), mm:
    x = -0.24 PD - 9.9, y = -0.30 PW - 10.9, z = +-(0.33 PW + 7.3)."""
    r_asis, l_asis, r_psis, l_psis = (ref[n] * 1000 for n in ("R.ASIS", "L.ASIS", "R.PSIS", "L.PSIS"))
    origin = (r_asis + l_asis) / 2
    pw = np.linalg.norm(r_asis - l_asis)
    pd = np.linalg.norm(origin - (r_psis + l_psis) / 2)
    z = (r_asis - l_asis) / pw
    y = np.cross(z, origin - (r_psis + l_psis) / 2)
    y /= np.linalg.norm(y) * np.sign(y @ UP)
    x = np.cross(y, z)
    local = [-0.24 * pd - 9.9, -0.30 * pw - 10.9, (1 if side == "R" else -1) * (0.33 * pw + 7.3)]
    return (origin + np.column_stack([x, y, z]) @ local) / 1000, (x, y, z, origin, pw, pd)


@pytest.mark.parametrize("side", ["R", "L"])
def test_harrington_hip_is_the_regression_applied_by_hand(ref, side):
    ms = markerset.load("rbds")
    hip = harrington_hip(ref, ms, side, UP)
    expected, (x, y, z, origin, pw, pd) = by_hand(ref, side)
    assert hip == pytest.approx(expected, abs=1e-9)
    local = np.array([x, y, z]) @ (hip * 1000 - origin)  # read back in the pelvis frame, mm
    sign = 1 if side == "R" else -1
    assert local == pytest.approx([-0.24 * pd - 9.9, -0.30 * pw - 10.9, sign * (0.33 * pw + 7.3)], abs=1e-6)
    assert 200 < pw < 300 and 120 < pd < 200  # an adult pelvis (mm)


def test_calibrated_points_and_lengths(measured, ref):
    """The hips carried by the pelvis cluster are Harrington's; knee and ankle the midpoints of
    their landmarks; thigh and shank near Winter's fractions of the stature."""
    cal = measured[3.5].calibration
    for s in "RL":
        assert cal.points[f"{s}.hip"][2] == pytest.approx(harrington_hip(ref, cal.markerset, s, cal.axes.up), abs=1e-12)
        for joint in ("knee", "ankle"):
            lateral, medial = (ref[n] for n in cal.markerset.landmarks(s, joint))
            assert cal.points[f"{s}.{joint}"][2] == pytest.approx((lateral + medial) / 2)
        assert cal.points[f"{s}.hip"][0] == cal.markerset.pelvis
        for seg, per in LENGTH_PER_HEIGHT.items():
            assert cal.lengths[f"{s}.{seg}"] == pytest.approx(per * HEIGHT, rel=0.2)
        assert abs(math.degrees(cal.foot_offset[s])) < 15


def test_a_stature_the_legs_do_not_fit_is_refused(static, run35):
    ms = markerset.load("rbds")
    with pytest.raises(MocapError, match=f"{STATIC}: the right thigh is .* m long, not a 4 m runner's"):
        calibrate(clean(copy.deepcopy(static)), run35, ms, 4.0)
