"""optim.stride.result: one rank of strides (valid, converged, cost) and a stride's validity from
its checks' stated tolerances."""

from types import SimpleNamespace

import numpy as np
import pytest

from formopt.optim.stride.checks import CROUCH_DEG, STIFF_LANDING_J
from formopt.optim.stride.problem import StrideSettings
from formopt.optim.stride.result import RESERVE_WINDOW_S, TOLERANCES, Stride, rank, reserve_mean


def _stride(valid, success, objective):
    return SimpleNamespace(valid=valid, success=success, objective_value=objective)


def test_valid_before_invalid_converged_before_not_then_the_cost():
    cheap_invalid = _stride(False, True, 0.1)
    dear_valid = _stride(True, True, 0.9)
    failed = _stride(False, False, 0.01)
    cheap_valid = _stride(True, True, 0.5)
    ordered = sorted([cheap_invalid, dear_valid, failed, cheap_valid], key=rank)
    assert ordered == [cheap_valid, dear_valid, cheap_invalid, failed]


def _checked(checks, impacts=(), success=True):
    """A Stride's validity from its checks alone (the other fields are not read)."""
    s = Stride.__new__(Stride)
    s.checks, s.impacts, s.success, s.held, s.budget = checks, list(impacts), success, [], {}
    return s


def test_a_check_beyond_its_tolerance_makes_a_stride_invalid():
    good = {k: 0.5 * v for k, v in TOLERANCES.items()}
    assert _checked(good).valid and not _checked(good).failed_checks
    for key, limit in TOLERANCES.items():
        bad = _checked({**good, key: 2 * limit})
        assert not bad.valid and bad.failed_checks[0].startswith(key)
    assert not _checked({**good, "drift_m": float("nan")}).valid  # a NaN is no pass
    assert not _checked(good, success=False).valid


def test_an_invalid_impact_is_named():
    impact = {"point": "heel", "leg": "L", "law": "no-slip", "valid": False, "mu_c": 0.93,
              "approach_mps": -1.2}
    s = _checked({}, [impact])
    assert not s.valid and "heel impact of leg L invalid under no-slip (mu_c 0.93" in s.failed_checks[0]


def test_the_default_duration_bounds_hold_a_runners_phases():
    """RBDS001 at 3.5 m/s (heel 0.03 s, flat 0.12, forefoot 0.09, flight 0.11: problem.py) lies
    inside every default bound, not on one."""
    bounds = StrideSettings().duration
    runner = {"heel": 0.03, "flat": 0.12, "forefoot": 0.09, "flight": 0.11}
    assert all(bounds[p][0] < d < bounds[p][1] for p, d in runner.items())


def test_a_sticking_impact_on_the_cone_edge_is_valid_and_remarked():
    edge = {"point": "heel", "leg": "L", "law": "no-slip", "valid": True, "mu_c": 0.8000002,
            "on_cone_edge": True, "mode": "stick"}
    inside = {**edge, "point": "forefoot", "mu_c": 0.4, "on_cone_edge": False}
    s = _checked({}, [edge, inside])
    s.on_bound, s.friction = [], 0.8
    assert s.valid and len(s.remarks) == 1 and "heel impact of leg L on the friction cone's edge" in s.remarks[0]


def test_a_sliding_touchdown_says_how_far_it_slid():
    slide = {"point": "forefoot", "leg": "L", "law": "coulomb", "valid": True, "mu_c": 0.8,
             "on_cone_edge": False, "mode": "slide", "slide_s": 0.045, "slide_m": -0.18}
    s = _checked({}, [slide])
    s.on_bound, s.friction = [], 0.8
    assert s.remarks == ["forefoot impact of leg L solved sliding under coulomb: it slides 45 ms and 18.0 cm"]


