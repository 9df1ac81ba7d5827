"""Reading motion capture: RBDS subject 001 (C3D and text layout) with its units, rates and
force plate; the marker maps; the text writer read back."""

import numpy as np
import pytest
from helpers import DATA

from formopt.io import markerset, mocap

RBDS, RIC = DATA / "rbds", DATA / "ric"
RUN35 = RBDS / "RBDS001runT35.c3d"
RUN25, FORCES25 = RBDS / "RBDS001runT25markers.txt", RBDS / "RBDS001runT25forces.txt"
RIC_RUN, RIC_STATIC = RIC / "20160226T120637_run.c3d", RIC / "20160226T120637_static.c3d"


@pytest.fixture(scope="module")
def run35():
    return mocap.read(RUN35)


def test_files_read_with_their_units_and_rates(run35):
    run25 = mocap.read(RUN25, FORCES25)
    assert run35.rate == 150.0 and run35.force_rate == 300.0
    assert run25.rate == pytest.approx(150.0) and run25.force_rate == pytest.approx(300.0)
    assert 0.5 < np.nanmedian(run35.markers["R.ASIS"][:, 1]) < 1.5  # metres, not millimetres
    assert np.max(np.abs(run35.force)) > 1000.0  # N, from ezc3d's force-plate calibration
    assert run35.units == "mm" and run25.units == "mm" and not run35.suspect  # read, not cleaned
    # the centre of pressure in m, within the plate (RBDS: 1.25-3.05 m along X) while loaded
    for run in (run35, run25):
        loaded = run.force[:, 1] > 500.0
        assert run.cop.shape == run.force.shape and np.all((run.cop[loaded, 0] > 1.2) & (run.cop[loaded, 0] < 3.1))


def test_marker_maps_are_recognised(run35):
    assert markerset.recognise(run35.markers).name == "rbds"
    assert markerset.recognise(mocap.read(RIC_RUN).markers).name == "ric"
    assert markerset.recognise(mocap.read(RIC_STATIC).markers).name == "ric"
    for name in markerset.shipped():
        assert markerset.load(name).name == name


def test_the_text_writer_read_back_gives_the_trial(run35, tmp_path):
    """RBDS text layout (mm, 10 significant digits): the same rates, markers, force and centre
    of pressure (tests/measure/test_pipeline.py: and the same touchdowns)."""
    mocap.write_text(run35, tmp_path / "m.txt", tmp_path / "f.txt")
    text = mocap.read(tmp_path / "m.txt", tmp_path / "f.txt")
    assert text.rate == pytest.approx(run35.rate) and text.force_rate == pytest.approx(run35.force_rate)
    assert list(text.markers) == list(run35.markers)
    for name, xyz in run35.markers.items():  # NaN where the C3D has none (equal_nan)
        np.testing.assert_allclose(text.markers[name], xyz, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(text.force, run35.force, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(text.cop, run35.cop, rtol=1e-9, atol=1e-12)


def test_require_names_the_missing_markers(run35):
    run35.require(["R.ASIS"], "the test")
    with pytest.raises(mocap.MocapError, match=r"RBDS001runT35.c3d: the test needs markers that are "
                                               "missing: R.Nose, L.Nose"):
        run35.require(["R.ASIS", "R.Nose", "L.Nose"], "the test")


def short_text(tmp_path, change_markers=None, change_forces=None):
    """The first 300 frames of T25 as text files, a column of each changed: (markers, forces)."""
    paths = []
    for source, rows, change, name in ((RUN25, 301, change_markers, "m.txt"),
                                       (FORCES25, 601, change_forces, "f.txt")):
        lines = source.read_text().splitlines()[:rows]
        cells = [line.split("\t") for line in lines]
        for row in cells[1:]:
            if callable(change):
                change(row)
        path = tmp_path / name
        path.write_text("\n".join("\t".join(c) for c in cells) + "\n" if change != "empty" else "")
        paths.append(path)
    return paths


@pytest.mark.parametrize("change_markers, change_forces, needle", [
    (None, lambda r: r.__setitem__(1, "nan"), "f.txt: no force sample has finite Fx, Fy and Fz"),
    (None, lambda r: r.__setitem__(3, "1e300"), "m.txt: a ground force of 1e+300 N, beyond 100000 N"),
    (lambda r: r.__setitem__(0, str(float(r[0]) * 1e9)), None, "m.txt: the Time column spans"),
    ("empty", None, "m.txt: not a marker text file in the RBDS layout (no data rows)"),
    (None, "empty", "f.txt: not a force text file in the RBDS layout (no data rows)")])
def test_a_damaged_text_trial_is_refused_in_one_line_naming_its_file(tmp_path, change_markers,
                                                                     change_forces, needle):
    """Before (issue 37): a traceback (a force column of NaN, a Time in ns), numpy's warning
    before the refusal (an empty file)."""
    import warnings

    markers, forces = short_text(tmp_path, change_markers, change_forces)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(mocap.MocapError) as err:
            mocap.read(markers, forces).check()
    assert "\n" not in str(err.value) and str(err.value).startswith(str(tmp_path)), err.value
    assert needle in str(err.value)


def test_labels_no_map_fits_are_refused_naming_the_trial(run35):
    with pytest.raises(mocap.InputError, match=r"^run\.c3d: the markers match no shipped marker map"):
        markerset.recognise({k: v for k, v in run35.markers.items() if k != "R.ASIS"}, "run.c3d")
