"""The shipped scenes: package data listed by `formopt scenes`, copied by `formopt scenes copy`,
and taken by name wherever a scene file is."""

import json

import pytest
from helpers import SHIPPED

import formopt
from formopt.cli import main


def test_every_shipped_scene_is_listed_with_a_title():
    names = formopt.scenes()
    assert set(names) == {p.stem for p in SHIPPED.glob("*.toml")}
    assert all(0 < len(title) <= 100 for title in names.values())
    assert names["stride_rbds001"].startswith("RBDS001 (Fukuchi et al. 2017: 62 kg")  # "et al." ends no sentence


def test_a_name_and_its_path_load_the_same_scene():
    assert formopt.load("heel_strike").state.tolist() == \
        formopt.load(SHIPPED / "heel_strike.toml").state.tolist()
    assert formopt.scene_path("demo.toml") == formopt.scene_path("demo") == SHIPPED / "demo.toml"


def test_a_path_wins_over_a_shipped_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "demo.toml").write_text((SHIPPED / "heel_strike.toml").read_text())
    assert formopt.load("demo.toml").strike == "heel"


def test_an_unknown_name_is_refused_naming_the_shipped_ones():
    with pytest.raises(formopt.SceneError, match=r"nosuch: no such file, and not a shipped scene.*demo"):
        formopt.load("nosuch")


def test_list_names_every_shipped_scene_with_or_without_its_word(capsys):
    assert main(["scenes"]) == 0
    listed = capsys.readouterr().out
    assert main(["scenes", "list"]) == 0
    assert capsys.readouterr().out == listed
    assert all(name in listed for name in formopt.scenes())


def test_copy_writes_once_and_refuses_to_overwrite(tmp_path, capsys):
    assert main(["scenes", "copy", "demo", str(tmp_path / "mine")]) == 0
    copied = tmp_path / "mine" / "demo.toml"
    assert copied.read_text() == (SHIPPED / "demo.toml").read_text()
    assert "formopt solve" in capsys.readouterr().out
    assert main(["scenes", "copy", "demo", str(tmp_path / "mine")]) == 2
    assert "exists already" in capsys.readouterr().err
    assert main(["scenes", "copy", "nosuch", str(tmp_path)]) == 2


def test_copy_refuses_a_link_or_a_folder_in_its_place(tmp_path, capsys):
    """A dangling DIR/demo.toml link would take the copy outside DIR; a folder is not a file."""
    outside, folder = tmp_path / "outside.toml", tmp_path / "mine"
    folder.mkdir()
    (folder / "demo.toml").symlink_to(outside)
    (folder / "stride.toml").mkdir()
    for name in ("demo", "stride"):
        assert main(["scenes", "copy", name, str(folder)]) == 2
        assert len(capsys.readouterr().err.strip().splitlines()) == 1
    assert not outside.exists() and (folder / "demo.toml").is_symlink()


def test_commands_take_a_shipped_name(capsys):
    assert main(["impact", "heel_strike", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["strike"] == "heel"