def test_a_crouched_stance_is_remarked():
    """Beyond CROUCH_DEG (a runner's stance knee at its deepest, 37-44 deg, half again) the stride
    says it is crouched; a runner's knee, or none computed (NaN), says nothing."""
    s = _checked({})
    s.on_bound, s.friction = [], 0.8
    assert s.remarks == []  # NaN: not computed
    s.stance_knee_deg = 44.0
    assert s.remarks == []
    s.stance_knee_deg = CROUCH_DEG + 25.0
    assert s.remarks == [f"a crouched stance: the stance knee flexes to {CROUCH_DEG + 25:.0f} deg, far beyond a "
                         "runner's 37-44 deg at 2.5-4.5 m/s (RBDS001 and RIC's runner)"]
    assert s.valid  # a remark, not a check: the model's stride, not a runner's


def test_a_stiff_landing_is_remarked():
    """Impacts beyond STIFF_LANDING_J a step (a runner's touchdown absorbs 0.5-5 J) are said; the
    torque scenes' heel and forefoot strides' 1.2-5.4 J are not."""
    s = _checked({})
    s.on_bound, s.friction = [], 0.8
    s.budget = {"impacts_J": 5.5}
    assert s.remarks == []
    s.budget = {"impacts_J": STIFF_LANDING_J + 18.1}
    assert s.remarks == ["a stiff landing: the impacts take 28 J a step, where a runner's touchdown absorbs "
                         "0.5-5 J (formopt compare on RBDS001 and RIC's runner, Coulomb or no-slip)"] and s.valid


def test_the_reserves_mean_over_their_window():
    """reserve_mean: |r| averaged over RESERVE_WINDOW_S, the worst window of the periodic stride
    (the next half stride the legs swapped), so a one-node spike counts by its impulse."""
    t = np.linspace(0.0, 0.3, 301)  # 1 ms intervals, a half period of 0.3 s
    r = np.zeros((6, t.size))
    r[1] = 0.04  # the right knee's constant reserve: its mean is itself
    assert reserve_mean(t, r) == pytest.approx(0.04)
    r[1], r[2, 150] = 0.0, 1.0  # one node's spike: a triangle of area 1 ms * 1 N m/kg
    assert reserve_mean(t, r) == pytest.approx(1e-3 / RESERVE_WINDOW_S)
    r[2, 150], r[1, -1], r[4, 0] = 0.0, 1.0, 1.0  # the right knee at the end, the left at the start:
    assert reserve_mean(t, r) == pytest.approx(1e-3 / RESERVE_WINDOW_S)  # one burst across the touchdown
    assert reserve_mean(t, -r) == reserve_mean(t, r)  # |r|


def test_the_reserves_mean_reads_them_linear_between_the_nodes():
    """reserve_mean against a brute-force moving mean of |r| linear between the nodes (a lone
    spike at W = h reads 0.75 of its height), with a phase boundary's time twice, and a window
    longer than the half period refused."""
    t = np.linspace(0.0, 0.1, 11)  # 10 ms intervals
    r = np.zeros((6, t.size))
    r[2, 5] = 1.0
    assert reserve_mean(t, r, 0.01) == pytest.approx(0.75)
    t = np.r_[np.linspace(0.0, 0.04, 5), np.linspace(0.04, 0.1, 7)]  # a phase boundary at 40 ms: twice
    r = np.random.default_rng(0).normal(size=(6, t.size))  # two values there
    times, rows = np.concatenate([t, t + t[-1]]), np.abs(np.hstack([r, r[[3, 4, 5, 0, 1, 2]]]))
    fine = np.linspace(0.0, times[-1], 200001)
    k = np.clip(np.searchsorted(times, fine, side="right") - 1, 0, times.size - 2)
    h = np.diff(times)[k]
    s = np.divide(fine - times[k], h, out=np.zeros_like(fine), where=h > 0)
    linear = rows[:, k] * (1 - s) + rows[:, k + 1] * s  # |r| on a 1 us grid
    window = 0.013
    step = fine[1] - fine[0]
    area = np.concatenate([np.zeros((6, 1)), np.cumsum(0.5 * (linear[:, 1:] + linear[:, :-1]) * step, axis=1)], axis=1)
    n = round(window / step)
    brute = ((area[:, n:] - area[:, :-n]) / window)[:, :fine.size // 2].max()
    assert reserve_mean(t, r, window) == pytest.approx(brute, rel=1e-4)
    with pytest.raises(ValueError, match=r"window 0\.2 s outside"):
        reserve_mean(t, r, 0.2)
