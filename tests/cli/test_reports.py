"""One JSON report per result: the result's to_dict plus the run's context, written and
printed by cli/common.emit."""

import json

import pytest
from helpers import SHIPPED

from formopt import impact, load, solve
from formopt.cli import main
from formopt.cli.common import scene_context


def printed(argv, capsys) -> dict:
    code = main(argv)
    report = json.loads(capsys.readouterr().out)  # --json: nothing but the report on stdout
    assert code == 0
    return report


def test_impact_report_is_the_result_in_its_context(capsys):
    path = SHIPPED / "heel_strike.toml"
    scene = load(path)
    report = printed(["impact", str(path), "--json"], capsys)
    assert report == json.loads(json.dumps({**scene_context(scene), **impact(scene).to_dict()}))


def test_solve_report_is_the_optimum_in_its_context(tmp_path, capsys):
    path = SHIPPED / "demo.toml"
    report = printed(["solve", str(path), "--json", "--starts", "1", "--out", str(tmp_path)], capsys)
    assert json.loads((tmp_path / "result.json").read_text()) == report  # written whole, the same
    opt = solve(load(path), starts=1).to_dict()
    for key in ("success", "status", "objective", "T_c", "verdict", "held_by", "terms"):
        assert report[key] == (pytest.approx(opt[key]) if isinstance(opt[key], float) else opt[key])
    assert report["reference"]["indicators"]["T_c"] == pytest.approx(opt["reference"]["indicators"]["T_c"])
    assert report["touchdown"]["strike"] == load(path).strike and "touchdown" in report["reference"]


def test_the_demo_headline_is_the_optimised_energy_of_its_json(tmp_path, capsys):
    """`make demo`: the headline is T_c (what the demo minimises) in J per step and W, the same
    numbers as result.json; a weighted objective's drop is never called a saving."""
    assert main(["solve", "demo", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    data = json.loads((tmp_path / "result.json").read_text())
    assert data["objective_terms"] == {"T_c": 1.0} and data["saving_of"] == "T_c"
    ref, opt = data["reference_terms"]["T_c"], data["terms"]["T_c"]
    assert data["saving_per_step"] == pytest.approx(ref - opt) and data["saving_W"] == pytest.approx(
        (ref - opt) * 171.4 / 60)
    line = next(s for s in text.splitlines() if s.startswith("against the reference:"))
    assert line == (f"against the reference: T_c per step {ref:.4g} -> {opt:.4g} J, "
                    f"{ref - opt:.4g} J less ({data['saving_W']:.3g} W at 171.4 steps/min)")
    assert "saves" not in text


def test_a_weighted_objective_drop_is_not_called_a_saving(tmp_path, capsys):
    assert main(["solve", "demo_support", "--out", str(tmp_path), "--starts", "2"]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("against the reference:"))
    data = json.loads((tmp_path / "result.json").read_text())
    rise = data["terms"]["T_c"] - data["reference_terms"]["T_c"]
    assert rise > 0 and data["saving_per_step"] == pytest.approx(-rise)
    assert f"{rise:.4g} J more" in line and "a weighted sum, not an energy saved" in line
