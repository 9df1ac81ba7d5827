"""Numerically sound at the extremes: property-based tests and the documented limits.

Every public result is finite and the invariants hold, or the call raises a ValueError that
says why. The tolerance of each invariant grows with the condition number of
Phi_q M^-1 Phi_q^T (the rounding the projection can amplify).
"""

import math

import numpy as np
import pytest
from helpers import touchdown
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from formopt import Impact
from formopt.mechanics.body import Body, bar, foot, paper_body, trunk
from formopt.mechanics.impact import CONDITION_LIMIT
from formopt.mechanics.model import build_model

EPS = np.finfo(float).eps
SETTINGS = settings(max_examples=60, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def body_with(ratio_trunk=1.0, ratio_foot=1.0, thigh_length=0.402, shank_length=0.4315):
    """The paper body with segment masses scaled and segment lengths set."""
    base = paper_body()
    thigh, shank = base["thigh"], base["shank"]
    return Body({
        "trunk": trunk(58.5 * ratio_trunk),
        "thigh": bar("thigh", thigh.mass, thigh_length, 0.408 * thigh_length,
                     thigh.mass * (0.329 * thigh_length) ** 2),
        "shank": bar("shank", shank.mass, shank_length, 0.446 * shank_length,
                     shank.mass * (0.255 * shank_length) ** 2),
        "foot": foot(1.0 * ratio_foot, (0.06, -0.045), 0.0042 * ratio_foot, (-0.055, -0.07), (0.16, -0.07)),
    }, "extreme")


def check(result):
    """Finite outputs and the invariants, to a tolerance set by the conditioning."""
    values = [result.T, result.T_c, result.T_a, *result.impulse_total, *result.dv_com,
              *result.qd_plus, result.condition]
    values += [v for v in (result.mu_c, result.mu_c_momentum) if v is not None]
    assert np.all(np.isfinite(values))
    tol = 1e3 * EPS * result.condition * max(result.T, 1e-300)
    assert result.T_c >= -tol
    assert abs(result.T_c + result.T_a - result.T) <= tol + 1e-300
    assert result.T_a <= result.T + tol


angles = st.tuples(st.floats(-30, 60), st.floats(-30, 120), st.floats(0, 135), st.floats(-50, 30))
velocities = st.tuples(st.floats(-15, 15), st.floats(-15, 5))
rates = st.tuples(*[st.floats(-1500, 1500)] * 3)


@SETTINGS
@given(angles=angles, v=velocities, w=rates, strike=st.sampled_from(["heel", "forefoot"]),
       slope=st.floats(-30, 30))
def test_any_touchdown_gives_finite_indicators_or_a_clear_error(leg, angles, v, w, strike, slope):
    x = touchdown(*angles, v=v, w=(0.0, *w))
    try:
        result = Impact(leg, strike, math.radians(slope), 0.8)(x)
    except ValueError as err:
        assert "singular" in str(err)
        return
    check(result)


@SETTINGS
@given(trunk_ratio=st.floats(1e-4, 1e4), foot_ratio=st.floats(1e-4, 1e4),
       thigh=st.floats(0.01, 3.0), shank=st.floats(0.01, 3.0), strike=st.sampled_from(["heel", "forefoot"]))
def test_any_body_gives_finite_indicators_or_a_clear_error(trunk_ratio, foot_ratio, thigh, shank, strike):
    model = build_model(body_with(trunk_ratio, foot_ratio, thigh, shank))
    try:
        result = Impact(model, strike, 0.0, 0.8)(touchdown())
    except ValueError as err:
        assert "singular" in str(err)
        return
    check(result)
    assert result.condition < CONDITION_LIMIT


# -- the documented extremes --------------------------------------------------------------

def test_fully_extended_knee_is_regular(leg):
    """Natural coordinates have no singularity at a straight knee: exact as anywhere else."""
    r = Impact(leg, "forefoot", 0.0, 0.8)(touchdown(knee=0.0, ankle=-20.0))
    check(r)
    assert r.condition < 1e3


def test_foot_perpendicular_to_the_ground(leg):
    """Foot angle -90 deg (toe straight down): a forefoot strike is still a regular impact."""
    shank = 22.0 - 0.0 - 18.0
    r = Impact(leg, "forefoot", 0.0, 0.8)(touchdown(ankle=-90.0 - shank))
    check(r)


@pytest.mark.parametrize("speed", [0.0, 1e-9, 1e-3, 15.0])
def test_touchdown_speeds_from_zero_to_15(leg, speed):
    x = touchdown(v=(speed, -0.2 * speed), w=(0.0, 0.0, 0.0, 0.0))
    r = Impact(leg, "forefoot", 0.0, 0.8)(x)
    check(r)
    assert r.T_c <= r.T
    if speed == 0.0:  # no motion: nothing absorbed, no impulse, mu_c undefined (said so)
        assert r.T == 0.0 and r.T_c == 0.0 and r.mu_c is None
        assert any("undefined" in w for w in r.warnings)


def test_impact_scales_with_the_square_of_speed(leg):
    """T_c is a quadratic form of the velocities: T_c(k v) = k^2 T_c(v)."""
    x = touchdown()
    small = x.copy()
    small[4:] *= 1e-6
    a, b = Impact(leg, "forefoot", 0.0, 0.8)(x), Impact(leg, "forefoot", 0.0, 0.8)(small)
    assert b.T_c == pytest.approx(a.T_c * 1e-12, rel=1e-8)


@pytest.mark.parametrize("ratio", [1e-4, 1e4])
def test_mass_ratios(ratio):
    for r in (Impact(build_model(body_with(ratio_trunk=ratio)), "forefoot", 0.0, 0.8)(touchdown()),
              Impact(build_model(body_with(ratio_foot=ratio)), "forefoot", 0.0, 0.8)(touchdown())):
        check(r)


def test_a_heavy_trunk_tends_to_a_fixed_hip(leg):
    """As the trunk's mass grows the hip stops moving in the impact: dv_trunk -> 0."""
    heavy = Impact(build_model(body_with(ratio_trunk=1e4)), "forefoot", 0.0, 0.8)(touchdown())
    normal = Impact(leg, "forefoot", 0.0, 0.8)(touchdown())
    assert np.hypot(*heavy.dv_trunk) < 1e-3 * np.hypot(*normal.dv_trunk)


@pytest.mark.parametrize("length", [0.01, 3.0])
def test_very_short_and_very_long_segments(length):
    r = Impact(build_model(body_with(thigh_length=length, shank_length=length)), "forefoot", 0.0, 0.8)(
        touchdown(ankle=-40.0))
    check(r)


@pytest.mark.parametrize("friction,valid", [(1e-9, False), (1e9, True)])
def test_friction_near_zero_and_very_large(leg, friction, valid):
    x = touchdown(v=(3.5, -0.7), w=(0.0, -100.0, -400.0, -300.0), hip=30.0, knee=20.0, ankle=-15.0)
    r = Impact(leg, "forefoot", 0.0, friction=friction)(x)
    check(r)
    assert r.valid is valid


@pytest.mark.parametrize("slope", [-30.0, 30.0])
def test_steep_slopes(leg, slope):
    r = Impact(leg, "heel", math.radians(slope), 0.8)(touchdown(ankle=10.0))
    check(r)


def test_strike_point_that_cannot_reach_the_ground(leg):
    """A heel strike with the forefoot below the ground: the impact is computed, flagged invalid."""
    r = Impact(leg, "heel", 0.0, 0.8)(touchdown(ankle=-30.0))
    assert not r.valid and any("below the ground" in w for w in r.warnings)


def test_a_segment_without_inertia_is_a_point_mass_on_its_line():
    """Zero inertia about the centre of mass: the shank's own block is singular, but knee and
    ankle carry the thigh's and the foot's mass, so M stays positive definite: exact."""
    segments = dict(body_with().segments)
    segments["shank"] = bar("shank", 3.2, 0.43, 0.19, 0.0)
    check(Impact(build_model(Body(segments, "point-mass shank")), "forefoot", 0.0, 0.8)(touchdown()))


def test_a_massless_foot_is_refused():
    """Heel and forefoot carry no mass at all: M is singular, refused when the model is built."""
    segments = dict(body_with().segments)
    segments["foot"] = foot(0.0, (0.06, -0.045), 0.0, (-0.055, -0.07), (0.16, -0.07))
    with pytest.raises(ValueError, match="singular"):
        build_model(Body(segments, "massless foot"))


def test_nonfinite_state_is_refused(leg):
    x = touchdown()
    x[2] = np.nan
    with pytest.raises(ValueError, match="touchdown knee = nan rad is outside"):
        Impact(leg, "forefoot", 0.0, 0.8)(x)
