"""Stride scenes and `formopt stride`: the shipped scenes load, bad keys are named in one line,
the touchdown commands refuse a stride scene cleanly, and the command writes its JSON (the keys
issue 23 lists), CSV, figures and OpenSim files."""

import json
import tomllib

import pytest
from helpers import SHIPPED

from formopt import load
from formopt.cli import main
from formopt.io.scene import SceneError, parse
from formopt.io.stride_scene import StrideScene
from formopt.mechanics.joint_space import JointSpace

STRIDE_SCENES = [p for p in sorted(SHIPPED.glob("*.toml")) if "stride" in tomllib.loads(p.read_text())]
JSON_KEYS = ("success", "status", "iterations", "solve_s", "speed_mps", "strike", "cadence_spm",
             "step_length_m", "stance_s", "flight_s", "duty_factor", "peak_vertical_grf_bw",
             "touchdown", "impacts", "budget", "cost_of_transport", "mechanical_power_W", "checks",
             "strides")


def test_shipped_stride_scenes_load():
    assert {p.name for p in STRIDE_SCENES} == {"stride.toml", "stride_muscles.toml", "stride_rbds001.toml"}
    paper, muscles, rbds = (load(p) for p in STRIDE_SCENES)
    assert isinstance(paper, StrideScene) and paper.speed == 3.5 and paper.strike == "heel"
    assert JointSpace(rbds.body).mass_total == pytest.approx(62.0)  # both legs and the trunk
    assert rbds.strike == "best"
    assert muscles.settings.actuation == "muscles" and muscles.settings.objective == "metabolic"
    assert muscles.body == rbds.body


@pytest.mark.parametrize("edit, key", [({"speed_mps": 40.0}, "stride.speed_mps"),
                                       ({"strike": "toe"}, "stride.strike"),
                                       ({"objective": "fun"}, "stride.objective"),
                                       ({"nodes": 3}, "stride.nodes"),
                                       ({"duration_s": {"flight": [0.2, 0.1]}}, "stride.duration_s.flight"),
                                       ({"cadense_spm": 170}, "stride.cadense_spm"),
                                       ({"clearance_m": 0.5}, "stride.clearance_m"),
                                       ({"clearance_m": "1 cm"}, "stride.clearance_m"),
                                       ({"grading": 1.5}, "stride.grading"),
                                       ({"search": "wide"}, "stride.search"),
                                       ({"spend": 2}, "stride.spend"),
                                       ({"search": "global", "starts": 2}, "stride.starts"),
                                       ({"search": "global", "spend": 9}, "stride.spend")])
def test_bad_stride_keys_are_named(edit, key):
    data = tomllib.loads(STRIDE_SCENES[0].read_text())
    data["stride"].update(edit)
    with pytest.raises(SceneError, match=key.replace(".", r"\.")):
        parse(data)


