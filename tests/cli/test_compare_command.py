"""formopt compare on RBDS001 T35: its JSON, CSV and OpenSim exports, a scene across trials,
and bad input refused with exit 2."""

import json

from helpers import DATA

from formopt.cli import compare as compare_command
from formopt.cli import main

RBDS = DATA / "rbds"
RUN35, STATIC = RBDS / "RBDS001runT35.c3d", RBDS / "RBDS001static.c3d"
RUN25, FORCES25 = RBDS / "RBDS001runT25markers.txt", RBDS / "RBDS001runT25forces.txt"


def test_cli_compare_json_exports_and_bad_input(tmp_path, capsys):
    code = main(["compare", "--no-stride", "--trial", str(RUN35), "--static", str(STATIC), "--mass", "62",
                 "--height", "1.81", "--json", "--out", str(tmp_path)])
    data = json.loads(capsys.readouterr().out)
    assert code == 0
    td = data["touchdowns"][0]
    assert {"segment_angles_deg", "foot_strike_angle_deg", "angles_deg", "rates_dps",
            "hip_velocity_mps", "method", "impact_point", "contact_order", "T_c_band_J",
            "valid_data", "contact_laws"} <= set(td)
    assert set(td["segment_angles_deg"]) == {"trunk", "thigh", "shank", "foot"}
    assert set(data["settings"]) >= {"cutoff_hz", "effective_cutoff_hz", "force_threshold_n", "contact",
                                     "friction", "bounds_deg", "body", "markers"}
    # 10 Hz design cut-off run forward and back at 150 Hz: -3 dB at 0.806 of it (test_filters)
    assert data["settings"]["effective_cutoff_hz"] == 8.06
    assert data["settings"]["contact"] == "coulomb"  # the default law (issue 24)
    # one optimum per side, of that side's own dominant impact point: every valid step of
    # that point (valid under the law) gets its optimum, started from the side's, and converges
    for side, opt in data["optimum"].items():
        own = [t for t in data["touchdowns"] if t["valid_data"] and t["side"] == side
               and t["impact_point"] == opt["point"] and t["valid"]]
        assert opt["success"] and opt["per_step"]["converged"] == opt["per_step"]["steps"] == len(own)
        lo, hi = opt["saving_band_J"]
        assert lo <= opt["saving_J_per_step"] <= hi and opt["resolvable"] == (lo > 0 or hi < 0)
    assert len((tmp_path / "touchdowns.csv").read_text().splitlines()) == len(data["touchdowns"]) + 1
    trc = (tmp_path / "markers.trc").read_text().splitlines()
    assert trc[0].startswith("PathFileType\t4") and trc[2].split("\t")[2] == "4500"
    mot = (tmp_path / "angles.mot").read_text().splitlines()
    assert "endheader" in mot and mot[mot.index("endheader") + 1].startswith("time\tpelvis_tilt")
    assert main(["compare", "--trial", str(tmp_path / "none.c3d"), "--static", str(STATIC),
                 "--mass", "62", "--height", "1.81"]) == 2
    assert "no such file" in capsys.readouterr().err


def test_scene_file_gives_one_table_across_trials(tmp_path, capsys, monkeypatch):
    """A scene of two trials (its bounds beyond the default range of motion accepted): one
    table across them, and with --json only JSON on stdout (issue 25), each trial's report
    built once (Comparison.to_dict) and written whole beside its figure; its stride model
    handed to each trial's stride section (here a stand-in: no section). (The JSON checks were
    test_compare_json's own run of the same two trials.)"""
    models = []
    monkeypatch.setattr(compare_command, "answer", lambda result, progress=None, model=None: models.append(model))
    scene = tmp_path / "runners.toml"
    scene.write_text(f'[compare]\nmass = 62\nheight = 1.81\nstatic = "{STATIC}"\nper_step = false\n'
                     f'bounds = {{ knee = [0, 90] }}\nstride_model = "quick"\n[[trial]]\ntrial = "{RUN35}"\n'
                     f'[[trial]]\ntrial = "{RUN25}"\nforces = "{FORCES25}"\n')
    out = tmp_path / "out"
    assert main(["compare", "--scene", str(scene), "--json", "--out", str(out), "--starts", "1"]) == 0
    assert models == ["quick", "quick"]
    rows = (out / "trials.csv").read_text().splitlines()
    assert len(rows) == 1 + 4 and "RBDS001runT25markers.txt" in rows[-1]
    printed = json.loads(capsys.readouterr().out)  # the whole of stdout is one JSON object
    assert [row["side"] for row in printed["trials"]] == ["R", "L", "R", "L"]
    for stem in ("RBDS001runT35", "RBDS001runT25markers"):
        report = json.loads((out / stem / "comparison.json").read_text())
        assert report["figure"] == str(out / stem / "comparison.png")
        assert {"settings", "touchdowns", "summary", "optimum"} <= set(report)
        assert set(report["optimum"]) == {"R", "L"}  # one per side, never pooled
        rows = [r for r in printed["trials"] if r["trial"].endswith(report["source"].split("/")[-1])]
        assert [r["T_c_J"] for r in rows] == [report["summary"][s]["T_c_mean"] for s in ("R", "L")]
    bad = tmp_path / "bad.toml"
    bad.write_text('[compare]\nmas = 62\n')
    assert main(["compare", "--scene", str(bad)]) == 2
    assert "unknown key 'mas'" in capsys.readouterr().err


def test_a_trial_that_cannot_be_read_is_refused_before_any_other_runs(tmp_path, capsys):
    """Issue 37: a scene whose second trial failed printed the first trial's progress and table,
    then the error. Every trial's files are read first: one line naming the trial and its file,
    and nothing written."""
    broken = tmp_path / "broken.c3d"
    broken.write_bytes(RUN35.read_bytes()[:5000])
    scene = tmp_path / "two.toml"
    scene.write_text(f'[compare]\nmass = 62\nheight = 1.81\nstatic = "{STATIC}"\nstride = false\n'
                     f'[[trial]]\ntrial = "{RUN35}"\n[[trial]]\ntrial = "{broken}"\n')
    out = tmp_path / "out"
    assert main(["compare", "--scene", str(scene), "--out", str(out)]) == 2
    printed = capsys.readouterr()
    assert printed.out == "" and not out.exists()
    [line] = printed.err.splitlines()
    assert f"trial 2 of 2 ({broken}): {broken}: " in line
