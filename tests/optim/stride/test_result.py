"""optim.stride.result: one rank of strides (valid, converged, cost) and a stride's validity from
its checks' stated tolerances."""

from types import SimpleNamespace

from formopt.optim.stride.checks import CROUCH_DEG, STIFF_LANDING_J
from formopt.optim.stride.problem import StrideSettings
from formopt.optim.stride.result import TOLERANCES, Stride, rank


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
