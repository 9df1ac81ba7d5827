"""gait2d's muscle table: read as shipped, with its licence beside it; a bad table is one line."""

import numpy as np
import pytest

from formopt.io.muscle_table import DATA, gait2d_muscles, read_gait2d_table
from formopt.mechanics.errors import InputError
from formopt.mechanics.muscles import MUSCLES


def test_the_shipped_table_is_gait2ds():
    table = read_gait2d_table()
    # gait2dc_par.xls, section 2, rows R.Iliopsoas .. R.TibialisAnt
    np.testing.assert_array_equal(table["Fmax"], [1500, 3000, 3000, 1200, 7000, 3000, 4000, 2500])
    np.testing.assert_array_equal(table["dRankle"], [0, 0, 0, 0, 0, -0.053, -0.053, 0.037])
    assert "Apache License" in (DATA.parent / "LICENSE-gait2dc.txt").read_text()
    assert gait2d_muscles().names == MUSCLES


def test_a_bad_table_names_the_file(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        read_gait2d_table(tmp_path / "missing.csv")
    bad = tmp_path / "bad.csv"
    bad.write_text(DATA.read_text().replace("1500.0", "strong"))
    with pytest.raises(InputError, match=r"bad\.csv: the muscle table needs numbers"):
        read_gait2d_table(bad)
    short = tmp_path / "short.csv"
    short.write_text("\n".join(DATA.read_text().splitlines()[:-1]))
    with pytest.raises(InputError, match="7 muscle rows"):
        read_gait2d_table(short)
