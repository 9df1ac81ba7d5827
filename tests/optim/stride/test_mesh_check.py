"""optim.stride.refine: a stride solved again on twice its nodes from itself, and what that moved
(MeshCheck; issue 34 item 2). The shipped stride scene (paper body, heel, torque+springs,
Hermite-Simpson) at 18 intervals (the heel strike's fewest), one start, checked on 36 once for the
module (24 took three times as long to solve as 20: 9 against 3 s of CPU; 18 and its check 7.3 s of
CPU against 20's 9.8, 2026-11-28); the record's
fields and changes, `converged` against the tolerance on constructed records, the finer solve's
start, the scene key's errors and `formopt stride --mesh-check` end to end. No new expression IPOPT sees: nothing for
test_derivatives.py."""

import json
import tomllib
from dataclasses import replace

import pytest
from helpers import SHIPPED

from formopt.cli import main
from formopt.io.scene import SceneError, parse
from formopt.optim.stride import optimum, refine
from formopt.optim.stride.refine import MESH_TOLERANCE_PCT, MeshCheck, fine_nodes, mesh_check, refined
from formopt.report.stride import stride_table
from formopt.studies import stride as study
from formopt.studies.stride import StrideStudy, mesh_text, stages

SCENE = SHIPPED / "stride.toml"
NODES = 18


def scene_data(**stride) -> dict:
    """The shipped stride scene at NODES nodes and one start, with `stride`'s keys over its [stride]."""
    data = tomllib.loads(SCENE.read_text())
    data["stride"].update({"nodes": NODES, "starts": 1, **stride})
    return data


@pytest.fixture(scope="module")
def coarse():
    """(the scene, its NLP, its stride at NODES nodes)."""
    scene = parse(scene_data())
    nlp = scene.nlp()
    return scene, nlp, optimum(nlp, scene.speed, scene.slope, scene.friction)


@pytest.fixture(scope="module")
def checked(coarse):
    _, nlp, stride = coarse
    return mesh_check(nlp, stride)


def record(cadence, objective, valid=True, success=True, touchdown=("stick", "stick")) -> MeshCheck:
    return MeshCheck(nodes=(40, 80), cadence_spm=cadence, objective_value=objective, touchdown=touchdown, valid=valid,
                     failed_checks=() if valid else ("drift_m 0.006 > 0.005",), success=success,
                     status="Solve_Succeeded" if success else "Maximum_Iterations_Exceeded",
                     iterations=50, cpu_s=1.0)


def test_the_record_holds_both_meshes(coarse, checked):
    _, _, stride = coarse
    assert checked.nodes == (NODES, 2 * NODES)
    assert checked.cadence_spm[0] == stride.cadence_spm and checked.objective_value[0] == stride.objective_value
    assert checked.success and checked.status == "Solve_Succeeded" and checked.iterations > 0 and checked.cpu_s > 0
    assert checked.valid == (not checked.failed_checks) and checked.coarse_valid == stride.valid
    assert checked.touchdown == ("stick", "stick") and not checked.continued  # no-slip; a torque rung: direct
    (c1, c2), (j1, j2) = checked.cadence_spm, checked.objective_value
    assert checked.cadence_change_pct == pytest.approx(100 * (c2 / c1 - 1), rel=1e-12)
    assert checked.objective_change_pct == pytest.approx(100 * (j2 / j1 - 1), rel=1e-12)
    # the same stride a mesh finer (18 -> 36, 2026-11-28: cadence -0.14 %, cost -0.77 %; 20 -> 40: -0.01 %,
    # -0.55 %), not another one
    assert abs(checked.cadence_change_pct) < 5 and j2 < j1
    out = json.loads(json.dumps(checked.to_dict()))
    assert out["converged"] == checked.converged and out["tolerance_pct"] == MESH_TOLERANCE_PCT
    assert out["nodes"] == [NODES, 2 * NODES] and out["cadence_change_pct"] == checked.cadence_change_pct


def test_converged_needs_both_changes_under_the_tolerance_and_a_valid_fine_stride():
    near, over = 1 + 0.99 * MESH_TOLERANCE_PCT / 100, 1 + 1.01 * MESH_TOLERANCE_PCT / 100
    assert record((170.0, 170.0 * near), (2.0, 2.0 / near)).converged
    assert not record((170.0, 170.0 * over), (2.0, 2.0)).converged
    assert not record((170.0, 170.0), (2.0, 2.0 * (2 - over))).converged
    assert not record((170.0, 170.0), (2.0, 2.0), valid=False).converged
    assert not record((170.0, 170.0), (2.0, 2.0), success=False).converged
    unanswered = replace(record((170.0, 170.0), (2.0, 2.0)), coarse_valid=False)  # the N-node stride invalid
    assert not unanswered.converged and unanswered.text().endswith("the 40-node stride itself is invalid")
    assert record((170.0, 170.0), (2.0, 1.9)).text() == \
        "80 nodes, solved from this 40-node stride, move the cadence +0.00 % and the cost -5.00 %: not converged at 1 %"
    assert "invalid (drift_m" in record((170.0, 170.0), (2.0, 2.0), valid=False).text()
    assert "did not converge" in record((170.0, 170.0), (2.0, 2.0), success=False).text()
    assert record((170.0, 170.0), (2.0, 2.0), touchdown=("slide", "stick")).text() == \
        "80 nodes, solved from this 40-node stride, move the cadence +0.00 % and the cost +0.00 %: converged " \
        "within 1 %; the touchdown sliding on 40 nodes, sticking on 80"
    assert replace(record((170.0, 170.0), (2.0, 2.0)), continued=True).text().endswith(
        "; solved by continuation (unsmoothed first: the direct solve met a restoration)")
    assert replace(record((170.0, 170.0), (2.0, 2.0)), mesh="intervals", coarse_valid=False).text().startswith(
        "80 intervals, solved from this 40-interval stride,")  # Hermite-Simpson's mesh, in its words


