"""Scenes: the shipped ones load and run; bad input names its key and exits with status 2."""

import copy
import json
import subprocess
import sys
import tomllib

import numpy as np
import pytest
from helpers import SHIPPED, touchdown

from formopt import SceneError, impact, load
from formopt.cli import main
from formopt.io.scene import parse

REFERENCE = SHIPPED / "forefoot_strike.toml"


@pytest.fixture()
def reference():
    return tomllib.loads(REFERENCE.read_text())


@pytest.mark.parametrize("path", [p for p in sorted(SHIPPED.glob("*.toml"))  # stride scenes:
                                  if "stride" not in tomllib.loads(p.read_text())],  # test_stride_scene
                         ids=lambda p: p.name)
def test_shipped_scenes_load_and_run(path):
    scene = load(path)
    r = impact(scene)
    assert r.T > 0 and 0 <= r.T_c <= r.T


def test_reference_scene_state(reference):
    scene = parse(reference)
    assert np.allclose(scene.state, touchdown(w=(0.0, -150.0, 120.0, 40.0)))
    assert scene.strike == "forefoot" and scene.friction == 0.8 and scene.slope == 0.0
    assert scene.body["thigh"].inertia_proximal == pytest.approx(0.557)


def test_preset_equals_the_explicit_body(reference):
    """The reference scene writes the paper body out; preset = "paper" gives the same numbers."""
    preset = copy.deepcopy(reference)
    preset["body"] = {"preset": "paper"}
    a, b = impact(parse(reference)), impact(parse(preset))
    assert abs(a.T_c - b.T_c) < 1e-3 * a.T_c  # the scene rounds the shank to 4 digits


def edit(data, path, value):
    *head, last = path.split(".")
    for key in head:
        data = data.setdefault(key, {})
    if value is DELETE:
        del data[last]
    else:
        data[last] = value


DELETE = object()
BAD = [
    ("touchdown.angles_deg.kne", 18.0, "touchdown.angles_deg.kne", "did you mean 'knee'"),
    ("ground.frction", 0.8, "ground.frction", "did you mean 'friction'"),
    ("touchdown.strike", "toe", "touchdown.strike", "must be one of heel, forefoot, flat"),
    ("touchdown.strike", "forfoot", "touchdown.strike", "did you mean 'forefoot'"),
    ("touchdown.angles_deg.knee", DELETE, "touchdown.angles_deg.knee", "missing"),
    ("touchdown.angles_deg.knee", "18", "touchdown.angles_deg.knee", "must be a number"),
    ("touchdown.angles_deg.knee", True, "touchdown.angles_deg.knee", "must be a number"),
    ("touchdown.angles_deg.knee", float("nan"), "touchdown.angles_deg.knee", "must be finite"),
    ("touchdown.hip_velocity", [3.5], "touchdown.hip_velocity", "pair"),
    ("touchdown.hip_velocity", [3.5, float("inf")], "touchdown.hip_velocity[1]", "finite"),
    ("body.thigh.mass", -10.3, "body.thigh.mass", "must be between 0.005 and 500 kg"),
    ("body.shank.length", 0.0, "body.shank.length", "must be between 0.05 and 1.5 m"),
    ("body.thigh.com", 0.5, "body.thigh.com", "between 0 and 0.402"),
    ("body.thigh.inertia_proximal", 0.2, "body.thigh.inertia_proximal", "centre of mass"),
    ("body.foot.heel", [0.3, -0.07], "body.foot.heel", "behind the forefoot"),
    ("body.trunk", DELETE, "body.trunk", "missing"),
    ("ground.friction", 0.0, "ground.friction", "must be > 0"),
    ("ground.slope_deg", 75.0, "ground.slope_deg", "between -60 and 60"),
    ("scene.model", "full", "scene.model", "must be one of effective-mass, shank-foot, leg, leg-trunk, full-body"),
    ("scene.name", "", "scene.name", "non-empty"),
    ("optimise", {"variables": ["knee"]}, "optimise", "did you mean 'optimize'"),
]


@pytest.mark.parametrize("path,value,key,message", BAD, ids=[b[0] + ":" + repr(b[1])[:12] for b in BAD])
def test_bad_input_names_the_key(reference, path, value, key, message):
    edit(reference, path, value)
    with pytest.raises(SceneError) as err:
        parse(reference)
    assert err.value.key == key
    assert message in str(err.value)


def test_body_given_two_ways_is_refused(reference):
    reference["body"] = {"preset": "paper", "mass": 70.0}
    with pytest.raises(SceneError, match=r"body.mass: give either"):
        parse(reference)


