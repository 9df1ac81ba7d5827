"""Bad input never crashes: mutated scenes through every command, bad output paths, and
sweeps that are interrupted, torn or run twice. Each either exits 2 with one line naming
what is wrong, or succeeds (or exits 1 with its reason) with finite numbers."""

import copy
import dataclasses
import errno
import functools
import io
import json
import math
import multiprocessing
import os
import re
import signal
import subprocess
import sys
import time
import tomllib
import warnings

import numpy as np
import pytest
from helpers import DATA, SHIPPED
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import formopt
from formopt.cli import main
from formopt.io import markerset, mocap
from formopt.mechanics.errors import InputError
from formopt.studies import sweep

SCENES = {p.name: tomllib.loads(p.read_text()) for p in sorted(SHIPPED.glob("*.toml"))}
FAST = settings(max_examples=150, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


def toml(value, depth=0) -> str:
    """Any parsed-TOML value (and the mutants below) back as TOML text, inline."""
    if isinstance(value, dict):
        items = ", ".join(f"{json.dumps(k)} = {toml(v, depth + 1)}" for k, v in value.items())
        return "\n".join(f"{json.dumps(k)} = {toml(v, 1)}" for k, v in value.items()) \
            if depth == 0 else "{" + items + "}"
    if isinstance(value, list):
        return "[" + ", ".join(toml(v, depth + 1) for v in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, (int, float)):
        return repr(value)
    return json.dumps(value)


def paths(value, prefix=()):
    """Every key path into a scene's tables."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield prefix + (k,)
            yield from paths(v, prefix + (k,))


REPLACEMENTS = st.sampled_from([
    "text", "", "ünïcødé\nnew line", True, [], {}, [1.0, 2.0, 3.0], {"a": 1},
    float("nan"), float("inf"), -float("inf"), 10**400, -1e308, 1e-320, 0, -1, 2**63,
    "nested", "long",
])


def mutant(data, path, action, replacement):
    data = copy.deepcopy(data)
    *parents, key = path
    holder = data
    for p in parents:
        holder = holder[p]
    if action == "delete":
        del holder[key]
    elif action == "misspell":
        holder[key + "x"] = holder.pop(key)
    elif action == "unicode key":
        holder[key + "\n\u00e9"] = holder.pop(key)
    else:
        if replacement == "nested":
            replacement = 1.0
            for _ in range(60):
                replacement = [replacement]
        elif replacement == "long":
            replacement = [1.0] * 20000
        holder[key] = replacement
    return data


@st.composite
def scene_mutants(draw, needs=None):
    names = [n for n, d in SCENES.items() if needs is None or needs in d]
    name = draw(st.sampled_from(names))
    data = SCENES[name]
    path = draw(st.sampled_from(list(paths(data))))
    action = draw(st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]))
    return mutant(data, path, action, draw(REPLACEMENTS))


def finite(value) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(finite(v) for v in value.values())
    if isinstance(value, list):
        return all(finite(v) for v in value)
    return True


def check(argv, capsys, json_out=True):
    """Run the command; exit 2 means one line on stderr, otherwise finite JSON on stdout."""
    code = main(argv)
    out, err = capsys.readouterr()
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("formopt: error: "), err[-2000:]
        assert len(lines[0]) < 600
    else:
        assert code in (0, 1), code
        if json_out:
            assert finite(json.loads(out)), "a success prints finite numbers"
    return code


def write(tmp_path, data, name="mutant.toml"):
    path = tmp_path / name
    path.write_text(toml(data), encoding="utf-8")
    return path


def test_the_writer_round_trips_every_shipped_scene(tmp_path):
    for name, data in SCENES.items():
        assert tomllib.loads(write(tmp_path, data).read_text()) == data, name


@FAST
@given(data=scene_mutants())
def test_mutated_scenes_through_impact(tmp_path, capsys, data):
    check(["impact", str(write(tmp_path, data)), "--json"], capsys)


@settings(FAST, max_examples=40)
@given(data=scene_mutants(needs="joints"))
def test_mutated_scenes_through_simulate(tmp_path, capsys, data):
    check(["simulate", str(write(tmp_path, data)), "--json", "--out", str(tmp_path / "out")], capsys)


@settings(FAST, max_examples=20)  # each valid mutant is a full solve; derandomized: the same 20 each run
@given(data=scene_mutants(needs="optimize"))
def test_mutated_scenes_through_solve(tmp_path, capsys, data):
    check(["solve", str(write(tmp_path, data)), "--json", "--starts", "1", "--out",
           str(tmp_path / "out")], capsys)


@settings(FAST, max_examples=10)
@given(data=scene_mutants(needs="joints"))
def test_mutated_scenes_through_sweep(tmp_path, capsys, data):
    out = tmp_path / f"sweep{time.monotonic_ns()}.csv"
    check(["sweep", str(write(tmp_path, data)), "--param", "knee_deg=10:12:2", "--out", str(out),
           "--no-progress", "--workers", "1"], capsys, json_out=False)


@pytest.mark.parametrize("content", [b"", b"\x00\xff\xfe" * 100, b"[scene\nname = ", b"a = " +
                                     b"[" * 5000 + b"]" * 5000, b"x = 1\n" * 300000])
@pytest.mark.parametrize("command", ["impact", "simulate", "solve"])
def test_broken_files_exit_2_with_one_line(tmp_path, capsys, content, command):
    path = tmp_path / "broken.toml"
    path.write_bytes(content)
    assert check([command, str(path), "--out" if command != "impact" else "--json",
                  *([str(tmp_path / "o")] if command != "impact" else [])], capsys) == 2


@pytest.mark.parametrize("out", ["a_file", "a_file/below", "a_file/below/deeper"])
@pytest.mark.parametrize("command", ["simulate", "solve"])
def test_bad_output_paths_exit_2_and_leave_no_temporary_files(tmp_path, capsys, out, command):
    (tmp_path / "a_file").write_text("not a folder")
    scene = SHIPPED / ("landing_spring.toml" if command == "simulate" else "demo.toml")
    extra = ["--starts", "1"] if command == "solve" else []
    assert check([command, str(scene), "--out", str(tmp_path / out), *extra], capsys,
                 json_out=False) == 2
    assert not [p for p in tmp_path.rglob("*") if ".tmp" in p.name]


def test_numeric_api_refuses_absurd_states():
    from formopt import Impact
    from formopt.mechanics.body import paper_body
    from formopt.mechanics.errors import InputError
    from formopt.mechanics.model import build_model
    impact = Impact(build_model(paper_body(), "leg"), "forefoot", 0.0, 0.8)
    good = [0.0, 0.4, 0.3, -0.2, 3.5, -0.6, 0.0, 0.0, 0.0, 0.0]
    for k, bad in ((4, 1e200), (0, float("nan")), (9, -float("inf")), (2, 40.0)):
        x = list(good)
        x[k] = bad
        with pytest.raises(InputError, match="touchdown"):
            impact(x)


SPRING = str(SHIPPED / "landing_spring.toml")


def sweep_args(out, points=9, workers=1):
    return ["sweep", SPRING, "--param", f"ankle_deg=-12:-8:{points}", "--out", str(out),
            "--no-progress", "--workers", str(workers)]


def rows(path):
    return path.read_text().splitlines()


def test_a_second_writer_is_refused(tmp_path, capsys):
    import fcntl
    out = tmp_path / "sweep.csv"
    with out.open("a") as fh:
        fcntl.flock(fh.fileno(), fcntl.LOCK_EX)
        assert check(sweep_args(out), capsys, json_out=False) == 2
    assert out.read_text() == ""  # nothing written by the refused sweep


def test_a_torn_last_row_is_repaired_on_resume(tmp_path, capsys):
    whole, torn = tmp_path / "whole.csv", tmp_path / "torn.csv"
    assert main(sweep_args(whole)) == 0
    torn.write_bytes(whole.read_bytes()[:-25])  # the last row cut by a full disk
    assert main(sweep_args(torn)) == 0
    assert "torn last row" in capsys.readouterr().err
    assert sorted(rows(torn)) == sorted(rows(whole))


class FullDisk(io.RawIOBase):
    """A file whose disk fills after `flushes` whole writes: the next loses its last bytes (a
    torn row), then ENOSPC."""

    def __init__(self, fd, flushes):
        self.file, self.flushes = io.FileIO(fd, "w"), flushes

    def writable(self):
        return True

    def write(self, data):
        if self.flushes < 0:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        self.flushes -= 1
        return self.file.write(data if self.flushes >= 0 else bytes(data)[:-3])

    def close(self):
        self.file.close()
        super().close()


@pytest.mark.parametrize("workers", [1, 2])
def test_a_full_disk_ends_the_sweep_in_one_line_and_the_same_command_resumes(tmp_path, capsys,
                                                                           monkeypatch, workers):
    """ENOSPC while rows are appended: exit 2 in one line, the pool ended, the rows written
    kept; the same command on a disk with room repairs the torn row and finishes (issue 37)."""
    out = tmp_path / "sweep.csv"
    opened = sweep.append_csv

    def full(path, header):
        fh, done, torn = opened(path, header)
        fd = os.dup(fh.fileno())  # the same open file (and lock), written through a full disk
        fh.close()
        return io.TextIOWrapper(io.BufferedWriter(FullDisk(fd, 1)), newline=""), done, torn

    monkeypatch.setattr(sweep, "append_csv", full)
    before = set(multiprocessing.active_children())  # in one process, the session's Dask cluster
    assert main(sweep_args(out, points=12, workers=workers)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "No space left on device" in err[0], err
    assert not set(multiprocessing.active_children()) - before  # the pool ended with the sweep
    written = rows(out)
    assert len(written) > 1 and not out.read_bytes().endswith(b"\n")  # some rows, the last torn
    monkeypatch.setattr(sweep, "append_csv", opened)
    assert main(sweep_args(out, points=12, workers=workers)) == 0
    assert len(rows(out)) == 13 and len(set(rows(out))) == 13


def test_ctrl_c_ends_with_one_line_and_the_same_command_resumes(tmp_path, capsys, monkeypatch):
    out = tmp_path / "sweep.csv"
    calls = []
    original = sweep.landing_rows

    def interrupted(scene, chunk):
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return original(scene, chunk)

    monkeypatch.setattr(sweep, "landing_rows", interrupted)
    assert main(sweep_args(out, points=20)) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"formopt: interrupted: 8 of 20 rows written to {out}; the same command resumes"]
    monkeypatch.setattr(sweep, "landing_rows", original)
    assert main(sweep_args(out, points=20)) == 0
    assert len(rows(out)) == 21 and len(set(rows(out))) == 21  # the header and 20 rows, once


def test_killed_sweep_takes_its_pool_workers_with_it(tmp_path):
    out = tmp_path / "sweep.csv"
    proc = subprocess.Popen([sys.executable, "-m", "formopt.cli", *sweep_args(out, 3000, workers=2)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 600  # the readiness marker, however loaded the machine
    while not (out.exists() and len(rows(out)) > 20):
        assert time.monotonic() < deadline and proc.poll() is None, "the sweep wrote no 20 rows"
        time.sleep(0.1)
    children = subprocess.run(["pgrep", "-P", str(proc.pid)], capture_output=True,
                              text=True).stdout.split()
    assert children, "the pool's workers"
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    deadline = time.monotonic() + 120.0  # PR_SET_PDEATHSIG: measured 15-26 ms; generous for a loaded machine
    while time.monotonic() < deadline and any(os.path.exists(f"/proc/{c}") for c in children):
        time.sleep(0.05)
    assert not [c for c in children if os.path.exists(f"/proc/{c}")]
    written = rows(out)
    assert all(len(r.split(",")) == len(written[0].split(",")) for r in written[:-1])


def test_a_newline_in_a_file_name_stays_on_one_line(tmp_path, capsys):
    assert check(["impact", str(tmp_path / "no\nsuch.toml")], capsys, json_out=False) == 2
    # a newline is a legal character of a Linux path: the landing runs and its output says where
    assert check(["simulate", SPRING, "--out", str(tmp_path / "a\nb" / "c")], capsys, json_out=False) == 0


# -- compare scenes and marker maps: the same vocabulary as scenes (issue 25) -------------------

RUN35, STATIC = DATA / "rbds" / "RBDS001runT35.c3d", DATA / "rbds" / "RBDS001static.c3d"
RUN25, FORCES25 = DATA / "rbds" / "RBDS001runT25markers.txt", DATA / "rbds" / "RBDS001runT25forces.txt"
COMPARE = f'[compare]\nmass = 62\nheight = 1.81\nstatic = "{STATIC}"\n'
ONE_TRIAL = f'[[trial]]\ntrial = "{RUN35}"\n'


@pytest.mark.parametrize("text,needle", [
    (COMPARE + "[[trial]]\ntrial = 42\n", "trial[1].trial: must be a non-empty string, not 42"),
    (COMPARE.replace(f'"{STATIC}"', "{ a = 1 }") + ONE_TRIAL, "compare.static: must be a non-empty"),
    ("[[compare]]\nmass = 62\n", "compare: must be a table, not list"),
    (COMPARE + 'bounds = "knee"\n' + ONE_TRIAL, "compare.bounds: must be a table of JOINT = [lo, hi]"),
    (COMPARE + "bounds = [0]\n" + ONE_TRIAL, "compare.bounds: must be a table"),
    (COMPARE + 'bounds = ["a", "b"]\n' + ONE_TRIAL, "compare.bounds: must be a table"),
    (COMPARE + "bounds = 5\n" + ONE_TRIAL, "compare.bounds: must be a table"),
    (COMPARE + "bounds = { knee = [0, 200] }\n" + ONE_TRIAL, "knee's range of motion"),
    (COMPARE + "bounds = { kne = [0, 20] }\n" + ONE_TRIAL, "did you mean 'knee'"),
    (COMPARE + "markers = 42\n" + ONE_TRIAL, "compare.markers: must be a non-empty string"),
    (COMPARE + "friction = 0\n" + ONE_TRIAL, "compare.friction: must be > 0"),
    (COMPARE + "starts = 2.5\n" + ONE_TRIAL, "compare.starts: must be a whole number"),
    (COMPARE + "per_step = 1\n" + ONE_TRIAL, "compare.per_step: must be true or false"),
    (COMPARE + 'contact = "coulomn"\n' + ONE_TRIAL, "did you mean 'coulomb'"),
    (COMPARE + 'stride_model = "scene"\n' + ONE_TRIAL, "did you mean 'scenes'"),
    (COMPARE + f'[trial]\ntrial = "{RUN35}"\n', "trial: must be [[trial]] entries"),
    ("[compare]\nmas = 62\n", "compare.mas: unknown key 'mas' (did you mean 'mass'?)"),
    ("[comparee]\n", "did you mean 'compare'"),
    ("a = " + "[" * 2000 + "]" * 2000 + "\n", "nested too deeply"),
])
def test_bad_compare_scenes_exit_2_with_one_line(tmp_path, capsys, text, needle):
    path = write_text(tmp_path / "compare.toml", text)
    assert main(["compare", "--scene", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("formopt: error: ")
    assert needle in err[0] and str(path) in err[0]


def write_text(path, text, encoding="utf-8"):
    path.write_text(text, encoding=encoding)
    return path


@pytest.mark.parametrize("content", [(COMPARE + ONE_TRIAL).encode("utf-16"), bytes(range(256)) * 8])
def test_compare_scenes_that_are_not_utf8_text_exit_2(tmp_path, capsys, content):
    path = tmp_path / "compare.toml"
    path.write_bytes(content)
    assert check(["compare", "--scene", str(path)], capsys, json_out=False) == 2


def test_a_cluster_of_one_marker_named_three_times_is_refused(tmp_path, capsys):
    """Three copies of one thigh marker span no plane: refused with the map's file and key
    (before, hip 14.8 and knee -11.5 deg with every step "valid")."""
    text = (markerset.SHIPPED / "rbds.toml").read_text().replace(
        '"Thigh.Bottom.Lateral", "Thigh.Top.Medial", "Thigh.Bottom.Medial"',
        '"Thigh.Top.Lateral", "Thigh.Top.Lateral"')
    path = write_text(tmp_path / "one_marker.toml", text)
    args = ["compare", "--trial", str(RUN35), "--static", str(STATIC), "--mass", "62",
            "--height", "1.81", "--markers", str(path), "--out", str(tmp_path / "o")]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "one_marker.toml: leg.thigh: names 'Thigh.Top.Lateral' more than once" in err[0]


COMPARE_SCENE = {"compare": {"mass": 62, "height": 1.81, "static": "no_static.c3d", "friction": 0.8,
                             "contact": "coulomb", "bounds": {"knee": [0.0, 60.0]}, "starts": 2,
                             "per_step": False, "markers": "rbds"},
                 "trial": [{"trial": "no_trial.c3d", "sex": "female"}]}


@FAST
@given(path=st.sampled_from([*paths(COMPARE_SCENE), ("trial", 0, "trial"), ("trial", 0, "sex")]),
       action=st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]),
       replacement=REPLACEMENTS)
def test_mutated_compare_scenes_exit_2_with_one_line(tmp_path, capsys, path, action, replacement):
    """Every mutant is refused in one line: by the vocabulary, or (when it is still valid) by
    its missing trial files, so no mutant reaches the measurement."""
    scene = write(tmp_path, mutant(COMPARE_SCENE, path, action, replacement), "compare.toml")
    assert check(["compare", "--scene", str(scene), "--out", str(tmp_path / "o")], capsys,
                 json_out=False) == 2


MAP = tomllib.loads((markerset.SHIPPED / "rbds.toml").read_text())


@FAST
@given(path=st.sampled_from(list(paths(MAP))),
       action=st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]),
       replacement=REPLACEMENTS)
def test_mutated_marker_maps_load_or_are_refused_in_one_line(tmp_path, path, action, replacement):
    try:
        markerset.load(write(tmp_path, mutant(MAP, path, action, replacement), "map.toml"))
    except InputError as err:
        assert "\n" not in str(err) and "map.toml" in str(err)


@pytest.mark.parametrize("table, key, value, error", [
    ("leg", "thigh", MAP["leg"]["shank"], "leg.shank: 'R.Shank.Top.Lateral' (side R) is in leg.thigh"),
    ("sides", "L", "R.", "leg.thigh: 'R.Thigh.Top.Lateral' (side L) is in leg.thigh (side R)")])
def test_a_marker_shared_by_two_segments_is_refused(tmp_path, table, key, value, error):
    """A thigh cluster that is the shank's markers gave angles (issue 37): a marker tracks one
    segment (both legs under one prefix share every marker)."""
    data = copy.deepcopy(MAP)
    data[table][key] = value
    with pytest.raises(InputError, match=re.escape(error)):
        markerset.load(write(tmp_path, data, "shared.toml"))


# -- the numeric API and sweep parameters: the same acceptance rule (issue 25) ---------------

NUMBERS = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6),
                    st.sampled_from([0, -1, 1e-300, 1e300, 2.5, True, "1", None]))


@st.composite
def api_calls(draw):
    """(function name, keyword arguments) of the numeric API, each argument drawn from
    absurd and ordinary numbers alike."""
    kind = draw(st.sampled_from(["solve", "simulate_state", "impact"]))
    if kind == "solve":
        key = draw(st.sampled_from(["starts", "seed", "tolerance", "max_iterations"]))
        return kind, {key: draw(NUMBERS)}
    if kind == "simulate_state":
        return kind, {k: draw(st.one_of(NUMBERS, st.just(default))) for k, default in
                      (("friction", 0.8), ("dt", 1e-3), ("duration", 0.05))}
    return kind, {"friction": draw(NUMBERS), "slope": draw(st.one_of(NUMBERS, st.floats(-1.0, 1.0))),
                  "law": draw(st.sampled_from(["no-slip", "coulomb", "frictionless"]))}


def call_api(kind, kwargs, context):
    """Run one API call; its result (finite, T_c >= 0 where valid) or an InputError."""
    import formopt
    from formopt.mechanics.landing import simulate_state

    if kind == "solve":  # solve(scene, **overrides) builds this Problem first: the check is there
        return context["problem"](**kwargs)
    if kind == "simulate_state":
        scene, lm = context["landing"]
        landing = simulate_state(lm, scene.strike, scene.state, **kwargs)
        return float(landing.energy[-1])
    result = formopt.Impact(context["leg"], "heel", kwargs["slope"], kwargs["friction"],
                            law=kwargs["law"])(context["state"])
    assert math.isfinite(result.T_c) and (result.T_c >= -1e-9 * result.T or not result.valid)
    return result.T_c


@pytest.fixture(scope="module")
def api_context():
    return api_setup()


def api_setup() -> dict:
    """What the API fuzz calls act on: the demo's problem settings (built, not solved), the
    spring landing's model, the paper's leg at the reference touchdown."""
    from helpers import touchdown

    import formopt
    from formopt.mechanics.landing import LandingModel

    demo, spring = formopt.load(SHIPPED / "demo.toml"), formopt.load(SHIPPED / "landing_spring.toml")
    return {"problem": lambda **kw: dataclasses.replace(demo.problem, **kw),
            "landing": (spring, LandingModel(spring.model(), spring.joints, spring.slope, True,
                                             spring.numerics.integrator, "no-slip")),
            "leg": demo.model(), "state": touchdown()}


@settings(max_examples=120, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(call=api_calls())
def test_the_numeric_api_takes_an_argument_or_refuses_it_in_one_line(api_context, call):
    """Every call either returns finite numbers (never a negative valid T_c), raises
    InputError with one line naming the argument, or (a landing) Diverged in one line; none hangs (bounded: a landing of at most
    LANDING_DURATION_S with a step of at least LANDING_DT_S)."""
    from formopt.mechanics.landing import Diverged

    kind, kwargs = call
    try:
        call_api(kind, kwargs, api_context)
    except Diverged as err:  # a landing's stated failure (exit 1 at the command line)
        assert "\n" not in str(err)
    except InputError as err:
        text = str(err)
        assert "\n" not in text and any(k in text for k in (*kwargs, "friction", "slope")), text


PARAM_TEXT = st.builds(
    lambda name, a, b, n: f"{name}={a}:{b}:{n}",
    st.sampled_from([*sweep.PARAMETERS, "speed", "", "friction=1"]),
    st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(["x", "", "1e400"])),
    st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from(["x", "-0"])),
    st.one_of(st.integers(-3, 3), st.sampled_from([10**6, 10**7, "2.5", "x", ""])))


@settings(max_examples=300, deadline=None, derandomize=True)
@given(texts=st.lists(PARAM_TEXT, min_size=1, max_size=3))
def test_sweep_parameters_are_checked_before_any_work(texts):
    """Any --param values: refused in one line naming the parameter, or a grid of at most
    MAX_POINTS points whose every value lies in its physical range (sweep.parse_param's
    ranges), each quantity once; no numpy warning on the way, no memory for a huge COUNT."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a numpy warning would print before the one line
            params = [sweep.parse_param(t) for t in texts]
            sweep.check_grid(params)
    except InputError as err:
        assert "\n" not in str(err) and ("--param" in str(err) or "grid" in str(err))
        return
    assert math.prod(len(v) for _, v in params) <= sweep.MAX_POINTS
    assert all(np.all(np.isfinite(v)) for _, v in params)


@pytest.mark.parametrize("argv", [["simulate", SPRING], ["solve", str(SHIPPED / "demo.toml")],
                                  ["sweep", SPRING, "--param", "knee_deg=1:2:2"]])
def test_an_empty_out_is_refused_not_taken_for_the_default(tmp_path, capsys, monkeypatch, argv):
    """`--out ""` is an empty path (issue 25), not "not given": nothing is written to out/."""
    monkeypatch.chdir(tmp_path)
    assert check([*argv, "--out", ""], capsys, json_out=False) == 2
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("name, content", [("s.png", None), ("s", None), ("binary.csv", bytes(range(256)) * 8)])
def test_a_sweep_writes_only_a_csv_it_owns(tmp_path, capsys, name, content):
    """A figure's name is the CSV's with the figure's suffix: --out s.png would write the CSV,
    then the figure over it; a binary file is not a sweep to resume (issue 37)."""
    out = tmp_path / name
    if content is not None:
        out.write_bytes(content)
    assert check(sweep_args(out, points=2), capsys, json_out=False) == 2
    assert (out.read_bytes() if content is not None else out.exists()) == (content or False)


@pytest.mark.parametrize("dangling", [True, False])
def test_a_sweep_never_writes_through_a_link(tmp_path, capsys, dangling):
    """--out a symbolic link: appending would write to the file it points to, outside the
    user's choice (a dangling link's target created, issue 37's campaign)."""
    outside, out = tmp_path / "outside.csv", tmp_path / "s.csv"
    if not dangling:
        outside.write_text("mine\n")
    out.symlink_to(outside)
    assert check(sweep_args(out, points=2), capsys, json_out=False) == 2
    assert (outside.read_text() == "mine\n") if not dangling else not outside.exists()


@pytest.mark.parametrize("redirect", [">/dev/full", ">&-"])
def test_a_full_or_closed_stdout_is_one_line_and_exit_2(redirect):
    """Nowhere to print the answer: one line on stderr, exit 2, no traceback (issue 37)."""
    done = subprocess.run(f"{sys.executable} -m formopt.cli impact heel_strike {redirect}", shell=True,
                          stderr=subprocess.PIPE, text=True)
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1, done.stderr


@pytest.mark.parametrize("argv, use", [
    (["impact", "stride"], "formopt stride"), (["simulate", "stride"], "formopt stride"),
    (["solve", "stride"], "formopt stride"), (["solve", "heel_strike"], "formopt simulate"),
    (["sweep", "stride", "--landings", "--param", "speed_mps=3:3.5:2"], "formopt stride"),
    (["stride", "demo"], "formopt solve"), (["stride", "landing_spring"], "formopt simulate"),
    (["bench", "stride"], "unrecognized arguments: stride")])
def test_a_command_refuses_a_scene_it_cannot_take_naming_the_one_to_use(tmp_path, capsys, argv, use):
    """Every command takes every scene kind or refuses it in one line, before any work (issue 37)."""
    monkey_out = ["--out", str(tmp_path / ("s.csv" if argv[0] == "sweep" else "o"))]
    assert main([*argv, *(monkey_out if argv[0] != "impact" else [])]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and use in err[0], err
    assert not list(tmp_path.iterdir())  # refused before anything is written


def test_an_objective_weight_beyond_its_range_is_refused(tmp_path, capsys):
    """1e308 overflowed the objective to inf and its JSON report to a traceback (issue 37)."""
    data = copy.deepcopy(SCENES["demo.toml"])
    data["optimize"]["objective"]["T_c"] = 1e308
    assert check(["solve", str(write(tmp_path, data)), "--json", "--out", str(tmp_path / "o")], capsys) == 2


@pytest.mark.parametrize("argv, option", [
    (["stride", "stride", "--speed", "abc"], "argument --speed: invalid float value: 'abc'"),
    (["sweep", "demo", "--param", "knee_deg=0:1:2", "--workers", "two"], "argument --workers"),
    (["compare", "--mass"], "argument --mass: expected one argument"),
    (["solve"], "required: scene"), (["nosuch"], "invalid choice: 'nosuch'"),
    (["sweep", "landing_spring", "--param", "ankle_deg=-12:-8:2", "--scheduler", " "], "--scheduler ''")])
def test_an_option_argparse_refuses_is_one_line_naming_it(tmp_path, monkeypatch, capsys, argv, option):
    """No usage dump: one line naming the option, exit 2, before any work (issue 37)."""
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("formopt: error: ") and option in err[0], err
    assert not list(tmp_path.iterdir())


# -- the command line's own options, damaged trial files (issue 37) ---------------------------

BAD_VALUES = st.sampled_from(["abc", "", " ", "nan", "inf", "-inf", "1e999", "-5", "ü\nx"])


def typed_options() -> dict[str, list[str]]:
    """Each command's options that take a typed or chosen value (argparse's own parser)."""
    from formopt.cli import parser

    top = parser()
    commands = next(a for a in top._actions if isinstance(a.choices, dict)).choices
    return {name: [a.option_strings[-1] for a in cmd._actions if a.option_strings and (a.type or a.choices)]
            for name, cmd in commands.items()}


def base_argv(command: str, folder, trial: str = "no_trial.c3d") -> list[str]:
    """A command line that would run, with a bad option to come (compare: `trial`)."""
    return {"impact": ["impact", "heel_strike", "--json"],
            "solve": ["solve", "demo", "--out", str(folder / "o")],
            "simulate": ["simulate", "landing_spring", "--out", str(folder / "o")],
            "sweep": ["sweep", "landing_spring", "--param", "ankle_deg=-12:-8:2", "--no-progress",
                      "--out", str(folder / "s.csv")],
            "compare": ["compare", "--trial", trial, "--static", str(STATIC), "--mass", "62", "--height",
                        "1.81", "--no-per-step", "--no-stride", "--starts", "1", "--out", str(folder / "o")],
            "bench": ["bench", "--quick", "--out", str(folder / "o")],
            "stride": ["stride", "stride", "--out", str(folder / "o")],
            "scenes": ["scenes"], "data": ["data"]}[command]


@st.composite
def bad_options(draw, folder_name="f"):
    """(command, the option and its bad value): a typed option with a value it cannot take, an
    unknown option, an option without its value, or sweep's --scheduler without an address."""
    options = typed_options()
    command = draw(st.sampled_from(sorted(options)))
    kind = draw(st.sampled_from(["typed", "typed", "unknown", "dangling", "scheduler"]))
    if kind == "typed" and options[command]:
        return command, [draw(st.sampled_from(options[command])), draw(BAD_VALUES)]
    if kind == "scheduler" and command == "sweep":
        return command, ["--scheduler", draw(st.sampled_from(["", " ", "\t"]))]
    return command, ["--nosuch", "1"] if kind != "dangling" or not options[command] else [options[command][-1]]


@FAST
@given(case=bad_options())
def test_a_bad_option_is_one_line_naming_it_before_any_work(tmp_path, capsys, case):
    """argparse's own errors (`--speed abc`) and the options' ranges: exit 2 in one line, no
    usage dump, before any work (compare's trial is missing: nothing is read)."""
    command, bad = case
    assert check([*base_argv(command, tmp_path), *bad], capsys, json_out=False) == 2


@st.composite
def damaged_text_trial(draw):
    """(file, damage, column, rows): one column of RBDS001 T25's first 300 frames (markers) or
    600 samples (forces) damaged in some rows, or the file cut."""
    which = draw(st.sampled_from(["markers", "forces"]))
    damage = draw(st.sampled_from(["nan", "empty", "text", "huge", "inf", "zero", "negative",
                                   "times 1e-3", "times 1e3", "cut rows", "cut columns", "no rows"]))
    return which, damage, draw(st.integers(0, 30)), draw(st.sampled_from(["all", "half", "one"]))


def write_damaged(folder, case) -> tuple:
    """The damaged pair of text files (markers, forces) of `case` (damaged_text_trial)."""
    which, damage, column, rows = case
    out = []
    for name, source, count in (("markers", RUN25, 301), ("forces", FORCES25, 601)):
        cells = [line.split("\t") for line in source.read_text().splitlines()[:count]]
        if name == which:
            k = column % len(cells[0])
            chosen = range(1, len(cells)) if rows == "all" else range(1, len(cells), 2) if rows == "half" else [50]
            for r in chosen:
                cell = cells[r][k]
                cells[r][k] = {"nan": "nan", "empty": "", "text": "x", "huge": "1e300", "inf": "inf",
                               "zero": "0", "negative": f"-{cell}",
                               "times 1e-3": f"{float(cell or 'nan') * 1e-3:g}",
                               "times 1e3": f"{float(cell or 'nan') * 1e3:g}"}.get(damage, cell)
            cells = cells[:len(cells) // 3] if damage == "cut rows" else cells[:1] if damage == "no rows" \
                else [c[:k] for c in cells] if damage == "cut columns" else cells
        path = folder / f"{name}.txt"
        path.write_text("\n".join("\t".join(c) for c in cells) + "\n")
        out.append(path)
    return tuple(out)


def measured_or_refused(folder, case, static) -> str:
    """Read and measure a damaged trial: "measured", or the refusal's class (one line naming
    one of its files, or not)."""
    from formopt.measure import measure

    markers, forces = write_damaged(folder, case)
    try:
        measure(mocap.read(markers, forces), static, 1.81)
    except InputError as refusal:
        named = str(refusal).startswith((str(markers), str(forces), static.source))
        return "refused one line" if named and "\n" not in str(refusal) else "refused, not naming its file"
    return "measured"


@settings(FAST, max_examples=15)
@given(case=damaged_text_trial())
def test_a_damaged_text_trial_is_measured_or_refused_naming_its_file(tmp_path, case):
    """No traceback, no numpy warning, a refusal names the file (issue 37)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert measured_or_refused(tmp_path, case, standing()) in ("measured", "refused one line")


@functools.cache
def standing():
    """RBDS001's standing trial, read once."""
    return mocap.read(STATIC)


# -- stride scenes: every [stride] key (issue 37 item 7); parsed only, no solve ---------------

STRIDE_EVERY_KEY = {**SCENES["stride.toml"], "stride": {
    **SCENES["stride.toml"]["stride"], "cadence_spm": 170.0, "impact_weight": 0.5, "torque_limit_nm_per_kg": 4.0,
    "max_iterations": 100, "starts": 2, "transcription": "hermite-simpson",
    "duration_s": {"flight": [0.02, 0.3], "heel": [0.005, 0.1]}, "tendons": {"hip": 0.0, "knee": 2.5, "ankle": 4.0},
    "actuation": "torque+springs"}}
STRIDE_MUSCLES = {**SCENES["stride.toml"], "stride": {  # the muscle rung's keys (issue 33)
    "speed_mps": 3.5, "strike": "heel", "actuation": "muscles", "objective": "activation", "nodes": 24}}
STRIDE_PATHS = [(base, path) for base in (STRIDE_EVERY_KEY, STRIDE_MUSCLES) for path in paths(base)]


@FAST
@given(where=st.sampled_from(STRIDE_PATHS),
       action=st.sampled_from(["delete", "misspell", "unicode key", "replace", "replace"]),
       replacement=REPLACEMENTS)
def test_mutated_stride_scenes_load_or_are_refused_in_one_line(where, action, replacement):
    """Each key of a [stride] scene (and its ground and body; a torque+springs scene and a
    muscle one) deleted, misspelt or replaced: the scene loads as a StrideScene within the
    stride's ranges, or is refused in one line naming the key, before any solve."""
    from formopt.io.scene import SceneError, parse
    from formopt.io.stride_scene import StrideScene
    from formopt.optim.stride import ranges

    base, path = where
    try:
        scene = parse(mutant(base, path, action, replacement))
    except (SceneError, InputError) as err:
        assert "\n" not in str(err).strip() and len(str(err)) < 600, str(err)
        return
    assert isinstance(scene, StrideScene)
    ranges.point(scene.speed, scene.cadence)
    assert scene.settings.nodes in ranges.RANGES["nodes"] and scene.friction in ranges.RANGES["friction"]


@FAST
@given(speed=NUMBERS)
def test_the_stride_api_refuses_a_speed_outside_its_range_before_any_solve(speed):
    from formopt.optim.stride import ranges

    if speed is None or (isinstance(speed, (int, float)) and not isinstance(speed, bool)
                         and math.isfinite(speed) and speed in ranges.RANGES["speed_mps"]):
        return  # the scene's or a runner's speed: a solve, not an attack
    with pytest.raises(InputError, match="speed_mps"):
        formopt.stride(formopt.load("stride"), speed=speed)