def test_touchdown_commands_refuse_a_stride_scene(capsys):
    assert main(["impact", str(STRIDE_SCENES[0]), "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "formopt stride" in err[0]


def test_stride_command_writes_its_report(tmp_path, capsys):
    scene = tmp_path / "small.toml"
    # 18 nodes (a forefoot strike's fewest under no-slip) and one start: the report's keys and
    # files are the point, not the optimum (24 nodes took 5.2 s of solves, 18 take 2.6)
    scene.write_text(STRIDE_SCENES[0].read_text().replace("nodes = 40", "nodes = 18\nstarts = 1")
                     .replace('strike = "heel"', 'strike = "forefoot"'))
    code = main(["stride", str(scene), "--json", "--out", str(tmp_path / "out"), "--speed", "3.3"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    assert all(k in report for k in JSON_KEYS)
    assert report["speed_mps"] == 3.3 and report["strike"] == "forefoot"
    assert report["swing_clearance_m"] >= 0.01 - 1e-6  # contact.CLEARANCE, the default
    assert report["mesh"].startswith("hermite-simpson at 18 intervals is not mesh-converged")  # said beside the numbers
    assert report["transcription_note"] == ""  # measured to differ for the muscles' cost only
    row = report["strides"][0]
    assert row["swing_clearance_m"] == report["swing_clearance_m"] and row["search"] is None  # the local search
    assert set(report["budget"]) >= {"positive_work_J", "negative_work_J", "impacts_J",
                                     "friction_J", "passive_J", "balance_J"}
    assert set(report["impacts"][0]) >= {"point", "time_s", "T_c", "law", "mode", "mu_c", "valid"}
    names = {p.split("/")[-1] for p in report["files"]}
    assert {"stride.csv", "stride.mot", "stride_grf.sto", "stride_stick.png",
            "stride_angles.png", "stride_budget.png"} <= names


def test_the_swing_clearance_is_a_key_with_a_default():
    data = tomllib.loads(STRIDE_SCENES[0].read_text())
    assert parse(data).settings.clearance == 0.01  # contact.CLEARANCE
    data["stride"]["clearance_m"] = 0.0
    assert parse(data).settings.clearance == 0.0  # the ground alone, as before 2026-11-25


def test_the_torque_scenes_solve_the_runner_stride():
    """The shipped torque scenes hold problem.RUNNER_ANKLE's stride (Hermite-Simpson, the ankle's
    tendon, the impacts charged, moment dynamics, the approach floor), whose mesh note
    (notes.RUNNER_MESH) says what it was measured to move."""
    from formopt.optim.stride.notes import RUNNER_MESH, mesh_note
    from formopt.optim.stride.problem import APPROACH_SPEED, MOMENT_TIME, RUNNER_ANKLE, RUNNER_IMPACT_WEIGHT

    for name in ("stride.toml", "stride_rbds001.toml"):
        settings = load(SHIPPED / name).settings
        assert (settings.transcription, settings.nodes, settings.tendons) == ("hermite-simpson", 40, RUNNER_ANKLE)
        assert (settings.impact_weight, settings.moment_time, settings.approach_speed) == \
            (RUNNER_IMPACT_WEIGHT, MOMENT_TIME, APPROACH_SPEED)
        assert RUNNER_MESH in mesh_note(settings)


def test_the_actuation_ladder_is_one_key():
    data = tomllib.loads(STRIDE_SCENES[0].read_text())  # the paper body's scene, its tendons taken out
    data["stride"].pop("tendons")
    data["stride"].pop("objective")
    data["stride"].pop("moment_time_s")  # the torque rungs' (refused with muscles: below)
    rungs = {}
    for rung in ("torque", "torque+springs", "muscles"):
        data["stride"]["actuation"] = rung
        rungs[rung] = parse(data).settings
    assert rungs["torque"].actuation == "torque" and not rungs["torque"].tendons
    assert rungs["torque+springs"].tendons == {"knee": 2.5, "ankle": 4.0}  # RUNNER_TENDONS
    muscles = rungs["muscles"]
    assert muscles.actuation == "muscles" and muscles.objective == "metabolic"  # the calibrated cost
    assert muscles.muscles.max_force[0] == pytest.approx(1500.0 * (73.0 / 75.0) ** (2 / 3))  # iliopsoas
    assert muscles.force_rate_power == 2  # the squared rates unless the key says 1
    data["stride"]["force_rate_power"] = 1
    assert parse(data).settings.force_rate_power == 1


@pytest.mark.parametrize("edit, key", [({"actuation": "springs"}, "stride.actuation"),
                                       ({"actuation": "muscles", "tendons": {"ankle": 4.0}}, "stride.tendons"),
                                       ({"actuation": "torque", "tendons": {"ankle": 4.0}}, "stride.tendons"),
                                       ({"actuation": "muscles", "torque_limit_nm_per_kg": 3.0},
                                        "stride.torque_limit_nm_per_kg"),
                                       ({"actuation": "muscles", "objective": "effort"}, "stride"),
                                       ({"actuation": "muscles", "force_rate_power": 3}, "stride.force_rate_power"),
                                       ({"actuation": "muscles", "moment_time_s": 0.012}, "stride.moment_time_s"),
                                       ({"actuation": "torque", "force_rate_power": 1}, "stride.force_rate_power"),
                                       ({"objective": "activation"}, "stride")])
def test_bad_actuation_is_named(edit, key):
    data = tomllib.loads(STRIDE_SCENES[0].read_text())
    data["stride"].pop("tendons")
    data["stride"].pop("moment_time_s")  # the torque rungs' (its own case above)
    data["stride"].update(edit)
    with pytest.raises(SceneError, match=key.replace(".", r"\.")):
        parse(data)


def test_the_global_search_is_one_key():
    from formopt.optim.stride.search import solves_planned
    from formopt.studies.stride import stages

    data = tomllib.loads(STRIDE_SCENES[0].read_text())
    data["stride"].update(search="global", spend=2)
    scene = parse(data)
    assert scene.search == "global" and scene.spend == 2
    assert stages(scene) == solves_planned(3.5, 2) and stages(scene, 4.0, "best") == 3 * solves_planned(4.0, 2)
    data["stride"].update(search="local", starts=2)
    data["stride"].pop("spend")
    assert stages(parse(data)) == 1


def test_the_grading_key_reaches_the_settings():
    """[stride] grading: each phase's mesh graded toward its ends (StrideSettings.grading)."""
    data = tomllib.loads(STRIDE_SCENES[0].read_text())
    data["stride"]["grading"] = 1.0
    assert parse(data).settings.grading == 1.0 and load(STRIDE_SCENES[0]).settings.grading == 0.0


def test_strikes_within_the_mesh_uncertainty_are_said_to_tie():
    """A scene's strikes whose costs differ by less than their mesh may move the difference are one
    answer (studies.stride.tie_note): each stride's own mesh check where it measured (IPOPT
    converged on 2N nodes, both strides valid), else the figure measured on its settings."""
    from types import SimpleNamespace

    from formopt.studies.stride import tie_note

    def stride(strike, objective, moved=None, valid=True, checked=True):
        check = None if moved is None else SimpleNamespace(objective_change_pct=moved, measured=checked)
        return SimpleNamespace(strike=strike, objective_value=objective, cadence_spm=180.0, valid=valid,
                               success=True, mesh_check=check)

    def figure(pct):
        return lambda s: pct

    forefoot, heel, flat = stride("forefoot", 1.0), stride("heel", 1.0004), stride("flat", 1.05)
    said = tie_note([forefoot, heel, flat], figure(0.3))
    assert "heel (180.0 steps/min) 0.04 % costlier" in said and "(0.60 %" in said and "flat" not in said
    assert said.endswith("either is its answer")
    assert tie_note([forefoot, heel, flat], figure(None)) == ""  # no figure known: nothing claimed
    checked = [stride("forefoot", 1.0, -0.22), stride("heel", 1.0004, -0.08)]
    assert "(0.30 %: each cost up to 0.22 and 0.08 %)" in tie_note(checked, figure(None))
    assert tie_note([stride("forefoot", 1.0, 0.01), stride("heel", 1.0004, 0.02)], figure(0.3)) == ""
    stopped = [stride("forefoot", 1.0, 0.01), stride("heel", 1.0004, 0.02, checked=False)]  # a stopped 2N solve
    assert "(0.31 %: each cost up to 0.01 and 0.30 %)" in tie_note(stopped, figure(0.3))  # its change no measure
    assert tie_note([forefoot, stride("heel", 1.0004, valid=False)], figure(0.3)) == ""  # an invalid stride: no answer
    negative = tie_note([stride("forefoot", -1.0), stride("heel", -0.999)], figure(0.3))  # a work objective below 0
    assert "heel (180.0 steps/min) 0.10 % costlier" in negative
    assert tie_note([forefoot, stride("heel", 1.001), stride("flat", 1.002)], figure(0.3)).endswith("any is its answer")


def test_the_measured_mesh_figure_is_the_strides_own():
    """notes.mesh_cost_pct: the torque scenes' stride 0.3 %, its flat strike and its forefoot below
    3.5 m/s (whose 80-interval solves did not converge) 1.1 %; under Coulomb 0.5 %, the forefoot
    below 3.5 m/s 2 %, the flat strike (no sliding touchdown) as without; other settings none.
    The mesh note says what Coulomb's strides moved under Coulomb only."""
    from dataclasses import replace

    from formopt.optim.stride.notes import (
        RUNNER_COST_PCT,
        RUNNER_COULOMB_COST_PCT,
        RUNNER_COULOMB_FOREFOOT_PCT,
        RUNNER_COULOMB_MESH,
        RUNNER_UNCONVERGED_PCT,
        mesh_cost_pct,
        mesh_note,
    )

    runner = load(SHIPPED / "stride_rbds001.toml").settings
    assert mesh_cost_pct(replace(runner, strike="heel"), 2.5) == RUNNER_COST_PCT == 0.3
    assert mesh_cost_pct(replace(runner, strike="forefoot"), 3.5) == RUNNER_COST_PCT
    assert mesh_cost_pct(replace(runner, strike="forefoot"), 2.5) == RUNNER_UNCONVERGED_PCT == 1.1
    assert mesh_cost_pct(replace(runner, strike="flat"), 4.5) == RUNNER_UNCONVERGED_PCT
    assert mesh_cost_pct(replace(runner, torque_velocity=True), 3.5) is None
    assert mesh_cost_pct(replace(runner, nodes=20), 3.5) is None
    coulomb = replace(runner, law="coulomb")
    assert mesh_cost_pct(replace(coulomb, strike="heel"), 2.5) == RUNNER_COULOMB_COST_PCT == 0.5
    assert mesh_cost_pct(replace(coulomb, strike="forefoot"), 2.5) == RUNNER_COULOMB_FOREFOOT_PCT == 2.0
    assert mesh_cost_pct(replace(coulomb, strike="flat"), 3.5) == RUNNER_UNCONVERGED_PCT
    assert RUNNER_COULOMB_MESH in mesh_note(coulomb) and RUNNER_COULOMB_MESH not in mesh_note(runner)


def test_a_least_costly_stride_unlike_a_runners_names_the_one_that_is_not():
    """studies.stride.unlike_note: where the best stride lands stiff or crouches
    (Stride.unlike_a_runner, checks.unlike_a_runner's remarks), the least costly valid one that does not, and its extra cost."""
    from types import SimpleNamespace

    from formopt.optim.stride.checks import unlike_a_runner
    from formopt.studies.stride import unlike_note

    def stride(strike, objective, impacts=3.0, knee=40.0, valid=True):
        return SimpleNamespace(strike=strike, objective_value=objective, cadence_spm=179.0, valid=valid, success=True,
                               unlike_a_runner=unlike_a_runner(knee, impacts))

    flat, forefoot, heel = stride("flat", 1.0, impacts=28.0), stride("forefoot", 1.02), stride("heel", 1.03)
    said = unlike_note([flat, forefoot, heel])
    assert said.startswith("the least costly stride, the flat strike, is unlike a runner's")
    assert said.endswith("the forefoot strike (179.0 steps/min, 2.0 % costlier)")
    assert unlike_note([forefoot, flat]) == ""  # the best is runner-like
    assert unlike_note([flat]) == ""  # one strike solved: its own NOTE says it
    assert unlike_note([flat, stride("heel", 1.1, knee=80.0)]).endswith("so is every other strike solved")
    assert unlike_note([flat, stride("forefoot", 1.02, valid=False), heel]).endswith("heel strike (179.0 steps/min, "
                                                                                      "3.0 % costlier)")
