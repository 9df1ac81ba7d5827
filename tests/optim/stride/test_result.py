"""optim.stride.result: one rank of strides (valid, converged, cost) and a stride's validity from
its checks' stated tolerances."""

from types import SimpleNamespace

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
    s.checks, s.impacts, s.success = checks, list(impacts), success
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
