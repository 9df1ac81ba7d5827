"""The joint-angle convention (design.md section 2), once in mechanics.model: segment angles
from joint angles and back, checked against the model's own landmark positions."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from formopt.mechanics.body import paper_body
from formopt.mechanics.model import STATE, joint_angles, positions, segment_angles

JOINTS = {"trunk": (-0.4, 1.2), "hip": (-0.5, 2.0), "knee": (0.0, 2.3), "ankle": (-0.8, 0.3)}


def from_down(v) -> float:
    """Angle of a vector from the downward vertical, positive when it points forward (rad)."""
    return math.atan2(v[0], -v[1])


def same_angle(a, b) -> bool:
    """a and b equal up to whole turns (atan2 wraps to (-pi, pi])."""
    return abs(math.remainder(a - b, 2 * math.pi)) < 1e-9


@settings(max_examples=50, deadline=None, derandomize=True)
@given(st.fixed_dictionaries({k: st.floats(*r) for k, r in JOINTS.items()}))
def test_segment_angles_match_the_model_and_invert(joints):
    seg = segment_angles(joints)
    assert joint_angles(seg) == pytest.approx(joints, abs=1e-12)
    x = np.zeros(len(STATE))
    for k in JOINTS:
        x[STATE.index(k)] = joints[k]
    p = positions(x, paper_body())
    assert same_angle(from_down(p["knee"] - p["hip"]), seg["thigh"])
    assert same_angle(from_down(p["ankle"] - p["knee"]), seg["shank"])
    sole = p["forefoot"] - p["heel"]  # the foot frame's x axis lies along heel -> forefoot
    local = np.subtract(*(paper_body()["foot"].landmarks[k] for k in ("forefoot", "heel")))
    foot = math.atan2(sole[1], sole[0]) - math.atan2(local[1], local[0])
    assert same_angle(foot, seg["foot"])


def test_the_ankle_is_zero_with_the_foot_perpendicular_to_the_shank():
    seg = segment_angles({"trunk": 0.0, "hip": 0.3, "knee": 0.3, "ankle": 0.0})
    assert seg["shank"] == 0.0 and seg["foot"] == 0.0  # shank vertical, foot level
    assert joint_angles({"shank": 0.2, "foot": -0.1}) == {"ankle": pytest.approx(-0.3)}
