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
