"""formopt data [copy DIR]: the trial shipped in the wheel, credited, and the same data as the
repository's RBDS001 run for its first 8 s."""

import ezc3d
import numpy as np
from helpers import DATA

from formopt.cli import main
from formopt.cli.data import SHIPPED, STATIC, TRIAL


def test_copy_gives_the_trial_its_licence_and_the_command_to_run(tmp_path, capsys):
    assert main(["data", "copy", str(tmp_path / "mine")]) == 0
    out = capsys.readouterr().out
    copied = {p.name for p in (tmp_path / "mine").iterdir()}
    assert copied == {TRIAL, STATIC, "README.md", "LICENSE"}
    assert f"formopt compare --trial {tmp_path / 'mine' / TRIAL} --static {tmp_path / 'mine' / STATIC}" in out
    assert "CC BY 4.0" in (tmp_path / "mine" / "LICENSE").read_text()
    assert "Fukuchi" in (tmp_path / "mine" / "README.md").read_text()
    assert main(["data", "copy", str(tmp_path / "mine")]) == 2  # never overwrites
    assert "exists already" in capsys.readouterr().err


def test_the_shipped_trial_is_the_first_8_s_of_the_measured_one():
    short, whole = ezc3d.c3d(str(SHIPPED / TRIAL)), ezc3d.c3d(str(DATA / "rbds" / "RBDS001runT35.c3d"))
    points, analogs = short["data"]["points"], short["data"]["analogs"]
    assert points.shape[2] == 1200 and analogs.shape[2] == 2400  # 8 s at 150 Hz and 300 Hz
    np.testing.assert_array_equal(points, whole["data"]["points"][:, :, :1200])
    np.testing.assert_array_equal(analogs, whole["data"]["analogs"][:, :, :2400])
    assert short["parameters"]["POINT"]["LABELS"]["value"] == whole["parameters"]["POINT"]["LABELS"]["value"]
    assert (SHIPPED / STATIC).read_bytes() == (DATA / "rbds" / "RBDS001static.c3d").read_bytes()


def test_listing_names_the_files(capsys):
    assert main(["data"]) == 0
    out = capsys.readouterr().out
    assert TRIAL in out and STATIC in out and "CC BY 4.0" in out
