"""The validation vocabulary (io/validate.py) and the limits it checks against: one-line errors
that name the file, the key, the value and the allowed range, for scenes, marker maps and
compare scenes alike."""

import math

import pytest

from formopt.io import markerset
from formopt.io import validate as val
from formopt.mechanics import limits

RBDS_MAP = markerset.SHIPPED / "rbds.toml"


def refused(call, *args, **kwargs) -> val.ValidationError:
    with pytest.raises(val.ValidationError) as err:
        call(*args, **kwargs)
    assert "\n" not in str(err.value)
    return err.value


def test_an_unknown_key_names_where_and_the_closest_spelling():
    err = refused(val.keys, {"frction": 0.8}, "ground", {"friction", "slope_deg"})
    assert err.key == "ground.frction" and "did you mean 'friction'" in str(err)
    err = refused(val.keys, {"zzz": 1}, "ground", {"friction", "slope_deg"})
    assert "expected one of: friction, slope_deg" in str(err)
    assert refused(val.keys, {}, "ground", {"friction"}, ("friction",)).reason == "missing"


@pytest.mark.parametrize("value,needle", [
    (float("nan"), "must be finite"), (10**400, "finite"), ("0.8", "must be a number, not str"),
    (True, "must be a number"), (0.0, "must be > 0 and <= 100, not 0"), (101.0, "<= 100, not 101"),
])
def test_a_number_outside_its_limit_names_value_and_range(value, needle):
    err = refused(val.number, {"friction": value}, "friction", "ground", limit=limits.FRICTION)
    assert err.key == "ground.friction" and needle in str(err)


def test_ranges_in_words_and_in_another_unit():
    assert limits.SLOPE_DEG.text() == "between -60 and 60 deg"
    assert limits.Range(0.0, low_open=True).text() == "> 0"
    assert limits.RATE_DPS.high == pytest.approx(math.degrees(limits.RATE_LIMIT))
    assert 0.0 not in limits.FRICTION and 0.8 in limits.FRICTION


def test_joint_bounds_lie_within_the_range_of_motion():
    assert val.joint_bounds([0, 60], "bounds.knee", "knee") == (0.0, 60.0)
    for bad, needle in (([0, 200], "knee's range of motion"), ([40, 10], "lo < hi"),
                        ([0], "[lo, hi]"), ("knee", "[lo, hi]"), (["a", "b"], "must be a number")):
        assert needle in str(refused(val.joint_bounds, bad, "bounds.knee", "knee"))


def test_labels_of_a_cluster_are_different_markers():
    assert val.labels({"c": ["a", "b", "c"]}, "c", "leg", 3, True) == ("a", "b", "c")
    assert "more than once" in str(refused(val.labels, {"c": ["a", "a", "a"]}, "c", "leg", 3, True))
    assert "at least 3" in str(refused(val.labels, {"c": ["a", "b"]}, "c", "leg", 3))
    assert "list of labels" in str(refused(val.labels, {"c": 42}, "c", "leg"))


@pytest.mark.parametrize("content,needle", [
    ("x = 1\n".encode("utf-16"), "not UTF-8"),
    (bytes(range(256)) * 8, "not UTF-8"),
    (b"a = " + b"[" * 2000 + b"]" * 2000, "nested too deeply"),
    (b"[pelvis\n", "not valid TOML"),
    (b"x = 1\n" * 300000, "MB"),
])
def test_unreadable_files_are_refused_naming_the_file(tmp_path, content, needle):
    path = tmp_path / "broken.toml"
    path.write_bytes(content)
    err = refused(val.read_toml, path, "a marker map")
    assert needle in str(err) and str(path) in str(err)


def map_text(**replace) -> str:
    text = RBDS_MAP.read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    return text


@pytest.mark.parametrize("text,key,needle", [
    ("markers = 42\n" + map_text(), "markers", "unknown key 'markers'"),
    (map_text(**{'thigh = ["Thigh.Top.Lateral", "Thigh.Bottom.Lateral", "Thigh.Top.Medial", '
                 '"Thigh.Bottom.Medial"]': 'thigh = ["Thigh.Top.Lateral"] \n'
                                           'thighs = 1'}), "leg.thighs", "did you mean 'thigh'"),
    (map_text(**{'"Thigh.Bottom.Lateral", "Thigh.Top.Medial", "Thigh.Bottom.Medial"':
                 '"Thigh.Top.Lateral", "Thigh.Top.Lateral"'}), "leg.thigh", "more than once"),
    (map_text(**{'hip = "harrington"': 'hip = "harington"'}), "pelvis.hip", "did you mean 'harrington'"),
    (map_text(**{'sides = { R = "R.", L = "L." }': 'sides = 5'}), "sides", "must be a table"),
    (map_text(**{'asis = ["R.ASIS", "L.ASIS"]': 'asis = ["R.ASIS"]'}), "pelvis.asis", "at least 2"),
    (map_text(**{'foot = ["Heel.Top"': 'foot = ["@knee", "Heel.Top"'}), "leg.foot", "@ankle"),
])
def test_bad_marker_maps_are_refused_naming_file_and_key(tmp_path, text, key, needle):
    path = tmp_path / "map.toml"
    path.write_text(text)
    err = refused(markerset.load, path)
    assert err.key == key and needle in str(err) and str(path) in str(err)


def test_the_shipped_marker_maps_load():
    for name in markerset.shipped():
        assert markerset.load(name).name == name