def test_scaled_body_scene(reference):
    reference["body"] = {"mass": 62.0, "height": 1.81, "sex": "male"}
    scene = parse(reference)
    assert scene.body.mass == pytest.approx(62.0)
    assert "de Leva" in scene.body.source


def write(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return path


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "formopt.cli", *map(str, args)],
                          capture_output=True, text=True)


def run_main(capsys, *args) -> tuple[int, str]:
    """formopt.cli.main in this process (a new interpreter costs about 0.7 s of CPU): its exit
    status and what it printed on stderr."""
    code = main([str(a) for a in args])
    return code, capsys.readouterr().err


def test_cli_bad_scene_exits_2_with_one_line(tmp_path):
    """The entry point itself (`python -m formopt.cli`) as a subprocess: the other tests call
    formopt.cli.main in this process."""
    text = REFERENCE.read_text().replace("knee = 18.0", "kne = 18.0")
    out = run_cli("impact", write(tmp_path, text))
    assert out.returncode == 2
    assert out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "touchdown.angles_deg.kne" in lines[0] and "knee" in lines[0]
    assert "Traceback" not in out.stderr


@pytest.mark.parametrize("text,needle", [
    ("[scene\nname = 1", "not valid TOML"),
    ("", "scene: missing"),
])
def test_cli_malformed_files(tmp_path, capsys, text, needle):
    code, err = run_main(capsys, "impact", write(tmp_path, text))
    assert code == 2 and needle in err and "Traceback" not in err


def test_cli_missing_file(capsys):
    code, err = run_main(capsys, "impact", "no/such/scene.toml")
    assert code == 2 and "cannot read" in err


def test_cli_unreachable_flat_posture(tmp_path, capsys):
    text = (SHIPPED / "flat_strike.toml").read_text().replace("ankle = -4.0", "ankle = 0.0")
    code, err = run_main(capsys, "impact", write(tmp_path, text))
    assert code == 2 and "sole on the ground" in err


def test_cli_json(capsys):
    assert main(["impact", str(REFERENCE), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("T", "T_c", "T_a", "impulse", "mu_c", "dv_trunk", "valid", "warnings"):
        assert key in data
    assert set(data["impulse"]) == {"forefoot"} and len(data["impulse"]["forefoot"]) == 2
    assert len(data["dv_trunk"]) == 2
    assert data["T_c"] + data["T_a"] == pytest.approx(data["T"], rel=1e-10)
    assert data["touchdown"]["angles_deg"]["knee"] == pytest.approx(18.0)
    assert isinstance(data["valid"], bool)


def test_cli_table(capsys):
    assert main(["impact", str(SHIPPED / "heel_strike.toml")]) == 0
    text = capsys.readouterr().out
    assert "T_c" in text and "heel" in text and "valid:" in text


def test_rigid_trunk_needs_its_inertia(reference):
    reference["scene"]["model"] = "leg-trunk"
    with pytest.raises(SceneError) as err:
        parse(reference)  # the reference trunk is only a mass
    assert err.value.key == "body.trunk.length"
    reference["body"]["trunk"] = {"mass": 44.0, "length": 0.5, "com": 0.31, "inertia_com": 2.7}
    reference["body"]["swing_leg"] = {"mass": 14.5}
    assert impact(parse(reference)).T_c > 0


@pytest.mark.parametrize("bounds,needle", [([0.0, 150.0], "knee's range of motion"),
                                           ([-10.0, 60.0], "knee's range of motion"),
                                           ([60.0, 10.0], "lo < hi")])
def test_bounds_beyond_the_range_of_motion_are_refused_as_compare_refuses_them(bounds, needle,
                                                                                capsys):
    """One rule for scenes and compare (io.validate.joint_bounds): refused, not clipped."""
    data = tomllib.loads((SHIPPED / "demo.toml").read_text())
    data["optimize"]["variables"] = ["hip", "knee", "ankle"]
    data["optimize"]["bounds_deg"] = {"knee": bounds}
    with pytest.raises(SceneError) as err:
        parse(data, "demo.toml")
    assert err.value.key == "optimize.bounds_deg.knee" and needle in str(err.value)
    assert main(["compare", "--trial", "t.c3d", "--static", "s.c3d", "--mass", "62", "--height",
                 "1.81", "--bounds", f"knee={bounds[0]:g}:{bounds[1]:g}"]) == 2
    assert f"--bounds.knee: [{bounds[0]:g}, {bounds[1]:g}]" in capsys.readouterr().err  # not the files


def test_load_names_the_file(tmp_path):
    text = REFERENCE.read_text().replace("friction = 0.8", "friction = 800.0")
    with pytest.raises(SceneError, match=r"scene.toml: ground.friction: must be > 0 and <= 100, not 800"):
        load(write(tmp_path, text))
