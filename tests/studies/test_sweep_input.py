"""Sweep parameters pass the scene's checks before any work: each value in its physical range,
each quantity once, a bounded grid, a CSV of this sweep only."""

import numpy as np
import pytest

from formopt.io.files import OutputError
from formopt.io.scene import load
from formopt.mechanics.errors import InputError
from formopt.studies import sweep
from helpers import SHIPPED

SPRING = SHIPPED / "landing_spring.toml"


@pytest.mark.parametrize("text, words", [
    ("friction=-0.5:-0.1:2", "friction = -0.5 is outside"),
    ("friction=0:1:2", "friction = 0 is outside"),
    ("slope_deg=70:89:2", "between -60 and 60 deg"),
    ("ankle_deg=-20:900:3", "ankle_deg = 900 is outside"),
    ("hip_vx=1:nan:3", "finite"),
])
def test_a_value_beyond_its_physical_range_is_refused(text, words):
    with pytest.raises(InputError, match=words):
        sweep.parse_param(text)


@pytest.mark.parametrize("names", [("ankle_deg", "ankle_deg"), ("speed_mps", "hip_vx")])
def test_one_quantity_twice_is_refused(names):
    with pytest.raises(InputError, match="same quantity"):
        sweep.check_grid([(n, np.array([1.0, 2.0])) for n in names])


def test_a_grid_beyond_the_limit_is_refused_before_any_work():
    huge = [("ankle_deg", np.zeros(100_000)), ("knee_deg", np.zeros(100_000))]
    with pytest.raises(InputError, match="more than the 1000000"):
        sweep.check_grid(huge)


def test_another_grid_into_an_existing_csv_is_refused(tmp_path):
    scene, out = load(SPRING), tmp_path / "sweep.csv"
    sweep.run(scene, [sweep.parse_param("ankle_deg=-2:2:2")], out, progress=False)
    before = out.read_text()
    with pytest.raises(OutputError, match="another grid"):
        sweep.run(scene, [sweep.parse_param("ankle_deg=-3:3:2")], out, progress=False)
    assert out.read_text() == before


def test_a_coulomb_sweep_after_a_no_slip_sweep_gets_its_own_model(tmp_path):
    """The cache of landing models is keyed by the contact law too (issue 25)."""
    import dataclasses

    import formopt

    scene = load(SPRING)
    coulomb = dataclasses.replace(scene, contact="coulomb")
    grid = [sweep.parse_param("ankle_deg=-16:-16:1")]
    sweep.run(scene, grid, tmp_path / "a.csv", progress=False)
    row = sweep.run(coulomb, grid, tmp_path / "b.csv", progress=False)[0]
    direct = formopt.simulate(dataclasses.replace(coulomb, state=sweep.apply(coulomb, {"ankle_deg": -16.0}).state))
    assert float(row["T_c_total"]) == pytest.approx(direct.T_c_total, rel=1e-9)
