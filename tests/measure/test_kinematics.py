"""Cluster fits and segment angles: Kabsch against scipy's Rotation.align_vectors (an
independent least-squares rotation, Markley's method), its residual against align_vectors's
rssd, and the segment-angle convention (design.md section 2) on a drawn leg."""

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from formopt.measure.axes import Axes
from formopt.measure.kinematics import pitch, segment_angles
from formopt.measure.rigid import fit_residual, kabsch

rng = np.random.default_rng(22)


def cluster(k=4):
    """k markers (k, 3), m, spread about 5-10 cm like a segment's cluster."""
    return rng.normal(scale=0.06, size=(k, 3)) + [0.1, 0.9, 0.2]


def scipy_fit(reference, current):
    """R (3, 3), t (3,) and rms residual from align_vectors on the centred clusters."""
    a, b = current - current.mean(axis=0), reference - reference.mean(axis=0)
    rot, rssd = Rotation.align_vectors(a, b)
    R = rot.as_matrix()
    return R, current.mean(axis=0) - R @ reference.mean(axis=0), rssd / math.sqrt(len(reference))


@pytest.mark.parametrize("noise", [0.0, 0.002, 0.02])
def test_kabsch_agrees_with_align_vectors_frame_by_frame(noise):
    reference = cluster()
    truth = Rotation.random(50, random_state=5).as_matrix()
    current = np.einsum("fij,kj->fki", truth, reference) + rng.normal(size=(50, 1, 3))
    current += rng.normal(scale=noise, size=current.shape)
    R, t = kabsch(reference, current)
    residual = fit_residual(reference, current, R, t)
    for f in range(50):
        R_s, t_s, rms = scipy_fit(reference, current[f])
        assert R[f] == pytest.approx(R_s, abs=1e-9) and t[f] == pytest.approx(t_s, abs=1e-9)
        assert residual[f] == pytest.approx(rms, abs=1e-8)  # scipy's rssd: sqrt of a round-off
    if noise == 0.0:
        assert R == pytest.approx(truth, abs=1e-12) and residual == pytest.approx(0, abs=1e-12)


def test_a_mirrored_cluster_gets_the_best_rotation_not_a_reflection():
    """The best orthogonal fit of a mirror image is a reflection; Kabsch's sign correction
    gives the best rotation, as align_vectors does (a proper rotation always)."""
    reference = cluster(5)
    current = reference * [1.0, 1.0, -1.0]
    R, t = kabsch(reference, current)
    R_s, t_s, rms = scipy_fit(reference, current)
    assert np.linalg.det(R) == pytest.approx(1.0) and R == pytest.approx(R_s, abs=1e-9)
    assert t == pytest.approx(t_s, abs=1e-9)
    assert fit_residual(reference, current[None], R[None], t[None])[0] == pytest.approx(rms, abs=1e-8)


def test_segment_angles_of_a_drawn_leg():
    """Thigh 30 deg ahead of the downward vertical, shank 10 deg behind it, foot line 5 deg
    toe-up relative to standing (standing line at -3 deg)."""
    def at(angle, length):  # the distal point from the proximal, angle from the downward vertical
        return length * np.array([math.sin(angle), -math.cos(angle)])
    hip = np.array([0.0, 0.9])
    knee = hip + at(math.radians(30), 0.45)
    ankle = knee + at(math.radians(-10), 0.43)
    heel = ankle + [-0.05, -0.07]
    fore = heel + 0.18 * np.array([math.cos(math.radians(2)), math.sin(math.radians(2))])
    points = {f"{s}.{k}": np.array([p]) for s in "RL" for k, p in
              zip(("hip", "knee", "ankle", "heel", "forefoot"), (hip, knee, ankle, heel, fore))}
    angles = segment_angles(points, {"R": math.radians(-3), "L": math.radians(-3)})
    for s in "RL":
        assert np.degrees([angles[f"{s}.thigh"][0], angles[f"{s}.shank"][0], angles[f"{s}.foot"][0]]) == \
            pytest.approx([30.0, -10.0, 5.0])


def test_pitch_is_the_forward_tilt_nose_down_positive():
    forward, up = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    axes = Axes(forward, np.cross(up, forward), up)  # left = up x forward, as find_axes
    tilt = np.radians([-20.0, 0.0, 15.0])
    R = Rotation.from_rotvec(np.outer(tilt, axes.left)).as_matrix()  # about left: forward turns down
    assert pitch(R, axes) == pytest.approx(tilt)
