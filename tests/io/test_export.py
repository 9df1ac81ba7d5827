"""io.export.write_osim: the planar body as an OpenSim 4 model, checked by its schema and its
numbers here (the `opensim` package, when installed, loads it: the optional test below)."""

import xml.etree.ElementTree as ET

import pytest

from formopt.io.export import MOT_COLUMNS, write_osim
from formopt.mechanics.body import scaled_body

BODY = scaled_body(62.0, 1.81, "male")


def test_the_model_has_the_bodys_masses_and_the_mots_coordinates(tmp_path):
    root = ET.parse(write_osim(tmp_path / "model.osim", BODY)).getroot()
    assert root.tag == "OpenSimDocument" and root.get("Version") == "40000"
    masses = [float(b.find("mass").text) for b in root.iter("Body")]
    assert sum(masses) == pytest.approx(BODY.mass) and len(masses) == 7
    coordinates = {c.get("name") for c in root.iter("Coordinate")}
    assert set(MOT_COLUMNS) <= coordinates and {"pelvis_tx", "pelvis_ty"} <= coordinates
    knees = [j for j in root.iter("PinJoint") if j.get("name").startswith("knee")]
    assert all(f.find("orientation").text.startswith("3.14159") for j in knees
               for f in j.iter("PhysicalOffsetFrame"))  # about -Z: flexion positive
    assert {m.get("name") for m in root.iter("Marker")} == {"heel_r", "forefoot_r", "heel_l", "forefoot_l"}


OPENSIM_CHECK = """
import sys, opensim as osim
model = osim.Model(sys.argv[1]); state = model.initSystem(); coords = model.getCoordinateSet()
def x_of(coordinate, degrees, body):
    coords.get(coordinate).setValue(state, degrees * 3.141592653589793 / 180.0, True)
    x = model.getBodySet().get(body).findStationLocationInGround(state, osim.Vec3(0, 0, 0)).get(0)
    coords.get(coordinate).setValue(state, 0.0, True)
    return x
print(model.getTotalMass(state), x_of("knee_angle_r", 30, "foot_r") < x_of("knee_angle_r", 0, "foot_r"),
      x_of("hip_flexion_r", 30, "shank_r") > x_of("hip_flexion_r", 0, "shank_r"))
"""


def test_opensim_loads_it_with_formopts_signs(tmp_path):
    """In a fresh interpreter: opensim's Moco links a CasADi of its own, which clashes with
    formopt's once both are loaded. Knee flexion moves the ankle back, hip flexion the knee
    forward."""
    import subprocess
    import sys

    if subprocess.run([sys.executable, "-c", "import opensim"], capture_output=True).returncode:
        pytest.skip("the opensim package is not installed")
    out = subprocess.run([sys.executable, "-c", OPENSIM_CHECK, str(write_osim(tmp_path / "m.osim", BODY))],
                         capture_output=True, text=True, check=True).stdout.split()
    assert float(out[-3]) == pytest.approx(62.0) and out[-2:] == ["True", "True"]


def test_the_ground_force_is_applied_at_the_centre_of_pressure(tmp_path):
    from formopt.io.export import write_grf

    force = [[[-50.0, 300.0], [20.0, 100.0]], [[0.0, 0.0], [0.0, 0.0]]]  # heel, forefoot; x, z
    points = [[[-0.05, 0.0], [0.15, 0.0]], [[0.0, 0.0], [0.2, 0.0]]]
    lines = write_grf(tmp_path / "grf.sto", [0.0, 0.01], force, points).read_text().splitlines()
    header = lines[6].split("\t")
    row = dict(zip(header, map(float, lines[7].split("\t"))))
    assert row["r_ground_force_vx"] == -30.0 and row["r_ground_force_vy"] == 400.0
    assert row["r_ground_force_px"] == pytest.approx(0.75 * -0.05 + 0.25 * 0.15)  # by the normal force
    assert dict(zip(header, map(float, lines[8].split("\t"))))["r_ground_force_px"] == 0.0  # none: the heel
