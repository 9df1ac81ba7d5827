"""compare with several trials: --json prints only JSON (issue 25); each trial's report is
built once (Comparison.to_dict) and written whole beside its figure."""

import json

from helpers import DATA

from formopt.cli import main

RBDS = DATA / "rbds"


def test_several_trials_with_json_print_only_json(tmp_path, capsys):
    scene = tmp_path / "two.toml"
    scene.write_text(f'[compare]\nmass = 62\nheight = 1.81\nstatic = "{RBDS / "RBDS001static.c3d"}"\n'
                     f'per_step = false\n[[trial]]\ntrial = "{RBDS / "RBDS001runT35.c3d"}"\n'
                     f'[[trial]]\ntrial = "{RBDS / "RBDS001runT25markers.txt"}"\n'
                     f'forces = "{RBDS / "RBDS001runT25forces.txt"}"\n')
    out = tmp_path / "out"
    assert main(["compare", "--no-stride", "--scene", str(scene), "--json", "--starts", "1", "--out", str(out)]) == 0
    printed = json.loads(capsys.readouterr().out)  # the whole of stdout is one JSON object
    assert [row["side"] for row in printed["trials"]] == ["R", "L", "R", "L"]
    for stem in ("RBDS001runT35", "RBDS001runT25markers"):
        report = json.loads((out / stem / "comparison.json").read_text())
        assert report["figure"] == str(out / stem / "comparison.png")
        assert {"settings", "touchdowns", "summary", "optimum"} <= set(report)
        assert set(report["optimum"]) == {"R", "L"}  # one per side, never pooled
        rows = [r for r in printed["trials"] if r["trial"].endswith(report["source"].split("/")[-1])]
        assert [r["T_c_J"] for r in rows] == [report["summary"][s]["T_c_mean"] for s in ("R", "L")]


def test_two_trials_with_one_file_name_keep_their_own_folders():
    """run.c3d of two runners: each trial writes into its own folder (issue 25)."""
    from formopt.cli.compare import trial_folders

    trials = [{"trial": "a/run.c3d"}, {"trial": "b/run.c3d"}, {"trial": "c/other.c3d"}]
    assert trial_folders(trials) == ["run-1", "run-2", "other"]
