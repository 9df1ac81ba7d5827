"""Touchdown rules: the force threshold on a synthetic force with known contacts, the foot-speed
rule against the force plate on RBDS001 T25 (which has forces), the strike pattern's
thresholds (Altman & Davis 2012)."""

import copy
import math

import numpy as np
import pytest
from trials import HEIGHT

from formopt.measure import measure
from formopt.measure.touchdowns import (
    FLAT_S,
    FOREFOOT_DEG,
    LEVEL_M,
    REARFOOT_DEG,
    contact_order,
    foot_speed_touchdowns,
    force_plate_touchdowns,
    strike_pattern,
)

UP = np.array([0.0, 1.0, 0.0])


def test_strike_patterns_from_the_foot_strike_angle():
    assert strike_pattern(math.radians(REARFOOT_DEG + 0.1)) == "heel"
    assert strike_pattern(math.radians(REARFOOT_DEG - 0.1)) == "midfoot"
    assert strike_pattern(math.radians(FOREFOOT_DEG + 0.1)) == "midfoot"
    assert strike_pattern(math.radians(FOREFOOT_DEG - 0.1)) == "forefoot"


def test_force_threshold_on_contacts_of_known_onset():
    """Half-sine stances of 1500 N, 0.25 s long, every 0.35 s, with 20 N noise: each onset
    found within 2 ms of where the noise-free force crosses 50 N, once per contact."""
    rate, onsets = 1000.0, np.arange(0.2, 5.0, 0.35)
    t = np.arange(int(5.5 * rate)) / rate
    fz = np.zeros_like(t)
    for t0 in onsets:
        inside = (t >= t0) & (t < t0 + 0.25)
        fz[inside] = 1500 * np.sin(np.pi * (t[inside] - t0) / 0.25)
    fz += np.random.default_rng(1).normal(scale=20.0, size=len(t))
    force = np.column_stack([0.05 * fz, fz, np.zeros_like(t)])  # Y up, a little fore-aft force
    crossing = onsets + 0.25 / np.pi * math.asin(50.0 / 1500.0)
    found = force_plate_touchdowns(force, rate, UP, 50.0)
    assert len(found) == len(onsets) and found == pytest.approx(crossing, abs=0.002)


def test_foot_speed_rule_on_a_foot_of_known_stance():
    """A foot that moves back with a 3 m/s belt in stance (0.2 s) and swings forward between:
    its speed over the ground falls below half the running speed at each stance's start."""
    rate, speed, stances = 150.0, 3.0, np.arange(0.3, 4.0, 0.7)
    t = np.arange(int(4.5 * rate)) / rate
    v = np.zeros((len(t), 2))
    v[:, 0] = 2 * speed  # swing: ahead of the hip, over the ground 3 m/s + belt
    for t0 in stances:
        v[(t >= t0) & (t < t0 + 0.2), 0] = -speed  # stance: carried back by the belt
    found = foot_speed_touchdowns(v, rate, belt=speed, speed=speed, fraction=0.5)
    assert found == pytest.approx(np.ceil(stances * rate - 1e-9) / rate, abs=1 / rate)


def test_foot_speed_touchdowns_agree_with_the_force_plate(run25, static, measured):
    """RBDS001 T25 without its force file: the foot's speed over the ground (half the running
    speed) gives the force plate's touchdowns to a frame or two (6.7 ms a frame)."""
    trial = copy.copy(run25)
    trial.force, trial.force_rate = None, None
    kinematic = measure(trial, static, HEIGHT).steps
    assert kinematic.method == "kinematics"
    force_times = np.array([td.time for td in measured[2.5].steps.touchdowns])
    gaps = [td.time - force_times[np.argmin(np.abs(force_times - td.time))] for td in kinematic.touchdowns]
    assert abs(np.median(gaps)) < 0.005 and np.percentile(np.abs(gaps), 90) < 0.015
    assert kinematic.cadence_spm == pytest.approx(measured[2.5].steps.cadence_spm, rel=0.02)
    assert [td.side for td in kinematic.touchdowns[:10]] == \
        [measured[2.5].steps.touchdowns[np.argmin(np.abs(force_times - td.time))].side
         for td in kinematic.touchdowns[:10]]