def test_the_fine_solve_starts_from_the_stride(coarse):
    """No IPOPT iteration on 2N nodes: the stride's own timing, so its cadence to round-off (the
    phase durations carried over as they are; the node histories interpolated)."""
    _, nlp, stride = coarse
    first = refined(nlp.variant({"max_iter": 0}, nodes=2 * NODES), stride, nlp, simulate=False)
    assert first.iterations == 0
    assert first.cadence_spm == pytest.approx(stride.cadence_spm, rel=1e-9)


def test_the_table_says_what_was_measured(coarse, checked):
    """The mesh note of a checked stride is its record's, not the canned figures (notes.mesh_note)."""
    _, _, stride = coarse
    strides = [replace(stride, mesh_check=checked)]
    table = stride_table(StrideStudy("small", strides, mesh_text(strides))).splitlines()
    assert [line for line in table if line.startswith("NOTE mesh")] == [f"NOTE mesh heel: {checked.text()}"]
    assert mesh_text(strides) == f"heel: {checked.text()}"
    assert not any(line.startswith("NOTE transcription") for line in table)
    noted = stride_table(StrideStudy("small", strides, mesh_text(strides), transcription="what it finds"))
    assert "NOTE transcription: what it finds" in noted.splitlines()  # beside a checked mesh too


@pytest.mark.parametrize("edit, message", [({"mesh_check": "yes"}, "true or false"),
                                           ({"mesh_check": True, "nodes": 80}, "checked on 160")])
def test_the_scene_key_is_named(edit, message):
    with pytest.raises(SceneError, match=r"stride\.mesh_check.*" + message):
        parse(scene_data(**edit))


def test_fine_nodes_refuses_past_the_range():
    assert fine_nodes(60) == 120
    with pytest.raises(Exception, match="at most 60 nodes"):
        fine_nodes(61)


def test_the_command_reports_the_check(coarse, checked, tmp_path, capsys, monkeypatch):
    """`--mesh-check` over a scene without the key: the record in the JSON (the best stride's and
    its row), the mesh note what was measured, one progress stage more. The command's two solves
    are the module's (its NLP's settings and the stride's speed and starts checked): solving them
    again cost 3 s of CPU; `formopt stride` solving end to end: test_stride_scene.py."""
    scene, nlp, stride = coarse
    path = tmp_path / "small.toml"
    path.write_text(SCENE.read_text().replace("nodes = 40", f"nodes = {NODES}\nstarts = 1"))
    assert stages(scene) == 1 and stages(parse(scene_data(mesh_check=True))) == 2

    def solved(on, speed, slope, mu, cadence, simulate, starts):
        assert (on.settings, speed, slope, mu, cadence, simulate, starts) == \
            (nlp.settings, scene.speed, scene.slope, scene.friction, scene.cadence, True, 1)
        return stride

    def mesh_checked(on, coarse_stride, simulate):
        assert on.settings == nlp.settings and coarse_stride is stride and simulate
        return checked

    monkeypatch.setattr(study, "optimum", solved)
    monkeypatch.setattr(study, "mesh_check", mesh_checked)
    code = main(["stride", str(path), "--json", "--mesh-check", "--out", str(tmp_path / "out")])
    report = json.loads(capsys.readouterr().out)
    assert code == (0 if report["valid"] else 1)
    check = report["mesh_check"]
    assert check["nodes"] == [NODES, 2 * NODES] and report["strides"][0]["mesh_check"] == check
    assert check["cadence_spm"][0] == pytest.approx(stride.cadence_spm)  # the reported stride: the N-node one
    assert report["cadence_spm"] == check["cadence_spm"][0]
    assert report["mesh"].startswith(f"heel: {2 * NODES} intervals, solved from this {NODES}-interval stride, move the "
                                     "cadence")  # the scene's Hermite-Simpson


def test_the_fine_stride_is_judged_as_the_stride(coarse, monkeypatch):
    """mesh_check's forward check as the stride's own (`simulate`: studies.stride.run's)."""
    _, nlp, stride = coarse
    seen = []
    monkeypatch.setattr(refine, "refined", lambda fine, s, source, simulate: seen.append(simulate) or s)
    for simulate in (False, True):
        assert mesh_check(nlp, stride, simulate).cadence_spm == (stride.cadence_spm,) * 2
    assert seen == [False, True]