def _landing(down: int, frames: int = 80, level: float = 0.02, speed: float = 0.004):
    """A point's height (m) falling `speed` m per frame until frame `down`, then at `level`."""
    k = np.arange(frames)
    return level + speed * np.clip(down - k, 0, None)


@pytest.mark.parametrize("heel_down, fore_down, order", [
    (20, 26, "heel"),     # 30 ms apart at 200 Hz: heel first
    (26, 20, "forefoot"),
    (20, 21, "flat"),     # 5 ms apart: within FLAT_S
])
def test_contact_order_from_each_point_reaching_its_own_stance_level(heel_down, fore_down, order):
    rate = 200.0
    # different stance levels (the heel marker sits lower on the shoe than the metatarsals')
    heel, fore = _landing(heel_down, level=0.015), _landing(fore_down, level=0.045)
    found, (t_heel, t_fore) = contact_order(heel, fore, 18, rate)
    assert found == order
    # each reach time: the frame where the point is LEVEL_M above its level (independent count)
    for t, down in ((t_heel, heel_down), (t_fore, fore_down)):
        assert t == pytest.approx((down - math.floor(LEVEL_M / 0.004) - 18) / rate)
    assert (abs(t_heel - t_fore) <= FLAT_S) == (order == "flat")


def test_the_forefoot_reaches_its_level_with_the_first_of_its_markers():
    """A forefoot landing on its lateral edge: the lateral metatarsal down 25 ms before the
    heel, the medial one 15 ms after it; their mean would come down with the heel (flat); the
    first marker makes it a forefoot contact."""
    rate = 200.0
    heel = _landing(26, level=0.015)
    lateral, medial = _landing(21, level=0.03), _landing(29, level=0.05)
    assert contact_order(heel, [lateral, medial], 18, rate)[0] == "forefoot"
    assert contact_order(heel, (lateral + medial) / 2, 18, rate)[0] == "flat"


def test_the_contact_order_of_rbds001_agrees_with_the_plate(measured):
    """RBDS001 lands forefoot first (the data set's own strike index; the plate's centre of
    pressure over the first 20 ms at 0.75-0.95 of the heel-forefoot line): the markers' contact
    order agrees in at least 9 of 10 steps and never says heel."""
    for m in measured.values():
        tds = m.steps.touchdowns
        assert all(td.cop_index is not None and 0.67 < td.cop_index < 1.1 for td in tds)
        orders = [td.contact_order for td in tds]
        assert orders.count("forefoot") >= 0.9 * len(tds) and "heel" not in orders


def test_a_step_whose_foot_angle_jumps_is_left_out_with_its_reason():
    """A heel striker's foot cluster that slips for one step: its foot strike angle reads -17
    deg among steps of 17 +- 1 deg (the rigidity test passes it); only that step is left out."""
    from formopt.measure.touchdowns import Touchdown, _jumps
    rng = np.random.default_rng(1)
    steps = []
    for k in range(20):
        foot = math.radians(-17.0 if k == 9 else 17.0 + rng.normal(0, 1))
        segs = {"trunk": 0.0, "thigh": 0.35 + rng.normal(0, 0.01), "shank": 0.05, "foot": foot}
        steps.append(Touchdown(k * 0.35, "R" if k % 2 else "L", 10 * k, "heel", foot, segs, {},
                               {"thigh": -2.0, "shank": 2.0, "foot": 1.0}, (3.3, -0.6), 0.9, {}))
    out = _jumps(steps)
    bad = [k for k, td in enumerate(out) if not td.valid_data]
    assert bad == [9]
    assert "the foot angle -17 deg is -34 from its neighbours' 17" in out[9].problems[0]
